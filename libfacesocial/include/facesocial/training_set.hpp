// A person's training samples with their provenance, and the policies that choose which of them
// train the person's classifier (paper section V: how large should a training set be, which
// samples should it keep?). A robot collects camera frames and tagged social photos over many
// sessions; a small set retrains quickly online (about 30 samples in the paper), a large one
// (up to 400) is better retrained in the background (BackgroundTrainer).
#pragma once

#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "facesocial/ehmm.hpp"

namespace facesocial {

class ClassifierBank;

/// Where a sample came from.
enum class SampleSource {
    Camera,       ///< the robot's own camera
    SocialPhoto,  ///< a tagged photo from the social network
};

/// "camera", "social".
std::string to_string(SampleSource source);

/// One normalised face of a person and where and when it was taken.
struct TrainingSample {
    cv::Mat face;                               ///< normalised face (CV_32F or CV_8U, one channel)
    SampleSource source = SampleSource::Camera;
    double capture_time = 0;                    ///< seconds (any epoch, one per robot)
    std::string session;                        ///< e.g. the date of the encounter
};

/// Which samples train a person's classifier.
struct TrainingPolicy {
    /// At most this many samples (0 = all). The paper retrained online from about 30.
    std::size_t max_size = 30;
    /// Over the cap: keep the newest samples (true) or spread the kept ones evenly over time,
    /// oldest to newest (false).
    bool prefer_recent = true;
    /// Outlier pruning: score every candidate with a model trained on the other half of the
    /// candidates (two folds alternating in time), and drop samples whose score is
    /// more than this many robust standard deviations (1.4826 x the median absolute deviation)
    /// under the median score (0 = off).
    /// Wrong tags and bad crops score far below a person's real faces.
    double prune_sigma = 0;
    /// Never prune below this many samples.
    std::size_t min_after_pruning = 3;
    /// True when the policy keeps every sample as it is (no cap, no pruning).
    bool keeps_all() const { return max_size == 0 && prune_sigma == 0; }
    /// No cap, no pruning: every sample trains the model.
    static TrainingPolicy keep_all() {
        TrainingPolicy p;
        p.max_size = 0;
        return p;
    }
    /// Throws std::invalid_argument naming the first invalid field.
    void validate() const;
};

/// What select_training_samples did.
struct SelectionReport {
    std::vector<std::size_t> kept;     ///< indices into the samples, oldest first
    std::vector<std::size_t> pruned;   ///< indices dropped as outliers
    std::vector<std::size_t> capped;   ///< indices dropped by the size cap
};

/// Applies a policy to one person's samples. Pruning trains embedded HMMs with `ehmm`. When
/// `others` is given (a bank of other people; `person` itself is skipped in it), a sample's
/// statistic is its own-model score minus its best score among the others: the EHMM's absolute
/// scores vary from photo to photo far more than between people, so a wrongly tagged face is
/// told by another person explaining it better, not by a low score (docs/classifier_bank.md).
/// Throws std::invalid_argument for an invalid policy or a sample without a face.
SelectionReport select_training_samples(const std::vector<TrainingSample>& samples, const TrainingPolicy& policy,
                                        const EhmmParams& ehmm = {}, const ClassifierBank* others = nullptr,
                                        const std::string& person = {});

}  // namespace facesocial
