// Pluggable face classifiers over a set of people: the embedded HMM (one model per person) and
// adapters for OpenCV's Eigenfaces, Fisherfaces and LBPH (contrib face module), so benchmarks
// compare them side by side.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "facesocial/ehmm.hpp"

namespace facesocial {

/// Which classifier FaceClassifier::create builds.
enum class ClassifierKind { Ehmm, Eigenfaces, Fisherfaces, Lbph };

/// "ehmm", "eigen", "fisher", "lbph".
std::string to_string(ClassifierKind kind);
/// Parses the names of to_string(ClassifierKind); std::invalid_argument for anything else.
ClassifierKind classifier_kind_from_string(const std::string& name);

/// How the EHMM classifier trains each person's model (docs/ehmm.md).
enum class EhmmTraining {
    /// Maximum likelihood from the person's faces alone, `ehmm.mixtures` Gaussians per state
    /// (the paper's training; 98.4% mean on ORL's random splits).
    Independent,
    /// A background model is trained on everyone's faces with `background_mixtures` Gaussians
    /// per state, and every person's model is its MAP adaptation to their faces (99.1%).
    Adapted,
};

/// "independent", "adapted".
std::string to_string(EhmmTraining training);
/// Parses the names of to_string(EhmmTraining); std::invalid_argument for anything else.
EhmmTraining ehmm_training_from_string(const std::string& name);

/// Parameters of every classifier kind (only the chosen kind's fields are used).
struct ClassifierParams {
    ClassifierKind kind = ClassifierKind::Ehmm;
    EhmmParams ehmm;            ///< Ehmm: topology and training
    EhmmTraining ehmm_training = EhmmTraining::Adapted;  ///< Ehmm: independent or adapted models
    int background_mixtures = 8;  ///< Ehmm, Adapted: Gaussians per state of the background (and so of every model)
    EhmmAdaptParams adaptation;   ///< Ehmm, Adapted: how the background moves to each person
    int eigen_components = 0;   ///< Eigenfaces: principal components kept (0 = all)
    int fisher_components = 0;  ///< Fisherfaces: discriminants kept (0 = people - 1)
    int lbph_radius = 1;        ///< LBPH: radius of the circular pattern
    int lbph_neighbors = 8;     ///< LBPH: sample points on the circle
    int lbph_grid = 8;          ///< LBPH: cells per side of the histogram grid
    int num_threads = -1;       ///< training and scoring threads (-1 = all cores)

    /// Throws std::invalid_argument naming the first invalid field.
    void validate() const;
    /// The EHMM parameters of the background model: `ehmm` with `background_mixtures`.
    EhmmParams background_params() const;
};

/// The background model of adapted EHMM training: trained on up to `faces_per_person` faces of
/// every person (spread evenly over each person's list), so one person with many images does
/// not dominate it. std::invalid_argument when there is no face at all.
EmbeddedHmm train_background(const std::vector<std::vector<cv::Mat>>& faces, const ClassifierParams& params,
                             std::size_t faces_per_person = 10);

/// A classifier over people 0..P-1. Faces are single-channel 8-bit or float images of one size
/// (normalised faces); scores are higher for a better match.
class FaceClassifier {
public:
    virtual ~FaceClassifier() = default;

    /// Short name ("ehmm", "eigen", ...).
    virtual std::string name() const = 0;

    /// Trains on faces[p] = the training faces of person p. Every person needs at least one
    /// face (Fisherfaces: at least two people); std::invalid_argument otherwise.
    virtual void train(const std::vector<std::vector<cv::Mat>>& faces) = 0;

    /// One score per person, higher = more alike. Throws std::logic_error before training.
    virtual std::vector<double> scores(const cv::Mat& face) const = 0;

    /// Number of people trained.
    virtual std::size_t size() const = 0;

    static std::unique_ptr<FaceClassifier> create(const ClassifierParams& params = {});
};

}  // namespace facesocial
