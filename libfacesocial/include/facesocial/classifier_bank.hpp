// The classifier bank: the vision module's API of the paper's section III.C. It keeps one
// training set per person and the classifiers trained from them, scores a face against every
// person, ranks the candidates and decides (with "unknown"), and persists everything in one
// versioned, checksummed file.
//
// Threading: every method may be called from several threads at once. Scoring works on an
// immutable snapshot of the trained models; training runs without holding the bank's lock and
// swaps the new snapshot in atomically, so faces can be scored while a person is retrained.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "facesocial/decision.hpp"
#include "facesocial/face_classifier.hpp"
#include "facesocial/face_normalizer.hpp"
#include "facesocial/training_set.hpp"

namespace facesocial {

/// Everything that shapes a bank; fixed when the bank is created and saved with it.
struct ClassifierBankParams {
    ClassifierParams classifier;  ///< the classifier kind (EHMM by default) and its parameters
    NormalizerParams normalizer;  ///< how normalize() turns face images into classifier input
    UnknownRule unknown;          ///< the rule decide() applies
    /// Which of a person's samples train their model: by default all of them; the paper's
    /// online size is TrainingPolicy{} (the newest 30). Pruning scores samples against the
    /// bank's other people.
    TrainingPolicy training = TrainingPolicy::keep_all();

    /// Throws std::invalid_argument naming the first invalid field, including a normaliser
    /// output size that differs from the EHMM's observation face size.
    void validate() const;
};

/// The scores of one face against the trained people, in the bank's order.
struct BankScores {
    std::vector<std::string> names;
    std::vector<double> scores;
};

class ClassifierBank {
public:
    /// Throws std::invalid_argument for invalid params.
    explicit ClassifierBank(const ClassifierBankParams& params = {});
    ~ClassifierBank();
    ClassifierBank(ClassifierBank&&) noexcept;
    ClassifierBank& operator=(ClassifierBank&&) noexcept;
    ClassifierBank(const ClassifierBank&) = delete;
    ClassifierBank& operator=(const ClassifierBank&) = delete;

    const ClassifierBankParams& params() const;
    /// The unknown rule can be changed at any time (it does not affect the models).
    void set_unknown_rule(const UnknownRule& rule);
    UnknownRule unknown_rule() const;

    /// Normalises an already cropped face image (8-bit grey or BGR) with the bank's normaliser.
    cv::Mat normalize(const cv::Mat& face_image) const;
    /// Normalises the face `box` of an 8-bit grey or BGR image.
    cv::Mat normalize(const cv::Mat& image, const cv::Rect& box) const;

    // --- training sets -----------------------------------------------------------------------

    /// Creates an empty training set. std::invalid_argument for an empty name, a name with
    /// control characters, or a person already there.
    void add_person(const std::string& name);
    /// Appends normalised faces (single-channel CV_32F or CV_8U of the normaliser's output size)
    /// to a person's training set, creating the person if needed. The faces are copied. The
    /// person's model is stale until trained again.
    void add_faces(const std::string& name, const std::vector<cv::Mat>& faces);
    /// Appends samples with their provenance (source, capture time, session); the faces are
    /// checked and copied as by add_faces.
    void add_samples(const std::string& name, const std::vector<TrainingSample>& samples);
    /// Empties a person's training set (the model stays until the person is trained again).
    void clear_faces(const std::string& name);
    /// Removes the person: training set and model. std::invalid_argument when not there.
    void remove_person(const std::string& name);

    bool contains(const std::string& name) const;
    /// Everyone with a training set, in enrolment order.
    std::vector<std::string> people() const;
    std::size_t face_count(const std::string& name) const;
    /// Copies of the person's normalised training faces.
    std::vector<cv::Mat> faces(const std::string& name) const;
    /// The person's samples with their provenance (faces copied). Faces added with add_faces
    /// are camera samples stamped with the wall-clock time of the call.
    std::vector<TrainingSample> samples(const std::string& name) const;
    /// Which samples (indices into samples()) the person's current model was trained from,
    /// and which the training policy left out.
    SelectionReport selection(const std::string& name) const;

    // --- models --------------------------------------------------------------------------------

    /// Retrains one person from their current training set. With the EHMM only that person's
    /// model changes (adapted training: from the bank's background model, built first from
    /// everyone's faces if there is none yet, which retrains everyone); the joint classifiers
    /// (Eigenfaces, Fisherfaces, LBPH) retrain everyone.
    /// std::invalid_argument for an unknown person or an empty training set.
    void train(const std::string& name);
    /// Retrains everyone whose training set changed since their last training (in parallel),
    /// skipping empty training sets. Adapted EHMM training first rebuilds the background model
    /// when there is none or the number of people has doubled since it was built, and then
    /// retrains everyone. Returns the names trained.
    std::vector<std::string> train();
    /// Adapted EHMM training: rebuilds the background model from everyone's training faces and
    /// retrains everyone from it. Returns the names trained (none for other kinds).
    std::vector<std::string> train_background();
    /// True when the bank holds a background model (adapted EHMM training, after training).
    bool has_background() const;
    /// True when the person's model reflects their current training set.
    bool is_trained(const std::string& name) const;
    /// The people recognition covers (those with a model), in the order of scores().
    std::vector<std::string> trained_people() const;
    /// People whose training set changed since their model was trained (or never trained).
    std::vector<std::string> stale() const;

    // --- recognition (scores cover the people with a model) ------------------------------------

    /// Scores a normalised face against every trained person (in parallel over people for the
    /// EHMM). Empty when no one is trained. std::invalid_argument for a wrong face type or size.
    BankScores scores(const cv::Mat& face) const;
    /// The `top_k` best candidates (0 = all), best first.
    std::vector<Candidate> rank(const cv::Mat& face, std::size_t top_k = 0) const;
    /// Ranked candidates and the decision under the bank's unknown rule.
    Decision decide(const cv::Mat& face) const;
    /// The same for a score vector computed elsewhere (for example accumulated over frames).
    Decision decide(const BankScores& scores) const;

    // --- persistence ---------------------------------------------------------------------------

    /// Writes params, training sets and models to `path` through a temporary file in the same
    /// folder and a rename, so an existing file is replaced only by a complete one.
    /// Throws FileError when it cannot be written.
    void save(const std::string& path) const;
    /// Reads a bank file. Throws FileError when it cannot be read and ModelFormatError when it
    /// is truncated, corrupt (checksum), foreign, or of a newer format version.
    static ClassifierBank load(const std::string& path);

    /// Format version written by save(); load() reads every version up to it.
    /// 1: first layout. 2: EhmmParams::recluster_mixtures stored with the EHMM parameters.
    /// 3: the training policy, and the provenance of every sample.
    /// 4: EHMM adapted training (parameters and the background model), EHMM layout 3 (row bands).
    static constexpr uint32_t kFormatVersion = 4;

private:
    struct Impl;
    /// The bank's training policy as a function of (name, samples), pruning against this bank.
    std::function<SelectionReport(const std::string&, const std::vector<TrainingSample>&)> selector() const;
    std::unique_ptr<Impl> impl_;
};

}  // namespace facesocial
