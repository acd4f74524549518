// facesocial detect: the front end over images, printed and optionally written to a folder.
#include <filesystem>
#include <iostream>

#include <opencv2/imgproc.hpp>

#include "cli.hpp"
#include "commands.hpp"
#include "facesocial/datasets.hpp"
#include "facesocial/error.hpp"
#include "facesocial/front_end.hpp"
#include "facesocial/image_io.hpp"

namespace facesocial::cli {

namespace fs = std::filesystem;

std::vector<fs::path> expand_inputs(const std::vector<std::string>& inputs) {
    std::vector<fs::path> files;
    for (const std::string& in : inputs) {
        std::error_code ec;
        if (fs::is_directory(in, ec)) {
            const auto images = list_images(in);
            if (images.empty()) throw FileError(in, "folder holds no image files");
            files.insert(files.end(), images.begin(), images.end());
        } else {
            files.emplace_back(in);  // load_image reports a missing or non-image file
        }
    }
    return files;
}

fs::path data_dir(const std::string& option_value) {
    if (option_value.empty()) return data_root();
    std::error_code ec;
    if (!fs::is_directory(option_value, ec)) throw FileError(option_value, "(--data) is not a directory");
    return option_value;
}

namespace {

cv::Mat annotate(const cv::Mat& image, const FrontEndResult& r) {
    cv::Mat out;
    if (image.channels() == 1)
        cv::cvtColor(image, out, cv::COLOR_GRAY2BGR);
    else
        out = image.clone();
    for (std::size_t i = 0; i < r.rejected.size(); ++i) {
        cv::rectangle(out, r.rejected[i].box, cv::Scalar(0, 0, 255), 1);
        cv::putText(out, "skin " + std::to_string(int(r.rejected_skin[i] * 100)) + "%",
                    r.rejected[i].box.tl() + cv::Point(0, -3), cv::FONT_HERSHEY_SIMPLEX, 0.35, cv::Scalar(0, 0, 255));
    }
    for (std::size_t i = 0; i < r.faces.size(); ++i) {
        const Detection& d = r.faces[i].detection;
        const cv::Scalar colour = is_profile(d.pose) ? cv::Scalar(255, 128, 0) : cv::Scalar(0, 220, 0);
        cv::rectangle(out, d.box, colour, 2);
        cv::putText(out, std::to_string(i) + " " + to_string(d.pose), d.box.tl() + cv::Point(0, -3),
                    cv::FONT_HERSHEY_SIMPLEX, 0.4, colour);
    }
    return out;
}

JsonObject box_json(const cv::Rect& b) {
    JsonObject o;
    o.add("x", b.x).add("y", b.y).add("w", b.width).add("h", b.height);
    return o;
}

}  // namespace

int cmd_detect(const std::vector<std::string>& argv) {
    const Args args(argv, {"--out"}, {"--profile", "--no-skin-filter", "--json"});
    if (args.positional().empty()) throw UsageError("detect: expected IMAGE or FOLDER");
    FrontEndParams params;
    params.use_profile = args.flag("--profile");
    params.use_skin_filter = !args.flag("--no-skin-filter");
    const FrontEnd front_end(params);

    const fs::path out_dir = args.get("--out");
    if (!out_dir.empty()) {
        std::error_code ec;
        fs::create_directories(out_dir, ec);
        if (ec) throw FileError(out_dir.string(), "cannot create output folder: " + ec.message());
    }
    const bool json = args.flag("--json");
    int total_faces = 0;
    const auto files = expand_inputs(args.positional());
    for (const fs::path& file : files) {
        const cv::Mat image = load_image(file, ImageColor::Any);
        const FrontEndResult r = front_end.process(image);
        total_faces += int(r.faces.size());
        if (json) {
            std::vector<JsonObject> faces, rejected;
            for (const auto& f : r.faces) {
                JsonObject o;
                o.add("box", box_json(f.detection.box)).add("pose", to_string(f.detection.pose));
                o.add("confidence", double(f.detection.confidence)).add("skin", f.skin_fraction);
                faces.push_back(o);
            }
            for (std::size_t i = 0; i < r.rejected.size(); ++i) {
                JsonObject o;
                o.add("box", box_json(r.rejected[i].box)).add("pose", to_string(r.rejected[i].pose));
                o.add("skin", r.rejected_skin[i]);
                rejected.push_back(o);
            }
            JsonObject line;
            line.add("file", file.string()).add("width", image.cols).add("height", image.rows);
            line.add("faces", faces).add("rejected_by_skin", rejected).add("skin_filter_skipped", r.skin_filter_skipped);
            std::cout << line.str() << "\n";
        } else {
            std::cout << file.string() << ": " << r.faces.size() << " face(s)";
            if (!r.rejected.empty()) std::cout << ", " << r.rejected.size() << " rejected by the skin filter";
            if (r.skin_filter_skipped) std::cout << " (grey image: skin filter skipped)";
            std::cout << "\n";
            for (const auto& f : r.faces) {
                const cv::Rect& b = f.detection.box;
                std::cout << "  " << to_string(f.detection.pose) << " at " << b.x << "," << b.y << " " << b.width << "x"
                          << b.height << " confidence " << f.detection.confidence;
                if (f.skin_fraction >= 0) std::cout << " skin " << int(f.skin_fraction * 100 + 0.5) << "%";
                std::cout << "\n";
            }
        }
        if (!out_dir.empty()) {
            const std::string stem = file.stem().string();
            save_image(out_dir / (stem + "_annotated.jpg"), annotate(image, r));
            for (std::size_t i = 0; i < r.faces.size(); ++i)
                save_image(out_dir / (stem + "_face" + std::to_string(i) + ".png"), FaceNormalizer::to_8bit(r.faces[i].face));
        }
    }
    if (!json) std::cout << files.size() << " image(s), " << total_faces << " face(s)\n";
    return 0;
}

}  // namespace facesocial::cli
