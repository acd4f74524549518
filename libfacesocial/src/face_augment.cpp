#include "facesocial/face_augment.hpp"

#include <random>

#include <opencv2/imgproc.hpp>

#include "checks.hpp"

namespace facesocial {

void AugmentParams::validate() const {
    auto check = [](const char* field, double v, double max) {
        if (!(v >= 0 && v <= max))
            detail::fail("AugmentParams", std::string(field) + " in [0, " + std::to_string(max) + "]", std::to_string(v));
    };
    check("max_rotation_deg", max_rotation_deg, 45);
    check("max_shift", max_shift, 0.5);
    check("max_scale", max_scale, 0.5);
    check("max_gain", max_gain, 0.9);
    check("max_bias", max_bias, 0.5);
}

std::vector<cv::Mat> augment_faces(const std::vector<cv::Mat>& faces, std::size_t count, const AugmentParams& params,
                                   uint32_t seed) {
    params.validate();
    if (faces.empty()) detail::fail("augment_faces", "at least one face", "none");
    const int type = faces[0].type();
    const cv::Size size = faces[0].size();
    for (const cv::Mat& f : faces) {
        if (f.empty() || f.channels() != 1 || (f.depth() != CV_8U && f.depth() != CV_32F))
            detail::fail("augment_faces", "single-channel 8-bit or float faces", f.empty() ? "an empty image" : detail::type_name(f.type()));
        if (f.type() != type || f.size() != size)
            detail::fail("augment_faces", "faces of one type and size (" + detail::type_name(type) + " " + detail::size_string(size) + ")",
                         detail::type_name(f.type()) + " " + detail::size_string(f.size()));
    }
    std::vector<cv::Mat> out;
    out.reserve(count);
    for (std::size_t i = 0; i < std::min(count, faces.size()); ++i) out.push_back(faces[i].clone());
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    std::bernoulli_distribution flip(0.5);
    // Intensity range of the faces: 255 for 8-bit; the spread of the values for float faces.
    double lo = 0, hi = 255;
    if (faces[0].depth() == CV_32F) cv::minMaxLoc(faces[0], &lo, &hi);
    const double range = std::max(hi - lo, 1e-6);
    for (std::size_t i = faces.size(); i < count; ++i) {
        const cv::Mat& src = faces[i % faces.size()];
        const cv::Point2f centre(0.5f * float(size.width - 1), 0.5f * float(size.height - 1));
        cv::Mat m = cv::getRotationMatrix2D(centre, params.max_rotation_deg * u(rng), 1.0 + params.max_scale * u(rng));
        m.at<double>(0, 2) += params.max_shift * size.width * u(rng);
        m.at<double>(1, 2) += params.max_shift * size.height * u(rng);
        cv::Mat warped;
        cv::warpAffine(src, warped, m, size, cv::INTER_LINEAR, cv::BORDER_REFLECT_101);
        if (params.mirror && flip(rng)) cv::flip(warped, warped, 1);
        const double gain = 1.0 + params.max_gain * u(rng), bias = params.max_bias * range * u(rng);
        cv::Mat varied;
        warped.convertTo(varied, type, gain, bias + (1.0 - gain) * (faces[0].depth() == CV_32F ? 0.0 : 127.5));
        out.push_back(varied);
    }
    return out;
}

}  // namespace facesocial
