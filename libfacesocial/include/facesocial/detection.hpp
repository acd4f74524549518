// A detected face and the geometry used to compare and merge detections.
#pragma once

#include <string>
#include <vector>

#include <opencv2/core.hpp>

namespace facesocial {

/// Head pose class of a detection, as told by the detector that found it.
enum class FacePose {
    Frontal,       ///< found by a frontal-face model
    ProfileLeft,   ///< profile, the face looks towards the left edge of the image
    ProfileRight,  ///< profile, the face looks towards the right edge of the image
};

/// "frontal", "profile-left" or "profile-right".
std::string to_string(FacePose pose);

/// True for ProfileLeft and ProfileRight.
inline bool is_profile(FacePose pose) { return pose != FacePose::Frontal; }

/// One face candidate in image coordinates.
struct Detection {
    cv::Rect box;                        ///< pixel box, inside the image it was found in
    FacePose pose = FacePose::Frontal;  ///< pose class of the detector that found it
    float confidence = 0.f;             ///< in (0, 1); grows with the evidence behind the box
};

/// Intersection over union of two boxes (0 when either is empty).
double iou(const cv::Rect& a, const cv::Rect& b);

/// Share of the smaller box covered by the intersection (1 when one box holds the other).
double containment(const cv::Rect& a, const cv::Rect& b);

/// How overlapping detections from one or several detectors are merged.
struct MergeParams {
    double iou_threshold = 0.3;          ///< boxes overlapping at least this much are one face
    double containment_threshold = 0.7;  ///< ... or when this share of the smaller box is covered
    bool prefer_frontal = true;          ///< a frontal box wins over a profile box it overlaps

    /// Throws std::invalid_argument when a threshold is outside (0, 1].
    void validate() const;
};

/// Greedy non-maximum suppression: keeps the strongest detection of each overlapping group
/// (frontal ones first when prefer_frontal), drops the others. The result is sorted by
/// decreasing confidence.
std::vector<Detection> merge_detections(std::vector<Detection> detections,
                                        const MergeParams& params = {});

}  // namespace facesocial
