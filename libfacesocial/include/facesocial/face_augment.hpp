// Small, realistic variations of face images (rotation, shift, scale, mirror, contrast and
// brightness) to grow a person's training set from few real images: for training-set size
// studies (paper Fig. 4) and for persons with few photos.
#pragma once

#include <cstdint>
#include <vector>

#include <opencv2/core.hpp>

namespace facesocial {

/// Ranges of the random variations; each is drawn uniformly in [-max, +max].
struct AugmentParams {
    double max_rotation_deg = 6.0;  ///< in-plane head roll
    double max_shift = 0.04;        ///< translation as a share of the image width / height
    double max_scale = 0.06;        ///< relative zoom
    bool mirror = true;             ///< flip left-right with probability 1/2
    double max_gain = 0.15;         ///< relative contrast change
    double max_bias = 0.10;         ///< brightness change as a share of the intensity range

    /// Throws std::invalid_argument naming the first invalid field.
    void validate() const;
};

/// Returns `count` faces: the originals first (in order, up to `count`), then variations of
/// them, cycling through the originals. Same type and size as the inputs (single-channel 8-bit
/// or float, all of one size). Deterministic for a given seed. Throws std::invalid_argument for
/// an empty input or mixed types / sizes.
std::vector<cv::Mat> augment_faces(const std::vector<cv::Mat>& faces, std::size_t count,
                                   const AugmentParams& params = {}, uint32_t seed = 0);

}  // namespace facesocial
