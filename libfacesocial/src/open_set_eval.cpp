#include "facesocial/open_set_eval.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "checks.hpp"

namespace facesocial {

double acceptance_rate(const std::vector<double>& stats, double threshold) {
    if (stats.empty()) return 0.0;
    const auto n = std::count_if(stats.begin(), stats.end(), [&](double s) { return s >= threshold; });
    return double(n) / double(stats.size());
}

double threshold_for_acceptance(const std::vector<double>& known, double share) {
    if (known.empty()) detail::fail("threshold_for_acceptance", "at least one known statistic", "none");
    if (!(share > 0 && share <= 1)) detail::fail("threshold_for_acceptance", "a share in (0, 1]", std::to_string(share));
    std::vector<double> sorted = known;
    std::sort(sorted.begin(), sorted.end(), std::greater<>());
    // Accepting the k best needs the threshold at the k-th best value.
    const std::size_t k = std::size_t(std::ceil(share * double(sorted.size()) - 1e-9));
    return sorted[std::clamp<std::size_t>(k, 1, sorted.size()) - 1];
}

EqualErrorRate equal_error_rate(const std::vector<double>& known, const std::vector<double>& unknown) {
    if (known.empty() || unknown.empty())
        detail::fail("equal_error_rate", "known and unknown statistics", std::to_string(known.size()) + " known, " +
                                                                             std::to_string(unknown.size()) + " unknown");
    std::vector<double> candidates = known;
    candidates.insert(candidates.end(), unknown.begin(), unknown.end());
    std::sort(candidates.begin(), candidates.end());
    candidates.erase(std::unique(candidates.begin(), candidates.end()), candidates.end());
    candidates.push_back(std::nextafter(candidates.back(), INFINITY));  // accept nobody
    EqualErrorRate best{candidates.front(), 1.0};
    double best_gap = INFINITY;
    for (double t : candidates) {
        const double frr = 1.0 - acceptance_rate(known, t);
        const double far = acceptance_rate(unknown, t);
        if (std::abs(frr - far) < best_gap) {
            best_gap = std::abs(frr - far);
            best = {t, 0.5 * (frr + far)};
        }
    }
    return best;
}

}  // namespace facesocial
