// The vision front end of one frame (paper III.C.2): detect (frontal, optionally profile) ->
// skin filter -> elliptical normalisation of every surviving face.
#pragma once

#include <memory>
#include <vector>

#include <opencv2/core.hpp>

#include "facesocial/detection.hpp"
#include "facesocial/face_detector.hpp"
#include "facesocial/face_normalizer.hpp"
#include "facesocial/skin_filter.hpp"

namespace facesocial {

/// Parameters of the front end.
struct FrontEndParams {
    CascadeDetectorParams frontal;  ///< the frontal detector
    bool use_profile = false;       ///< also run the profile detector (both sides)
    CascadeDetectorParams profile = profile_cascade_params();  ///< the profile detector
    MergeParams merge;              ///< merging of frontal and profile detections
    bool use_skin_filter = true;    ///< drop candidates with too little skin colour
    SkinFilterParams skin;          ///< the skin rule and threshold
    bool normalize = true;          ///< produce normalised faces for the classifiers
    NormalizerParams normalizer;    ///< the normalised face

    /// Throws std::invalid_argument naming the first invalid field.
    void validate() const;
};

/// One face that passed the front end.
struct FrontEndFace {
    Detection detection;
    double skin_fraction = -1;  ///< -1 when the skin filter did not run (off, or grey image)
    NormalizedFace face;        ///< empty when params.normalize is false
};

/// What the front end found in one frame.
struct FrontEndResult {
    std::vector<FrontEndFace> faces;      ///< surviving faces, by decreasing confidence
    std::vector<Detection> rejected;      ///< candidates the skin filter dropped
    std::vector<double> rejected_skin;    ///< their skin fractions
    bool skin_filter_skipped = false;     ///< grey image: the filter was skipped
};

/// Runs detect -> skin filter -> normalise on frames. Safe to call from several threads.
class FrontEnd {
public:
    /// Throws std::invalid_argument for invalid params and FileError for missing cascades.
    explicit FrontEnd(const FrontEndParams& params = {});

    const FrontEndParams& params() const { return params_; }
    const FaceDetector& detector() const { return *detector_; }

    /// Requires an 8-bit grey or BGR image (std::invalid_argument otherwise).
    FrontEndResult process(const cv::Mat& image) const;

private:
    FrontEndParams params_;
    std::unique_ptr<FaceDetector> detector_;
    SkinFilter skin_;
    FaceNormalizer normalizer_;
};

}  // namespace facesocial
