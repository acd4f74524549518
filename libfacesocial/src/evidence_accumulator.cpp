#include "facesocial/evidence_accumulator.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <unordered_map>
#include <unordered_set>

namespace facesocial {

std::string to_string(AccumulationMode mode) {
    switch (mode) {
    case AccumulationMode::MovingAverage: return "average";
    case AccumulationMode::ExponentialDecay: return "decay";
    case AccumulationMode::MajorityVote: return "vote";
    }
    return "?";
}

AccumulationMode accumulation_mode_from_string(const std::string& name) {
    for (AccumulationMode m : {AccumulationMode::MovingAverage, AccumulationMode::ExponentialDecay, AccumulationMode::MajorityVote})
        if (to_string(m) == name) return m;
    throw std::invalid_argument("accumulation mode: expected average, decay or vote, got '" + name + "'");
}

void AccumulatorParams::validate() const {
    if (window < 1 || window > 100000)
        throw std::invalid_argument("AccumulatorParams: expected window in [1, 100000], got " + std::to_string(window));
    if (!(decay >= 0 && decay < 1))
        throw std::invalid_argument("AccumulatorParams: expected decay in [0, 1), got " + std::to_string(decay));
}

EvidenceAccumulator::EvidenceAccumulator(const AccumulatorParams& params) : params_(params) { params_.validate(); }

void EvidenceAccumulator::reset() {
    window_.clear();
    names_.clear();
    decayed_sum_.clear();
    decayed_weight_.clear();
    frames_ = 0;
}

void EvidenceAccumulator::add(const BankScores& frame) {
    if (frame.names.size() != frame.scores.size())
        throw std::invalid_argument("EvidenceAccumulator::add: expected as many scores as names, got " +
                                    std::to_string(frame.scores.size()) + " for " + std::to_string(frame.names.size()));
    std::unordered_set<std::string> seen;
    for (std::size_t i = 0; i < frame.names.size(); ++i) {
        if (!seen.insert(frame.names[i]).second)
            throw std::invalid_argument("EvidenceAccumulator::add: expected distinct names, got '" + frame.names[i] + "' twice");
        if (!std::isfinite(frame.scores[i]))
            throw std::invalid_argument("EvidenceAccumulator::add: expected finite scores, got " +
                                        std::to_string(frame.scores[i]) + " for '" + frame.names[i] + "'");
    }
    if (params_.mode == AccumulationMode::ExponentialDecay) {
        const double keep = params_.decay;
        for (std::size_t k = 0; k < names_.size(); ++k) decayed_sum_[k] *= keep, decayed_weight_[k] *= keep;
        for (std::size_t i = 0; i < frame.names.size(); ++i) {
            auto it = std::find(names_.begin(), names_.end(), frame.names[i]);
            std::size_t k = std::size_t(it - names_.begin());
            if (it == names_.end()) names_.push_back(frame.names[i]), decayed_sum_.push_back(0), decayed_weight_.push_back(0);
            decayed_sum_[k] += (1 - keep) * frame.scores[i];
            decayed_weight_[k] += 1 - keep;
        }
        ++frames_;
        return;
    }
    window_.push_back(frame);
    while (int(window_.size()) > params_.window) window_.pop_front();
    frames_ = int(window_.size());
}

BankScores EvidenceAccumulator::mean_scores() const {
    BankScores out;
    if (params_.mode == AccumulationMode::ExponentialDecay) {
        for (std::size_t k = 0; k < names_.size(); ++k)
            if (decayed_weight_[k] > 0) out.names.push_back(names_[k]), out.scores.push_back(decayed_sum_[k] / decayed_weight_[k]);
        return out;
    }
    std::unordered_map<std::string, std::size_t> index;
    std::vector<int> count;
    for (const BankScores& f : window_)
        for (std::size_t i = 0; i < f.names.size(); ++i) {
            auto [it, fresh] = index.emplace(f.names[i], out.names.size());
            if (fresh) out.names.push_back(f.names[i]), out.scores.push_back(0), count.push_back(0);
            out.scores[it->second] += f.scores[i];
            ++count[it->second];
        }
    for (std::size_t k = 0; k < out.scores.size(); ++k) out.scores[k] /= count[k];
    return out;
}

BankScores EvidenceAccumulator::accumulated() const {
    if (params_.mode != AccumulationMode::MajorityVote) return mean_scores();
    BankScores out = mean_scores();  // every name of the window, first-seen order
    std::fill(out.scores.begin(), out.scores.end(), 0.0);
    for (const BankScores& f : window_) {
        if (f.names.empty()) continue;
        // The frame's winner: best score, ties by name (as rank_candidates).
        std::size_t best = 0;
        for (std::size_t i = 1; i < f.names.size(); ++i)
            if (f.scores[i] > f.scores[best] || (f.scores[i] == f.scores[best] && f.names[i] < f.names[best])) best = i;
        const auto it = std::find(out.names.begin(), out.names.end(), f.names[best]);
        out.scores[std::size_t(it - out.names.begin())] += 1.0 / double(window_.size());
    }
    return out;
}

Decision EvidenceAccumulator::decide(const UnknownRule& rule) const {
    const BankScores mean = mean_scores();
    Decision d = facesocial::decide(mean.names, mean.scores, rule);
    if (params_.mode != AccumulationMode::MajorityVote || !d.known) return d;
    const BankScores votes = accumulated();
    const std::vector<Candidate> by_votes = rank_candidates(votes.names, votes.scores);
    d.name = by_votes.front().name;
    d.ranked = by_votes;
    return d;
}

}  // namespace facesocial
