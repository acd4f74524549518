#include "facesocial/decision.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>

#include "checks.hpp"

namespace facesocial {

void UnknownRule::validate() const {
    if (!(min_variance >= 0))
        detail::fail("UnknownRule", "min_variance >= 0", std::to_string(min_variance));
    if (!(min_margin >= 0)) detail::fail("UnknownRule", "min_margin >= 0", std::to_string(min_margin));
    if (std::isnan(min_score)) detail::fail("UnknownRule", "min_score a number or -infinity", "NaN");
}

double score_variance(const std::vector<double>& scores) {
    if (scores.size() < 2) return 0.0;
    const double mean = std::accumulate(scores.begin(), scores.end(), 0.0) / double(scores.size());
    double ss = 0;
    for (double s : scores) ss += (s - mean) * (s - mean);
    return ss / double(scores.size());
}

std::vector<Candidate> rank_candidates(const std::vector<std::string>& names, const std::vector<double>& scores,
                                       std::size_t top_k) {
    if (names.size() != scores.size())
        detail::fail("rank_candidates", "one score per name (" + std::to_string(names.size()) + ")",
                     std::to_string(scores.size()) + " scores");
    std::vector<Candidate> out(names.size());
    for (std::size_t i = 0; i < names.size(); ++i) {
        if (std::isnan(scores[i])) detail::fail("rank_candidates", "scores that are numbers", "NaN for " + names[i]);
        out[i] = {names[i], scores[i]};
    }
    const auto better = [](const Candidate& a, const Candidate& b) {
        return a.score != b.score ? a.score > b.score : a.name < b.name;
    };
    if (top_k == 0 || top_k >= out.size()) {
        std::sort(out.begin(), out.end(), better);
    } else {
        std::partial_sort(out.begin(), out.begin() + std::ptrdiff_t(top_k), out.end(), better);
        out.resize(top_k);
    }
    return out;
}

Decision decide(const std::vector<std::string>& names, const std::vector<double>& scores, const UnknownRule& rule) {
    rule.validate();
    Decision d;
    d.ranked = rank_candidates(names, scores);
    d.variance = score_variance(scores);
    if (d.ranked.empty()) return d;
    d.score = d.ranked.front().score;
    d.margin = d.ranked.size() > 1 ? d.score - d.ranked[1].score : std::numeric_limits<double>::infinity();
    const bool flat = rule.min_variance > 0 && d.variance < rule.min_variance;
    const bool weak = d.score < rule.min_score;
    const bool close = d.margin < rule.min_margin;
    d.known = !flat && !weak && !close;
    if (d.known) d.name = d.ranked.front().name;
    return d;
}

}  // namespace facesocial
