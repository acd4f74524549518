#include "facesocial/face_normalizer.hpp"

#include <cmath>
#include <stdexcept>

#include <opencv2/imgproc.hpp>

#include "checks.hpp"

namespace facesocial {

NormalizerParams NormalizerParams::cropped() {
    NormalizerParams p;
    p.elliptical_mask = false;
    return p;
}

void NormalizerParams::validate() const {
    auto bad = [](const std::string& field, const std::string& expected, const std::string& got) {
        throw std::invalid_argument("NormalizerParams: expected " + field + " " + expected + ", got " + got);
    };
    if (output_size.width < 16 || output_size.height < 16 || output_size.width > 1024 || output_size.height > 1024)
        bad("output_size", "between 16x16 and 1024x1024", detail::size_string(output_size));
    if (!(ellipse_width > 0.1 && ellipse_width <= 1.5)) bad("ellipse_width", "in (0.1, 1.5]", std::to_string(ellipse_width));
    if (!(ellipse_height > 0.1 && ellipse_height <= 1.5))
        bad("ellipse_height", "in (0.1, 1.5]", std::to_string(ellipse_height));
    if (!(vertical_margin >= 0.0 && vertical_margin <= 1.0))
        bad("vertical_margin", "in [0, 1]", std::to_string(vertical_margin));
}

FaceNormalizer::FaceNormalizer(const NormalizerParams& params) : params_(params) {
    params_.validate();
    const cv::Size s = params_.output_size;
    mask_ = cv::Mat::zeros(s, CV_8UC1);
    if (!params_.elliptical_mask) {
        mask_.setTo(255);
        return;
    }
    const double a = s.width / 2.0 * params_.ellipse_width, b = s.height / 2.0 * params_.ellipse_height;
    const double cx = s.width / 2.0, cy = s.height / 2.0;
    for (int y = 0; y < s.height; ++y) {
        uchar* m = mask_.ptr<uchar>(y);
        const double dy = (y + 0.5 - cy) / b;
        for (int x = 0; x < s.width; ++x) {
            const double dx = (x + 0.5 - cx) / a;
            m[x] = dx * dx + dy * dy <= 1.0 ? 255 : 0;
        }
    }
}

NormalizedFace FaceNormalizer::normalize(const cv::Mat& image) const {
    detail::require_8bit_grey_or_bgr(image, "FaceNormalizer::normalize");
    return normalize(image, cv::Rect(0, 0, image.cols, image.rows));
}

NormalizedFace FaceNormalizer::normalize(const cv::Mat& image, const cv::Rect& box) const {
    detail::require_8bit_grey_or_bgr(image, "FaceNormalizer::normalize");
    detail::require_box_inside(box, image.size(), "FaceNormalizer::normalize");
    if (box.width < 8 || box.height < 8)
        detail::fail("FaceNormalizer::normalize", "a face box of at least 8x8 pixels", detail::rect_string(box));

    // Crop (with the vertical margin, replicating the border where it leaves the image).
    cv::Mat crop;
    const int margin = int(std::lround(box.height * params_.vertical_margin));
    const cv::Rect grown(box.x, box.y - margin, box.width, box.height + 2 * margin);
    const cv::Rect inside = grown & cv::Rect(0, 0, image.cols, image.rows);
    cv::copyMakeBorder(image(inside), crop, inside.y - grown.y, grown.br().y - inside.br().y, 0, 0,
                       cv::BORDER_REPLICATE);

    cv::Mat grey;
    if (crop.channels() == 3)
        cv::cvtColor(crop, grey, cv::COLOR_BGR2GRAY);
    else
        grey = crop;
    cv::Mat resized;
    const bool shrinking = grey.cols > params_.output_size.width;
    cv::resize(grey, resized, params_.output_size, 0, 0, shrinking ? cv::INTER_AREA : cv::INTER_LINEAR);

    cv::Mat equalized;
    if (params_.equalize) {
        // Equalise with the histogram of the ellipse pixels only, so background does not drive it.
        int hist[256] = {0};
        int count = 0;
        for (int y = 0; y < resized.rows; ++y) {
            const uchar* p = resized.ptr<uchar>(y);
            const uchar* m = mask_.ptr<uchar>(y);
            for (int x = 0; x < resized.cols; ++x)
                if (m[x]) ++hist[p[x]], ++count;
        }
        uchar lut[256];
        int cumulative = 0;
        for (int v = 0; v < 256; ++v) {
            cumulative += hist[v];
            lut[v] = cv::saturate_cast<uchar>(std::lround(255.0 * cumulative / std::max(count, 1)));
        }
        cv::LUT(resized, cv::Mat(1, 256, CV_8U, lut), equalized);
    } else {
        equalized = resized;
    }

    NormalizedFace face;
    face.mask = mask_.clone();
    equalized.convertTo(face.pixels, CV_32F);
    cv::Scalar mean, stddev;
    cv::meanStdDev(face.pixels, mean, stddev, mask_);
    if (stddev[0] < 1e-3) {
        face.pixels.setTo(0.f);  // a flat face carries no information: all zeros, never NaN
    } else {
        face.pixels = (face.pixels - mean[0]) / stddev[0];
        face.pixels.setTo(0.f, mask_ == 0);
    }
    return face;
}

cv::Mat FaceNormalizer::to_8bit(const NormalizedFace& face) {
    if (face.pixels.empty() || face.pixels.type() != CV_32FC1)
        detail::fail("FaceNormalizer::to_8bit", "a CV_32FC1 normalised face",
                     face.pixels.empty() ? "an empty face" : detail::type_name(face.pixels.type()));
    cv::Mat out;
    // +-3 standard deviations onto 0..255.
    face.pixels.convertTo(out, CV_8U, 255.0 / 6.0, 127.5);
    if (!face.mask.empty()) out.setTo(0, face.mask == 0);
    return out;
}

}  // namespace facesocial
