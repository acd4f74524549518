// Threshold analysis for open-set recognition: how a statistic of the score vector (the winning
// score, the variance of the scores, ...) separates faces of enrolled people from strangers.
// A face is accepted when its statistic is >= the threshold.
#pragma once

#include <vector>

namespace facesocial {

/// The share of `stats` that are >= `threshold` (0 for an empty list).
double acceptance_rate(const std::vector<double>& stats, double threshold);

/// The highest threshold that accepts at least `share` (in (0, 1]) of `known`. Throws
/// std::invalid_argument for an empty list or a share outside (0, 1].
double threshold_for_acceptance(const std::vector<double>& known, double share);

/// The operating point where the false-reject rate of `known` equals the false-accept rate of
/// `unknown` (the closest pair over all candidate thresholds; `rate` is their mean).
struct EqualErrorRate {
    double threshold = 0;
    double rate = 0;
};
/// Throws std::invalid_argument when either list is empty.
EqualErrorRate equal_error_rate(const std::vector<double>& known, const std::vector<double>& unknown);

}  // namespace facesocial
