// Private helpers that turn caller mistakes into std::invalid_argument with a useful message.
#pragma once

#include <sstream>
#include <stdexcept>
#include <string>

#include <opencv2/core.hpp>

namespace facesocial::detail {

/// "CV_8UC3", "CV_16UC1", ...
inline std::string type_name(int type) { return cv::typeToString(type); }

inline std::string size_string(const cv::Size& s) {
    return std::to_string(s.width) + "x" + std::to_string(s.height);
}

inline std::string rect_string(const cv::Rect& r) {
    std::ostringstream os;
    os << "(x=" << r.x << ", y=" << r.y << ", w=" << r.width << ", h=" << r.height << ")";
    return os.str();
}

[[noreturn]] inline void fail(const char* function, const std::string& expected,
                              const std::string& got) {
    throw std::invalid_argument(std::string(function) + ": expected " + expected + ", got " + got);
}

/// Requires a non-empty 8-bit image with 1 or 3 channels (grey or BGR).
inline void require_8bit_grey_or_bgr(const cv::Mat& image, const char* function) {
    if (image.empty()) fail(function, "a non-empty 8-bit 1- or 3-channel image", "an empty image");
    if (image.dims != 2) fail(function, "a 2-D image", std::to_string(image.dims) + "-D array");
    if (image.depth() != CV_8U || (image.channels() != 1 && image.channels() != 3))
        fail(function, "an 8-bit 1- or 3-channel image", type_name(image.type()));
}

/// Requires a non-empty 8-bit 3-channel (BGR) image.
inline void require_8bit_bgr(const cv::Mat& image, const char* function) {
    if (image.empty()) fail(function, "a non-empty 8-bit 3-channel BGR image", "an empty image");
    if (image.dims != 2) fail(function, "a 2-D image", std::to_string(image.dims) + "-D array");
    if (image.type() != CV_8UC3) fail(function, "an 8-bit 3-channel BGR image", type_name(image.type()));
}

/// Requires a non-empty box wholly inside an image of size `size`.
inline void require_box_inside(const cv::Rect& box, const cv::Size& size, const char* function) {
    if (box.width <= 0 || box.height <= 0) fail(function, "a non-empty box", rect_string(box));
    const cv::Rect image_rect(0, 0, size.width, size.height);
    if ((box & image_rect) != box)
        fail(function, "a box inside the " + size_string(size) + " image",
             rect_string(box) + ((box & image_rect).area() == 0 ? " (wholly outside)"
                                                                : " (partly outside)"));
}

}  // namespace facesocial::detail
