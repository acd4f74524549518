// From a score vector (one score per enrolled person) to ranked candidates and a hard decision,
// with the paper's "unknown" rule (section III.C.3): a face is unknown when the score vector is
// too flat (its variance is under a threshold: no person stands out) and/or the winning score is
// under a minimum. A third test, beyond the paper, looks at the margin between the winner and the
// runner-up, which separates strangers far better on ORL (docs/BENCHMARKS.md, eval unknown).
// Used on single-frame scores and on accumulated scores alike.
#pragma once

#include <limits>
#include <string>
#include <vector>

namespace facesocial {

/// Thresholds of the unknown rule. Both tests are off by default; a face is unknown when any
/// enabled test fires.
struct UnknownRule {
    /// Unknown when the population variance of the score vector is below this (0 = off).
    /// A bank of one person always has variance 0, so this test rejects everything there.
    double min_variance = 0.0;
    /// Unknown when the best score is below this (-infinity = off).
    double min_score = -std::numeric_limits<double>::infinity();
    /// Unknown when the winner beats the runner-up by less than this (0 = off). Never fires
    /// with a single enrolled person.
    double min_margin = 0.0;

    /// Throws std::invalid_argument for a negative or NaN min_variance or min_margin, or a NaN
    /// min_score.
    void validate() const;
};

/// One person's standing for a face.
struct Candidate {
    std::string name;
    double score = 0;
};

/// The outcome for one face.
struct Decision {
    bool known = false;              ///< false: no one enrolled, or the unknown rule fired
    std::string name;                ///< the winner when known, empty otherwise
    double score = 0;                ///< the best score (0 when nobody is enrolled)
    double variance = 0;             ///< population variance of the score vector
    double margin = 0;               ///< best minus second-best score (+infinity for one person)
    std::vector<Candidate> ranked;   ///< everyone, best first (ties by name), for second guesses
};

/// Population variance of the scores (0 for fewer than two).
double score_variance(const std::vector<double>& scores);

/// The `top_k` best candidates (0 = all), best first; ties broken by name so the order does not
/// depend on the order of people. Throws std::invalid_argument when the sizes differ or a score
/// is NaN.
std::vector<Candidate> rank_candidates(const std::vector<std::string>& names, const std::vector<double>& scores,
                                       std::size_t top_k = 0);

/// Ranks and applies the rule. Same errors as rank_candidates and UnknownRule::validate.
Decision decide(const std::vector<std::string>& names, const std::vector<double>& scores, const UnknownRule& rule);

}  // namespace facesocial
