// Temporal evidence accumulation (paper sections III.C.3 and V): a face seen over several frames
// is recognised from the classifiers' continuous scores accumulated in a moving window, at the
// level of the score vector before any decision (the paper: equal weights, about 25 frames at
// 5 fps). Alternatives for comparison: exponential decay of the past, and a majority vote of the
// per-frame winners. The bank's unknown rule is applied to the accumulated vector.
#pragma once

#include <deque>
#include <string>
#include <vector>

#include "facesocial/classifier_bank.hpp"
#include "facesocial/decision.hpp"

namespace facesocial {

/// How frames are combined.
enum class AccumulationMode {
    MovingAverage,     ///< equal-weight mean of the last `window` score vectors (the paper)
    ExponentialDecay,  ///< s = decay * s + (1 - decay) * frame, normalised by the weights so far
    MajorityVote,      ///< per-frame winners voted over the last `window` frames
};

/// "average", "decay", "vote".
std::string to_string(AccumulationMode mode);
/// Parses those names; std::invalid_argument otherwise.
AccumulationMode accumulation_mode_from_string(const std::string& name);

/// Parameters of the accumulator.
struct AccumulatorParams {
    AccumulationMode mode = AccumulationMode::MovingAverage;
    int window = 25;       ///< frames in the moving window (MovingAverage, MajorityVote), >= 1
    double decay = 0.9;    ///< ExponentialDecay: weight kept by the past at each frame, in [0, 1)
    /// Throws std::invalid_argument naming the first invalid field.
    void validate() const;
};

/// Accumulates the score vectors of one face track.
///
/// Frames are aligned by name, so people enrolled or removed while the track runs are handled:
/// a person's accumulated score is the mean (or decayed mean) over the frames that scored them.
/// Not thread-safe: one accumulator per track.
class EvidenceAccumulator {
public:
    /// Throws std::invalid_argument for invalid params.
    explicit EvidenceAccumulator(const AccumulatorParams& params = {});
    const AccumulatorParams& params() const { return params_; }

    /// Adds one frame's scores. std::invalid_argument when names and scores differ in length,
    /// a name repeats, or a score is not finite.
    void add(const BankScores& frame);
    /// Frames currently contributing (<= window for the windowed modes; all for decay).
    int frames() const { return frames_; }
    /// Forgets every frame.
    void reset();

    /// The accumulated score vector, names in first-seen order. MovingAverage and
    /// ExponentialDecay: (weighted) mean scores. MajorityVote: the share of the window's frames
    /// each person won. Empty before the first frame.
    BankScores accumulated() const;

    /// Ranked candidates and the decision under `rule`. For MajorityVote the candidates are
    /// ranked by votes and the rule is applied to the mean scores of the same window (so the
    /// thresholds mean the same as for one frame); the decision's score, variance and margin
    /// are those of the mean scores.
    Decision decide(const UnknownRule& rule) const;

private:
    BankScores mean_scores() const;

    AccumulatorParams params_;
    std::deque<BankScores> window_;     // windowed modes
    std::vector<std::string> names_;    // decay: names seen so far
    std::vector<double> decayed_sum_;   // decay: sum of weight * score per name
    std::vector<double> decayed_weight_;
    int frames_ = 0;
};

}  // namespace facesocial
