// Scoring detections against ground-truth boxes.
#pragma once

#include <vector>

#include <opencv2/core.hpp>

#include "facesocial/detection.hpp"

namespace facesocial {

/// Counts of one matching.
struct DetectionCounts {
    int true_positives = 0;   ///< detections matched one-to-one to a truth box
    int false_positives = 0;  ///< detections matched to no truth box
    int false_negatives = 0;  ///< truth boxes left unmatched

    DetectionCounts& operator+=(const DetectionCounts& o);
    /// true_positives / (true_positives + false_negatives); 0 when there is no truth box.
    double recall() const;
    /// true_positives / (true_positives + false_positives); 1 when there is no detection.
    double precision() const;
};

/// Greedy one-to-one matching by decreasing IoU: a detection and a truth box match when their
/// IoU is at least `min_iou` and neither is matched yet.
DetectionCounts match_detections(const std::vector<cv::Rect>& truth,
                                 const std::vector<Detection>& detections, double min_iou = 0.5);

}  // namespace facesocial
