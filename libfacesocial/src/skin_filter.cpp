#include "facesocial/skin_filter.hpp"

#include <algorithm>
#include <cstdlib>
#include <stdexcept>

#include <opencv2/imgproc.hpp>

#include "checks.hpp"

namespace facesocial {

namespace {

inline bool peer_daylight(int r, int g, int b) {
    const int mx = std::max({r, g, b});
    const int mn = std::min({r, g, b});
    return r > 95 && g > 40 && b > 20 && mx - mn > 15 && std::abs(r - g) > 15 && r > g && r > b;
}

inline bool peer_flash(int r, int g, int b) {
    return r > 220 && g > 210 && b > 170 && std::abs(r - g) <= 15 && r > b && g > b;
}

inline bool is_skin(SkinRule rule, int r, int g, int b) {
    if (peer_daylight(r, g, b)) return true;
    return rule == SkinRule::PeerDaylightOrFlash && peer_flash(r, g, b);
}

}  // namespace

void SkinFilterParams::validate() const {
    if (!(min_skin_fraction >= 0.0 && min_skin_fraction <= 1.0))
        throw std::invalid_argument("SkinFilterParams: expected min_skin_fraction in [0, 1], got " +
                                    std::to_string(min_skin_fraction));
    if (grey_tolerance < 0 || grey_tolerance > 255)
        throw std::invalid_argument("SkinFilterParams: expected grey_tolerance in [0, 255], got " +
                                    std::to_string(grey_tolerance));
}

SkinFilter::SkinFilter(const SkinFilterParams& params) : params_(params) { params_.validate(); }

cv::Mat SkinFilter::skin_mask(const cv::Mat& bgr) const {
    detail::require_8bit_bgr(bgr, "SkinFilter::skin_mask");
    cv::Mat mask(bgr.size(), CV_8UC1);
    for (int y = 0; y < bgr.rows; ++y) {
        const uchar* p = bgr.ptr<uchar>(y);
        uchar* m = mask.ptr<uchar>(y);
        for (int x = 0; x < bgr.cols; ++x, p += 3) m[x] = is_skin(params_.rule, p[2], p[1], p[0]) ? 255 : 0;
    }
    return mask;
}

double SkinFilter::skin_fraction(const cv::Mat& bgr, const cv::Rect& box) const {
    detail::require_8bit_bgr(bgr, "SkinFilter::skin_fraction");
    detail::require_box_inside(box, bgr.size(), "SkinFilter::skin_fraction");
    const cv::Mat roi = bgr(box);
    // Ellipse inscribed in the box: ((x - cx) / a)^2 + ((y - cy) / b)^2 <= 1, pixel centres.
    const double a = box.width / 2.0, b = box.height / 2.0;
    long skin = 0, counted = 0;
    for (int y = 0; y < roi.rows; ++y) {
        const uchar* p = roi.ptr<uchar>(y);
        const double dy = (y + 0.5 - b) / b;
        int x0 = 0, x1 = roi.cols;
        if (params_.ellipse_only) {
            const double half = a * std::sqrt(std::max(0.0, 1.0 - dy * dy));
            x0 = std::clamp(int(std::ceil(a - half - 0.5)), 0, roi.cols);
            x1 = std::clamp(int(std::floor(a + half - 0.5)) + 1, x0, roi.cols);
        }
        for (int x = x0; x < x1; ++x) skin += is_skin(params_.rule, p[3 * x + 2], p[3 * x + 1], p[3 * x]);
        counted += x1 - x0;
    }
    return counted > 0 ? double(skin) / double(counted) : 0.0;
}

bool SkinFilter::is_grey(const cv::Mat& image) const {
    detail::require_8bit_grey_or_bgr(image, "SkinFilter::is_grey");
    if (image.channels() == 1) return true;
    const int tol = params_.grey_tolerance;
    for (int y = 0; y < image.rows; ++y) {
        const uchar* p = image.ptr<uchar>(y);
        for (int x = 0; x < image.cols; ++x, p += 3) {
            if (std::abs(p[0] - p[1]) > tol || std::abs(p[1] - p[2]) > tol || std::abs(p[0] - p[2]) > tol)
                return false;
        }
    }
    return true;
}

SkinFilterResult SkinFilter::filter(const cv::Mat& image, const std::vector<Detection>& candidates) const {
    detail::require_8bit_grey_or_bgr(image, "SkinFilter::filter");
    for (const Detection& d : candidates) detail::require_box_inside(d.box, image.size(), "SkinFilter::filter");
    SkinFilterResult result;
    if (is_grey(image)) {
        result.skipped = true;
        result.kept = candidates;
        result.kept_fraction.assign(candidates.size(), -1.0);
        return result;
    }
    for (const Detection& d : candidates) {
        const double f = skin_fraction(image, d.box);
        if (f >= params_.min_skin_fraction) {
            result.kept.push_back(d);
            result.kept_fraction.push_back(f);
        } else {
            result.rejected.push_back(d);
            result.rejected_fraction.push_back(f);
        }
    }
    return result;
}

}  // namespace facesocial
