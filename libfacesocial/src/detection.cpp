#include "facesocial/detection.hpp"

#include <algorithm>
#include <stdexcept>

namespace facesocial {

std::string to_string(FacePose pose) {
    switch (pose) {
        case FacePose::Frontal: return "frontal";
        case FacePose::ProfileLeft: return "profile-left";
        case FacePose::ProfileRight: return "profile-right";
    }
    return "unknown";
}

double iou(const cv::Rect& a, const cv::Rect& b) {
    const double inter = (a & b).area();
    const double uni = double(a.area()) + double(b.area()) - inter;
    return uni > 0 ? inter / uni : 0.0;
}

double containment(const cv::Rect& a, const cv::Rect& b) {
    const double smaller = std::min(a.area(), b.area());
    return smaller > 0 ? (a & b).area() / smaller : 0.0;
}

void MergeParams::validate() const {
    if (!(iou_threshold > 0 && iou_threshold <= 1))
        throw std::invalid_argument("MergeParams: expected iou_threshold in (0, 1], got " + std::to_string(iou_threshold));
    if (!(containment_threshold > 0 && containment_threshold <= 1))
        throw std::invalid_argument("MergeParams: expected containment_threshold in (0, 1], got " +
                                    std::to_string(containment_threshold));
}

std::vector<Detection> merge_detections(std::vector<Detection> detections, const MergeParams& params) {
    params.validate();
    std::stable_sort(detections.begin(), detections.end(), [&](const Detection& a, const Detection& b) {
        if (params.prefer_frontal && is_profile(a.pose) != is_profile(b.pose)) return !is_profile(a.pose);
        return a.confidence > b.confidence;
    });
    std::vector<Detection> kept;
    for (const Detection& d : detections) {
        const bool overlaps = std::any_of(kept.begin(), kept.end(), [&](const Detection& k) {
            return iou(k.box, d.box) >= params.iou_threshold ||
                   containment(k.box, d.box) >= params.containment_threshold;
        });
        if (!overlaps) kept.push_back(d);
    }
    std::stable_sort(kept.begin(), kept.end(),
                     [](const Detection& a, const Detection& b) { return a.confidence > b.confidence; });
    return kept;
}

}  // namespace facesocial
