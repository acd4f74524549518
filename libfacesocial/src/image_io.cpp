#include "facesocial/image_io.hpp"

#include <algorithm>
#include <cctype>
#include <fstream>
#include <system_error>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "facesocial/datasets.hpp"
#include "facesocial/error.hpp"

namespace facesocial {

namespace fs = std::filesystem;

cv::Mat load_image(const fs::path& path, ImageColor color) {
    std::error_code ec;
    if (!fs::exists(path, ec)) throw FileError(path.string(), "no such file");
    if (fs::is_directory(path, ec)) throw FileError(path.string(), "is a directory, expected an image file");
    std::ifstream probe(path, std::ios::binary);
    if (!probe) throw FileError(path.string(), "cannot be opened for reading");
    probe.close();

    int flags = cv::IMREAD_COLOR;
    if (color == ImageColor::Grey) flags = cv::IMREAD_GRAYSCALE;
    if (color == ImageColor::Any) flags = cv::IMREAD_ANYCOLOR;
    cv::Mat image;
    try {
        image = cv::imread(path.string(), flags);
    } catch (const cv::Exception& e) {
        throw FileError(path.string(), std::string("cannot be decoded as an image: ") + e.what());
    }
    if (image.empty())
        throw FileError(path.string(), "is not an image OpenCV can decode (expected JPEG, PNG, PNM, BMP, TIFF or WebP)");
    if (image.depth() != CV_8U) {  // IMREAD_ANYCOLOR keeps 8 bits, but be explicit
        cv::Mat converted;
        image.convertTo(converted, CV_8U);
        image = converted;
    }
    if (color == ImageColor::Any && image.channels() == 4) cv::cvtColor(image, image, cv::COLOR_BGRA2BGR);
    return image;
}

bool has_image_extension(const fs::path& path) {
    std::string ext = path.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
    static const char* const kExtensions[] = {".jpg", ".jpeg", ".png", ".pgm", ".ppm", ".pnm",
                                              ".bmp", ".tif", ".tiff", ".webp"};
    return std::any_of(std::begin(kExtensions), std::end(kExtensions),
                       [&](const char* e) { return ext == e; });
}

std::vector<fs::path> list_images(const fs::path& folder) {
    std::error_code ec;
    if (!fs::is_directory(folder, ec)) throw FileError(folder.string(), "is not a directory");
    std::vector<fs::path> files;
    for (const auto& entry : fs::directory_iterator(folder, ec)) {
        if (entry.is_regular_file() && has_image_extension(entry.path())) files.push_back(entry.path());
    }
    if (ec) throw FileError(folder.string(), "cannot be listed: " + ec.message());
    std::sort(files.begin(), files.end(), [](const fs::path& a, const fs::path& b) {
        return natural_less(a.filename().string(), b.filename().string());
    });
    return files;
}

void save_image(const fs::path& path, const cv::Mat& image) {
    bool ok = false;
    try {
        ok = cv::imwrite(path.string(), image);
    } catch (const cv::Exception& e) {
        throw FileError(path.string(), std::string("cannot be written: ") + e.what());
    }
    if (!ok) throw FileError(path.string(), "cannot be written (unknown extension or unwritable folder)");
}

}  // namespace facesocial
