// The embedded hidden Markov model of a face (Nefian & Hayes, 1998; paper section III.C.3):
// super-states run from the top of the face to the bottom (forehead, eyes, nose, mouth, chin);
// each super-state holds a left-to-right HMM over the block columns whose states emit mixtures
// of diagonal Gaussians over the DCT observation vectors. One model per person.
// The algorithm is described in docs/ehmm.md.
#pragma once

#include <iosfwd>
#include <memory>
#include <random>
#include <vector>

#include <opencv2/core.hpp>

#include "facesocial/observations.hpp"

namespace facesocial {

/// Topology and training parameters of an embedded HMM.
struct EhmmParams {
    ObservationParams observations;              ///< how faces become observation vectors
    std::vector<int> states{3, 6, 6, 6, 3};      ///< embedded states of each super-state, top to bottom
    int mixtures = 3;                            ///< diagonal Gaussians per embedded state
    int max_iterations = 15;                     ///< cap on Viterbi re-estimation rounds
    double tolerance = 1e-3;  ///< stop when the mean per-observation log-likelihood gains less
    double variance_floor = 0.02;  ///< variances >= this share of the training data's variance
    double min_transition = 1e-3;  ///< transition probabilities are kept in [min, 1 - min]
    /// Re-cluster every state's mixtures by k-means on the second Viterbi segmentation instead of
    /// reassigning them by likelihood. Mixtures seeded from the uniform segmentation can end up
    /// sharing one cluster, which hard re-estimation never undoes; re-clustering recovers models
    /// far better (see docs/ehmm.md), but on ORL's five faces per person it costs 0.3 points, so
    /// it is off by default.
    bool recluster_mixtures = false;
    /// After training, each super-state is confined to the block rows it took in the training
    /// faces, widened by this many rows on each side, and scoring evaluates its Gaussians only
    /// there (about 40% less work with the defaults). -1: every super-state may take every row.
    int band_margin = 2;

    /// Throws std::invalid_argument naming the first invalid field, including a grid too small
    /// for the topology (fewer block rows than super-states or fewer columns than states).
    void validate() const;
    int total_states() const;
};

/// Maximum a-posteriori adaptation of a background model (trained on many people) to one
/// person: every Gaussian, mixture weight and transition moves from the background's value
/// towards the statistics of the person's observations aligned to it, by the share
/// n / (n + relevance) where n counts those observations. Parts the person's few images hardly
/// show stay close to the background instead of being fitted to a handful of blocks.
struct EhmmAdaptParams {
    double relevance = 4.0;          ///< the background's weight, in observations
    int iterations = 3;              ///< rounds of {Viterbi segmentation, update}
    bool adapt_variances = true;     ///< else the person keeps the background's variances
    bool adapt_weights = true;       ///< mixture weights
    bool adapt_transitions = true;   ///< transitions of both levels

    /// Throws std::invalid_argument naming the first invalid field.
    void validate() const;
};

/// The Viterbi alignment of one face to a model.
struct EhmmSegmentation {
    cv::Size grid;                 ///< blocks per row x rows
    std::vector<int> super_state;  ///< per block row
    std::vector<int> state;        ///< per block (row-major): embedded state within its super-state
    double log_likelihood = 0;     ///< total Viterbi log-likelihood
};

/// What training did.
struct EhmmTrainingReport {
    int iterations = 0;                          ///< re-estimation rounds run
    std::vector<double> mean_log_likelihood;     ///< per observation, after segmentation, per round
    bool converged = false;                      ///< gain fell under the tolerance
};

/// A trained embedded HMM. Cheap to copy (shares the immutable model); safe to score from
/// several threads.
class EmbeddedHmm {
public:
    EmbeddedHmm();
    ~EmbeddedHmm();
    EmbeddedHmm(const EmbeddedHmm&);
    EmbeddedHmm& operator=(const EmbeddedHmm&);
    EmbeddedHmm(EmbeddedHmm&&) noexcept;
    EmbeddedHmm& operator=(EmbeddedHmm&&) noexcept;

    /// Trains on one person's faces (8-bit or float single-channel images, any size; resized to
    /// params.observations.face_size). Needs at least one face; std::invalid_argument otherwise.
    static EmbeddedHmm train(const std::vector<cv::Mat>& faces, const EhmmParams& params = {},
                             EhmmTrainingReport* report = nullptr);
    /// Trains on observation grids (all of the params' grid size).
    static EmbeddedHmm train(const std::vector<Observations>& observations, const EhmmParams& params,
                             EhmmTrainingReport* report = nullptr);

    /// Adapts `background` to one person's faces (resized to the background's face size) by MAP
    /// re-estimation (EhmmAdaptParams). The result has the background's topology and parameters.
    /// std::invalid_argument for an empty background or no face.
    static EmbeddedHmm adapt(const EmbeddedHmm& background, const std::vector<cv::Mat>& faces,
                             const EhmmAdaptParams& params = {}, EhmmTrainingReport* report = nullptr);
    /// Adapts to observation grids (all of the background's grid size).
    static EmbeddedHmm adapt(const EmbeddedHmm& background, const std::vector<Observations>& observations,
                             const EhmmAdaptParams& params = {}, EhmmTrainingReport* report = nullptr);

    /// True for a default-constructed model (nothing trained or loaded).
    bool empty() const;
    const EhmmParams& params() const;

    /// The paper's scaled log-probability: doubly embedded Viterbi log-likelihood divided by
    /// the number of observations. Higher is a better match. Throws std::logic_error when empty.
    double score(const cv::Mat& face) const;
    double score(const Observations& observations) const;

    /// The best alignment of a face's observations to the model.
    EhmmSegmentation segment(const Observations& observations) const;

    /// Draws an observation grid from the model (state path from the transitions, vectors from
    /// the Gaussians) with its true segmentation. For tests of training.
    std::pair<Observations, EhmmSegmentation> sample(cv::Size grid, std::mt19937& rng) const;

    /// A model with random but well separated Gaussians, for tests and benchmarks.
    static EmbeddedHmm random(const EhmmParams& params, std::mt19937& rng, double spread = 4.0);

    /// Binary serialisation (little-endian floats; the bank file adds header and checksum).
    /// Writes the current layout (that of bank format version ClassifierBank::kFormatVersion).
    void write(std::ostream& out) const;
    /// Reads what write() wrote, or the layout of an older bank `format_version`. Throws
    /// ModelFormatError (path given as "<stream>") on a short or inconsistent stream.
    static EmbeddedHmm read(std::istream& in, uint32_t format_version = kLayoutVersion);
    /// Layouts: 1 first; 2 adds recluster_mixtures; 3 adds band_margin and the row bands.
    static constexpr uint32_t kLayoutVersion = 3;  ///< layout written by write()

    struct Impl;  ///< private
    const Impl& impl() const;

private:
    std::shared_ptr<const Impl> impl_;
};

}  // namespace facesocial
