#include "facesocial/face_classifier.hpp"

#include <map>
#include <stdexcept>

#include <opencv2/face.hpp>

#include "checks.hpp"
#include "ehmm_impl.hpp"
#include "parallel.hpp"

namespace facesocial {

std::string to_string(ClassifierKind kind) {
    switch (kind) {
        case ClassifierKind::Ehmm: return "ehmm";
        case ClassifierKind::Eigenfaces: return "eigen";
        case ClassifierKind::Fisherfaces: return "fisher";
        case ClassifierKind::Lbph: return "lbph";
    }
    return "unknown";
}

ClassifierKind classifier_kind_from_string(const std::string& name) {
    for (ClassifierKind k : {ClassifierKind::Ehmm, ClassifierKind::Eigenfaces, ClassifierKind::Fisherfaces,
                             ClassifierKind::Lbph})
        if (to_string(k) == name) return k;
    throw std::invalid_argument("classifier_kind_from_string: expected ehmm, eigen, fisher or lbph, got '" + name + "'");
}

std::string to_string(EhmmTraining training) {
    return training == EhmmTraining::Independent ? "independent" : "adapted";
}

EhmmTraining ehmm_training_from_string(const std::string& name) {
    for (EhmmTraining t : {EhmmTraining::Independent, EhmmTraining::Adapted})
        if (to_string(t) == name) return t;
    throw std::invalid_argument("ehmm_training_from_string: expected independent or adapted, got '" + name + "'");
}

EhmmParams ClassifierParams::background_params() const {
    EhmmParams p = ehmm;
    p.mixtures = background_mixtures;
    return p;
}

EmbeddedHmm train_background(const std::vector<std::vector<cv::Mat>>& faces, const ClassifierParams& params,
                             std::size_t faces_per_person) {
    if (faces_per_person < 1) detail::fail("train_background", "faces_per_person >= 1", "0");
    std::vector<cv::Mat> pooled;
    for (const auto& person : faces) {
        const std::size_t n = person.size(), take = std::min(n, faces_per_person);
        for (std::size_t i = 0; i < take; ++i) pooled.push_back(person[i * n / take]);
    }
    if (pooled.empty()) detail::fail("train_background", "at least one face", "none");
    return EmbeddedHmm::train(pooled, params.background_params());
}

void ClassifierParams::validate() const {
    auto bad = [](const std::string& field, const std::string& expected, int got) {
        throw std::invalid_argument("ClassifierParams: expected " + field + " " + expected + ", got " + std::to_string(got));
    };
    if (kind == ClassifierKind::Ehmm) {
        ehmm.validate();
        if (ehmm_training != EhmmTraining::Independent && ehmm_training != EhmmTraining::Adapted)
            bad("ehmm_training", "independent or adapted", int(ehmm_training));
        if (background_mixtures < 1 || background_mixtures > 64) bad("background_mixtures", "in [1, 64]", background_mixtures);
        adaptation.validate();
    }
    if (eigen_components < 0) bad("eigen_components", ">= 0", eigen_components);
    if (fisher_components < 0) bad("fisher_components", ">= 0", fisher_components);
    if (lbph_radius < 1) bad("lbph_radius", ">= 1", lbph_radius);
    if (lbph_neighbors < 1 || lbph_neighbors > 31) bad("lbph_neighbors", "in [1, 31]", lbph_neighbors);
    if (lbph_grid < 1) bad("lbph_grid", ">= 1", lbph_grid);
    if (num_threads == 0 || num_threads < -1) bad("num_threads", "-1 or >= 1", num_threads);
}

namespace {

void require_faces(const std::vector<std::vector<cv::Mat>>& faces, const char* fn, std::size_t min_people) {
    if (faces.size() < min_people)
        detail::fail(fn, "at least " + std::to_string(min_people) + " people", std::to_string(faces.size()));
    for (std::size_t p = 0; p < faces.size(); ++p) {
        if (faces[p].empty()) detail::fail(fn, "at least one face per person", "none for person " + std::to_string(p));
        for (const cv::Mat& f : faces[p])
            if (f.empty() || f.channels() != 1 || (f.depth() != CV_8U && f.depth() != CV_32F))
                detail::fail(fn, "8-bit or float single-channel faces",
                             f.empty() ? "an empty image" : detail::type_name(f.type()));
    }
}

class EhmmClassifier final : public FaceClassifier {
public:
    explicit EhmmClassifier(const ClassifierParams& p) : params_(p) {}
    std::string name() const override { return "ehmm"; }
    std::size_t size() const override { return models_.size(); }

    void train(const std::vector<std::vector<cv::Mat>>& faces) override {
        require_faces(faces, "EhmmClassifier::train", 1);
        std::vector<EmbeddedHmm> models(faces.size());
        if (params_.ehmm_training == EhmmTraining::Adapted) {
            const EmbeddedHmm background = train_background(faces, params_);
            detail::parallel_for(
                faces.size(),
                [&](std::size_t p) { models[p] = EmbeddedHmm::adapt(background, faces[p], params_.adaptation); },
                params_.num_threads);
        } else {
            detail::parallel_for(
                faces.size(), [&](std::size_t p) { models[p] = EmbeddedHmm::train(faces[p], params_.ehmm); },
                params_.num_threads);
        }
        models_ = std::move(models);
    }

    std::vector<double> scores(const cv::Mat& face) const override {
        if (models_.empty()) throw std::logic_error("EhmmClassifier::scores: not trained");
        const Observations o = extract_observations(face, params_.ehmm.observations);
        // The [x^2, x, 1] features are the same for every person: build them once.
        thread_local RowMatrixF F;
        EmbeddedHmm::Impl::features(o, F);
        std::vector<double> s(models_.size());
        for (std::size_t p = 0; p < models_.size(); ++p) s[p] = models_[p].impl().score_features(F, o.grid);
        return s;
    }

private:
    ClassifierParams params_;
    std::vector<EmbeddedHmm> models_;
};

/// Eigenfaces, Fisherfaces and LBPH: score = minus the distance to the person's nearest
/// training face, as OpenCV's predict collector reports it.
class OpencvClassifier final : public FaceClassifier {
public:
    explicit OpencvClassifier(const ClassifierParams& p) : params_(p) {
        switch (p.kind) {
            case ClassifierKind::Eigenfaces: model_ = cv::face::EigenFaceRecognizer::create(p.eigen_components); break;
            case ClassifierKind::Fisherfaces: model_ = cv::face::FisherFaceRecognizer::create(p.fisher_components); break;
            default: model_ = cv::face::LBPHFaceRecognizer::create(p.lbph_radius, p.lbph_neighbors, p.lbph_grid, p.lbph_grid);
        }
    }
    std::string name() const override { return to_string(params_.kind); }
    std::size_t size() const override { return people_; }

    void train(const std::vector<std::vector<cv::Mat>>& faces) override {
        require_faces(faces, "FaceClassifier::train", params_.kind == ClassifierKind::Fisherfaces ? 2 : 1);
        std::vector<cv::Mat> images;
        std::vector<int> labels;
        for (std::size_t p = 0; p < faces.size(); ++p)
            for (const cv::Mat& f : faces[p]) images.push_back(prepare(f)), labels.push_back(int(p));
        model_->train(images, labels);
        people_ = faces.size();
    }

    std::vector<double> scores(const cv::Mat& face) const override {
        if (people_ == 0) throw std::logic_error("FaceClassifier::scores: not trained");
        auto collector = cv::face::StandardCollector::create(std::numeric_limits<double>::max());
        model_->predict(prepare(face), collector);
        std::vector<double> s(people_, -std::numeric_limits<double>::max());
        for (const auto& [label, distance] : collector->getResultsMap())
            if (label >= 0 && std::size_t(label) < people_) s[label] = -distance;
        return s;
    }

private:
    // LBPH needs 8-bit pixels; the subspace methods work on any depth. Float normalised faces
    // (zero mean, unit deviation) are mapped to 8 bits by +-3 deviations.
    cv::Mat prepare(const cv::Mat& f) const {
        if (f.depth() == CV_8U) return f;
        cv::Mat out;
        f.convertTo(out, CV_8U, 255.0 / 6.0, 127.5);
        return out;
    }

    ClassifierParams params_;
    cv::Ptr<cv::face::FaceRecognizer> model_;
    std::size_t people_ = 0;
};

}  // namespace

std::unique_ptr<FaceClassifier> FaceClassifier::create(const ClassifierParams& params) {
    params.validate();
    if (params.kind == ClassifierKind::Ehmm) return std::make_unique<EhmmClassifier>(params);
    return std::make_unique<OpencvClassifier>(params);
}

}  // namespace facesocial
