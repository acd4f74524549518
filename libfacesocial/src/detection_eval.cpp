#include "facesocial/detection_eval.hpp"

#include <algorithm>
#include <tuple>

namespace facesocial {

DetectionCounts& DetectionCounts::operator+=(const DetectionCounts& o) {
    true_positives += o.true_positives;
    false_positives += o.false_positives;
    false_negatives += o.false_negatives;
    return *this;
}

double DetectionCounts::recall() const {
    const int truth = true_positives + false_negatives;
    return truth > 0 ? double(true_positives) / truth : 0.0;
}

double DetectionCounts::precision() const {
    const int found = true_positives + false_positives;
    return found > 0 ? double(true_positives) / found : 1.0;
}

DetectionCounts match_detections(const std::vector<cv::Rect>& truth, const std::vector<Detection>& detections,
                                 double min_iou) {
    std::vector<std::tuple<double, std::size_t, std::size_t>> pairs;
    for (std::size_t t = 0; t < truth.size(); ++t)
        for (std::size_t d = 0; d < detections.size(); ++d) {
            const double o = iou(truth[t], detections[d].box);
            if (o >= min_iou) pairs.emplace_back(o, t, d);
        }
    std::sort(pairs.begin(), pairs.end(), [](const auto& a, const auto& b) { return std::get<0>(a) > std::get<0>(b); });
    std::vector<bool> truth_used(truth.size(), false), det_used(detections.size(), false);
    DetectionCounts c;
    for (const auto& [o, t, d] : pairs) {
        if (truth_used[t] || det_used[d]) continue;
        truth_used[t] = det_used[d] = true;
        ++c.true_positives;
    }
    c.false_negatives = int(truth.size()) - c.true_positives;
    c.false_positives = int(detections.size()) - c.true_positives;
    return c;
}

}  // namespace facesocial
