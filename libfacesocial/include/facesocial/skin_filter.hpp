// Skin-colour filtering of face candidates (paper III.C.2): a per-pixel RGB inequality rule,
// the skin fraction of a candidate box, and the candidates under a threshold dropped.
#pragma once

#include <vector>

#include <opencv2/core.hpp>

#include "facesocial/detection.hpp"

namespace facesocial {

/// Published RGB skin rules.
enum class SkinRule {
    /// Peer, Kovac & Solina (2003), "Human skin colour clustering for face detection", skin
    /// under uniform daylight: R > 95, G > 40, B > 20, max(R,G,B) - min(R,G,B) > 15,
    /// |R - G| > 15, R > G, R > B.
    PeerDaylight,
    /// The same paper's daylight rule OR its flash / lateral-illumination rule:
    /// R > 220, G > 210, B > 170, |R - G| <= 15, R > B, G > B.
    PeerDaylightOrFlash,
};

/// Parameters of the skin filter.
struct SkinFilterParams {
    SkinRule rule = SkinRule::PeerDaylightOrFlash;  ///< per-pixel rule
    double min_skin_fraction = 0.20;  ///< candidates with less skin are dropped (paper: 20%)
    /// Only the pixels inside the ellipse inscribed in the box are counted (background in the
    /// box corners then does not dilute the fraction).
    bool ellipse_only = true;
    /// A BGR image whose channels never differ by more than this is treated as grey (grey
    /// photos stored as colour files): the filter is then skipped.
    int grey_tolerance = 2;

    /// Throws std::invalid_argument naming the first invalid field.
    void validate() const;
};

/// Outcome of filtering one frame's candidates.
struct SkinFilterResult {
    std::vector<Detection> kept;      ///< candidates that passed (all of them when skipped)
    std::vector<Detection> rejected;  ///< candidates dropped for too little skin
    std::vector<double> kept_fraction;      ///< skin fraction of each kept candidate (-1 if skipped)
    std::vector<double> rejected_fraction;  ///< skin fraction of each rejected candidate
    bool skipped = false;  ///< the image has no colour (grey), so nothing was filtered
};

/// Applies a SkinRule to images and candidate boxes. Stateless apart from its params;
/// safe to use from several threads.
class SkinFilter {
public:
    /// Throws std::invalid_argument when params are invalid.
    explicit SkinFilter(const SkinFilterParams& params = {});

    const SkinFilterParams& params() const { return params_; }

    /// Per-pixel skin mask (CV_8U, 255 = skin) of an 8-bit BGR image.
    /// Throws std::invalid_argument for any other image type.
    cv::Mat skin_mask(const cv::Mat& bgr) const;

    /// Share of skin pixels in `box` (inside its ellipse when ellipse_only), in [0, 1].
    /// Requires an 8-bit BGR image and a non-empty box inside it; std::invalid_argument otherwise.
    double skin_fraction(const cv::Mat& bgr, const cv::Rect& box) const;

    /// True when the image carries no colour: 1 channel, or 3 channels within grey_tolerance.
    bool is_grey(const cv::Mat& image) const;

    /// Keeps the candidates with at least min_skin_fraction skin. For a grey image the filter is
    /// skipped (result.skipped, every candidate kept). Requires an 8-bit 1- or 3-channel image
    /// and boxes inside it.
    SkinFilterResult filter(const cv::Mat& image, const std::vector<Detection>& candidates) const;

private:
    SkinFilterParams params_;
};

}  // namespace facesocial
