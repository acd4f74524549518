#include "facesocial/training_set.hpp"

#include "facesocial/classifier_bank.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>

namespace facesocial {

std::string to_string(SampleSource source) { return source == SampleSource::Camera ? "camera" : "social"; }

void TrainingPolicy::validate() const {
    if (max_size > 100000)
        throw std::invalid_argument("TrainingPolicy: expected max_size in [0, 100000], got " + std::to_string(max_size));
    if (!(prune_sigma >= 0 && prune_sigma <= 100))
        throw std::invalid_argument("TrainingPolicy: expected prune_sigma in [0, 100], got " + std::to_string(prune_sigma));
    if (min_after_pruning < 1)
        throw std::invalid_argument("TrainingPolicy: expected min_after_pruning >= 1, got 0");
}

SelectionReport select_training_samples(const std::vector<TrainingSample>& samples, const TrainingPolicy& policy,
                                        const EhmmParams& ehmm, const ClassifierBank* others, const std::string& person) {
    policy.validate();
    for (std::size_t i = 0; i < samples.size(); ++i)
        if (samples[i].face.empty())
            throw std::invalid_argument("select_training_samples: expected a face in every sample, sample " +
                                        std::to_string(i) + " has none");
    // Oldest first (stable: equal times keep their order).
    std::vector<std::size_t> order(samples.size());
    std::iota(order.begin(), order.end(), 0);
    std::stable_sort(order.begin(), order.end(),
                     [&](std::size_t a, std::size_t b) { return samples[a].capture_time < samples[b].capture_time; });
    SelectionReport r;

    // Pruning first, so the cap chooses among good samples.
    std::vector<std::size_t> candidates = order;
    if (policy.prune_sigma > 0 && candidates.size() > policy.min_after_pruning) {
        // Each sample is scored by a model that did not see it (two folds, alternating in time):
        // a model trained on an outlier would explain it well.
        std::vector<cv::Mat> faces;
        for (std::size_t i : candidates) faces.push_back(samples[i].face);
        std::vector<double> score(candidates.size());
        for (std::size_t fold = 0; fold < 2; ++fold) {
            std::vector<cv::Mat> train;
            for (std::size_t k = 0; k < faces.size(); ++k)
                if (k % 2 != fold) train.push_back(faces[k]);
            const EmbeddedHmm model = EmbeddedHmm::train(train, ehmm);
            for (std::size_t k = fold; k < faces.size(); k += 2) score[k] = model.score(faces[k]);
        }
        if (others)
            for (std::size_t k = 0; k < faces.size(); ++k) {
                const BankScores s = others->scores(faces[k]);
                double best = -std::numeric_limits<double>::infinity();
                for (std::size_t j = 0; j < s.names.size(); ++j)
                    if (s.names[j] != person) best = std::max(best, s.scores[j]);
                if (std::isfinite(best)) score[k] -= best;
            }
        // Robust centre and spread (median, 1.4826 x median absolute deviation): a few outliers
        // must not widen the band that is meant to catch them.
        auto median = [](std::vector<double> v) {
            std::nth_element(v.begin(), v.begin() + long(v.size() / 2), v.end());
            double m = v[v.size() / 2];
            if (v.size() % 2 == 0) m = 0.5 * (m + *std::max_element(v.begin(), v.begin() + long(v.size() / 2)));
            return m;
        };
        const double mean = median(score);
        std::vector<double> dev;
        for (double s : score) dev.push_back(std::abs(s - mean));
        const double sd = 1.4826 * median(dev);
        // Worst first, while enough samples remain.
        std::vector<std::size_t> by_score(candidates.size());
        std::iota(by_score.begin(), by_score.end(), 0);
        std::sort(by_score.begin(), by_score.end(), [&](std::size_t a, std::size_t b) { return score[a] < score[b]; });
        std::vector<char> drop(candidates.size(), 0);
        std::size_t left = candidates.size();
        for (std::size_t k : by_score) {
            if (left <= policy.min_after_pruning || sd <= 0 || score[k] >= mean - policy.prune_sigma * sd) break;
            drop[k] = 1;
            --left;
        }
        std::vector<std::size_t> kept;
        for (std::size_t k = 0; k < candidates.size(); ++k) (drop[k] ? r.pruned : kept).push_back(candidates[k]);
        candidates = kept;
    }

    if (policy.max_size == 0 || candidates.size() <= policy.max_size) {
        r.kept = candidates;
        return r;
    }
    std::vector<char> keep(candidates.size(), 0);
    if (policy.prefer_recent) {
        for (std::size_t k = candidates.size() - policy.max_size; k < candidates.size(); ++k) keep[k] = 1;
    } else {
        // Evenly over time: the oldest, the newest and equal steps between.
        const std::size_t n = policy.max_size;
        for (std::size_t j = 0; j < n; ++j) {
            const std::size_t k = n == 1 ? candidates.size() - 1 : (j * (candidates.size() - 1) + (n - 1) / 2) / (n - 1);
            keep[k] = 1;
        }
    }
    for (std::size_t k = 0; k < candidates.size(); ++k) (keep[k] ? r.kept : r.capped).push_back(candidates[k]);
    return r;
}

}  // namespace facesocial
