#include "facesocial/classifier_bank.hpp"

#include <algorithm>
#include <chrono>
#include <functional>
#include <numeric>
#include <cstring>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <mutex>
#include <sstream>
#include <stdexcept>
#include <unistd.h>

#include "binary_io.hpp"
#include "checks.hpp"
#include "ehmm_impl.hpp"
#include "facesocial/error.hpp"
#include "parallel.hpp"

namespace facesocial {

namespace fs = std::filesystem;

void ClassifierBankParams::validate() const {
    classifier.validate();
    normalizer.validate();
    unknown.validate();
    training.validate();
    if (classifier.kind == ClassifierKind::Ehmm && classifier.ehmm.observations.face_size != normalizer.output_size)
        detail::fail("ClassifierBankParams",
                     "normalizer.output_size equal to the EHMM face size " +
                         detail::size_string(classifier.ehmm.observations.face_size),
                     detail::size_string(normalizer.output_size));
}

namespace {

/// Where a face came from (TrainingSample without the face).
struct Provenance {
    SampleSource source = SampleSource::Camera;
    double time = 0;
    std::string session;
};

double wall_clock_seconds() {
    return std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch()).count();
}

struct Person {
    std::string name;
    std::vector<cv::Mat> faces;  // normalised, CV_32FC1; never modified in place
    std::vector<Provenance> provenance;  // one per face
    SelectionReport selection;   // of the samples the model was trained from
    uint64_t version = 1;        // bumped by every change of the training set
    uint64_t trained_version = 0;  // version the model was trained from (0 = never)
    EmbeddedHmm model;           // EHMM kind only
};

/// What scoring reads: immutable once published.
struct Snapshot {
    std::vector<std::string> names;
    std::vector<EmbeddedHmm> models;                // EHMM: one per name
    std::shared_ptr<const FaceClassifier> joint;    // other kinds
    std::vector<std::size_t> joint_index;           // per name: its index in joint's scores
};

void require_name(const std::string& name, const char* fn) {
    if (name.empty()) detail::fail(fn, "a non-empty person name", "an empty name");
    for (unsigned char c : name)
        if (c < 0x20 || c == 0x7f) detail::fail(fn, "a person name without control characters", "'" + name + "'");
}

}  // namespace

struct ClassifierBank::Impl {
    ClassifierBankParams params;
    FaceNormalizer normalizer;
    mutable std::mutex mutex;  // guards people, params.unknown and the snapshot pointer
    std::vector<Person> people;
    std::shared_ptr<const Snapshot> snapshot = std::make_shared<Snapshot>();
    EmbeddedHmm background;         // EHMM, adapted training: the model every person adapts from
    uint64_t background_people = 0;  // people whose faces trained it

    explicit Impl(const ClassifierBankParams& p) : params(p), normalizer(p.normalizer) {}

    bool joint_kind() const { return params.classifier.kind != ClassifierKind::Ehmm; }

    Person* find(const std::string& name) {
        for (auto& p : people)
            if (p.name == name) return &p;
        return nullptr;
    }
    Person& get(const std::string& name, const char* fn) {
        Person* p = find(name);
        if (!p) detail::fail(fn, "an enrolled person", "'" + name + "'");
        return *p;
    }

    std::shared_ptr<const Snapshot> current() const {
        std::lock_guard lock(mutex);
        return snapshot;
    }

    /// EHMM: republishes the models of the people who have one. Call with the lock held.
    void publish_models() {
        auto s = std::make_shared<Snapshot>();
        for (const Person& p : people)
            if (!p.model.empty()) s->names.push_back(p.name), s->models.push_back(p.model);
        snapshot = std::move(s);
    }

    /// Joint kinds: drops people no longer enrolled from the published joint model. Lock held.
    void prune_joint() {
        auto s = std::make_shared<Snapshot>();
        s->joint = snapshot->joint;
        for (std::size_t i = 0; i < snapshot->names.size(); ++i)
            if (find(snapshot->names[i])) s->names.push_back(snapshot->names[i]), s->joint_index.push_back(snapshot->joint_index[i]);
        snapshot = std::move(s);
    }

    void check_face(const cv::Mat& f, const char* fn) const {
        const cv::Size size = params.normalizer.output_size;
        if (f.empty()) detail::fail(fn, "a normalised face", "an empty image");
        if (f.dims != 2 || f.channels() != 1 || (f.depth() != CV_32F && f.depth() != CV_8U))
            detail::fail(fn, "a single-channel CV_32F or CV_8U normalised face", detail::type_name(f.type()));
        if (f.size() != size)
            detail::fail(fn, "a face of the normaliser's size " + detail::size_string(size), detail::size_string(f.size()));
    }

    /// Chooses the training faces of one person from their samples (the bank's policy).
    using Selector = std::function<SelectionReport(const std::string&, const std::vector<TrainingSample>&)>;

    std::vector<TrainingSample> samples_of(const Person& p) const {
        std::vector<TrainingSample> out;
        for (std::size_t i = 0; i < p.faces.size(); ++i)
            out.push_back({p.faces[i], p.provenance[i].source, p.provenance[i].time, p.provenance[i].session});
        return out;
    }
    /// Applies the policy outside the lock; keep-all keeps the insertion order.
    std::pair<std::vector<cv::Mat>, SelectionReport> choose(const std::string& name, const std::vector<TrainingSample>& s,
                                                            const Selector& select) const {
        SelectionReport r;
        if (params.training.keeps_all()) {
            r.kept.resize(s.size());
            std::iota(r.kept.begin(), r.kept.end(), 0);
        } else {
            r = select(name, s);
        }
        std::vector<cv::Mat> faces;
        for (std::size_t i : r.kept) faces.push_back(s[i].face);
        return {std::move(faces), std::move(r)};
    }

    std::vector<std::string> train_joint(const Selector& select);
    std::vector<std::string> train_ehmm(const std::vector<std::string>* only, const Selector& select,
                                        bool rebuild_background = false);
};

std::vector<std::string> ClassifierBank::Impl::train_joint(const Selector& select) {
    std::vector<std::string> names;
    std::vector<uint64_t> versions;
    std::vector<std::vector<TrainingSample>> samples;
    {
        std::lock_guard lock(mutex);
        for (const Person& p : people)
            if (!p.faces.empty()) names.push_back(p.name), versions.push_back(p.version), samples.push_back(samples_of(p));
    }
    if (names.empty()) return {};
    std::vector<std::vector<cv::Mat>> sets;
    std::vector<SelectionReport> reports;
    for (std::size_t i = 0; i < names.size(); ++i) {
        auto [faces, report] = choose(names[i], samples[i], select);
        sets.push_back(std::move(faces));
        reports.push_back(std::move(report));
    }
    std::shared_ptr<FaceClassifier> classifier = FaceClassifier::create(params.classifier);
    classifier->train(sets);
    std::lock_guard lock(mutex);
    auto s = std::make_shared<Snapshot>();
    s->joint = std::move(classifier);
    for (std::size_t i = 0; i < names.size(); ++i) {
        Person* p = find(names[i]);
        if (!p) continue;  // removed while training
        p->trained_version = std::max(p->trained_version, versions[i]);
        p->selection = reports[i];
        s->names.push_back(names[i]);
        s->joint_index.push_back(i);
    }
    snapshot = std::move(s);
    return names;
}

std::vector<std::string> ClassifierBank::Impl::train_ehmm(const std::vector<std::string>* only, const Selector& select,
                                                         bool rebuild_background) {
    const bool adapted = params.classifier.ehmm_training == EhmmTraining::Adapted;
    std::vector<std::string> names;
    std::vector<uint64_t> versions;
    std::vector<std::vector<TrainingSample>> samples;
    EmbeddedHmm prior;
    {
        std::lock_guard lock(mutex);
        if (only) {
            for (const std::string& n : *only) {
                Person& p = get(n, "ClassifierBank::train");
                if (p.faces.empty()) detail::fail("ClassifierBank::train", "training faces for '" + n + "'", "none");
            }
        }
        std::size_t with_faces = 0;
        for (const Person& p : people) with_faces += !p.faces.empty();
        // The background is (re)built on first use, when the bank has doubled since it was
        // built, or on request; then everyone adapts again from the new one.
        rebuild_background = adapted && with_faces > 0 &&
                             (rebuild_background || background.empty() || (!only && with_faces >= 2 * background_people));
        prior = background;
        for (const Person& p : people) {
            const bool wanted = only ? std::find(only->begin(), only->end(), p.name) != only->end()
                                     : p.version != p.trained_version;
            if (!p.faces.empty() && (wanted || rebuild_background))
                names.push_back(p.name), versions.push_back(p.version), samples.push_back(samples_of(p));
        }
    }
    std::vector<std::vector<cv::Mat>> sets(names.size());
    std::vector<SelectionReport> reports(names.size());
    for (std::size_t i = 0; i < names.size(); ++i) std::tie(sets[i], reports[i]) = choose(names[i], samples[i], select);
    if (rebuild_background) prior = facesocial::train_background(sets, params.classifier);
    std::vector<EmbeddedHmm> models(names.size());
    detail::parallel_for(
        names.size(),
        [&](std::size_t i) {
            models[i] = adapted ? EmbeddedHmm::adapt(prior, sets[i], params.classifier.adaptation)
                                : EmbeddedHmm::train(sets[i], params.classifier.ehmm);
        },
        params.classifier.num_threads);
    std::lock_guard lock(mutex);
    if (rebuild_background) background = prior, background_people = names.size();
    for (std::size_t i = 0; i < names.size(); ++i) {
        Person* p = find(names[i]);
        if (!p || p->trained_version > versions[i]) continue;  // removed, or a newer training won
        p->trained_version = versions[i];
        p->model = std::move(models[i]);
        p->selection = std::move(reports[i]);
    }
    publish_models();
    return names;
}

ClassifierBank::ClassifierBank(const ClassifierBankParams& params) {
    params.validate();
    impl_ = std::make_unique<Impl>(params);
}
ClassifierBank::~ClassifierBank() = default;
ClassifierBank::ClassifierBank(ClassifierBank&&) noexcept = default;
ClassifierBank& ClassifierBank::operator=(ClassifierBank&&) noexcept = default;

const ClassifierBankParams& ClassifierBank::params() const { return impl_->params; }

void ClassifierBank::set_unknown_rule(const UnknownRule& rule) {
    rule.validate();
    std::lock_guard lock(impl_->mutex);
    impl_->params.unknown = rule;
}

UnknownRule ClassifierBank::unknown_rule() const {
    std::lock_guard lock(impl_->mutex);
    return impl_->params.unknown;
}

cv::Mat ClassifierBank::normalize(const cv::Mat& face_image) const {
    return impl_->normalizer.normalize(face_image).pixels;
}

cv::Mat ClassifierBank::normalize(const cv::Mat& image, const cv::Rect& box) const {
    return impl_->normalizer.normalize(image, box).pixels;
}

void ClassifierBank::add_person(const std::string& name) {
    require_name(name, "ClassifierBank::add_person");
    std::lock_guard lock(impl_->mutex);
    if (impl_->find(name)) detail::fail("ClassifierBank::add_person", "a new person", "'" + name + "', already enrolled");
    impl_->people.push_back(Person{name, {}, {}, {}, 1, 0, {}});
}

void ClassifierBank::add_faces(const std::string& name, const std::vector<cv::Mat>& faces) {
    std::vector<TrainingSample> samples;
    const double now = wall_clock_seconds();
    for (const cv::Mat& f : faces) samples.push_back({f, SampleSource::Camera, now, {}});
    add_samples(name, samples);
}

void ClassifierBank::add_samples(const std::string& name, const std::vector<TrainingSample>& samples) {
    require_name(name, "ClassifierBank::add_faces");
    std::vector<cv::Mat> copies;
    copies.reserve(samples.size());
    for (const TrainingSample& s : samples) {
        const cv::Mat& f = s.face;
        if (!std::isfinite(s.capture_time))
            detail::fail("ClassifierBank::add_samples", "a finite capture time", std::to_string(s.capture_time));
        impl_->check_face(f, "ClassifierBank::add_faces");
        cv::Mat c;
        f.convertTo(c, CV_32F);  // always a fresh buffer: the caller's data is not shared
        if (c.data == f.data) c = c.clone();
        copies.push_back(std::move(c));
    }
    std::lock_guard lock(impl_->mutex);
    Person* p = impl_->find(name);
    if (!p) {
        impl_->people.push_back(Person{name, {}, {}, {}, 1, 0, {}});
        p = &impl_->people.back();
    }
    p->faces.insert(p->faces.end(), copies.begin(), copies.end());
    for (const TrainingSample& s : samples) p->provenance.push_back({s.source, s.capture_time, s.session});
    ++p->version;
}

void ClassifierBank::clear_faces(const std::string& name) {
    std::lock_guard lock(impl_->mutex);
    Person& p = impl_->get(name, "ClassifierBank::clear_faces");
    p.faces.clear();
    p.provenance.clear();
    ++p.version;
}

void ClassifierBank::remove_person(const std::string& name) {
    std::lock_guard lock(impl_->mutex);
    impl_->get(name, "ClassifierBank::remove_person");
    std::erase_if(impl_->people, [&](const Person& p) { return p.name == name; });
    if (impl_->joint_kind())
        impl_->prune_joint();
    else
        impl_->publish_models();
}

bool ClassifierBank::contains(const std::string& name) const {
    std::lock_guard lock(impl_->mutex);
    return impl_->find(name) != nullptr;
}

std::vector<std::string> ClassifierBank::people() const {
    std::lock_guard lock(impl_->mutex);
    std::vector<std::string> names;
    for (const Person& p : impl_->people) names.push_back(p.name);
    return names;
}

std::size_t ClassifierBank::face_count(const std::string& name) const {
    std::lock_guard lock(impl_->mutex);
    return impl_->get(name, "ClassifierBank::face_count").faces.size();
}

std::vector<cv::Mat> ClassifierBank::faces(const std::string& name) const {
    std::lock_guard lock(impl_->mutex);
    std::vector<cv::Mat> out;
    for (const cv::Mat& f : impl_->get(name, "ClassifierBank::faces").faces) out.push_back(f.clone());
    return out;
}

std::vector<TrainingSample> ClassifierBank::samples(const std::string& name) const {
    std::lock_guard lock(impl_->mutex);
    std::vector<TrainingSample> out = impl_->samples_of(impl_->get(name, "ClassifierBank::samples"));
    for (TrainingSample& s : out) s.face = s.face.clone();
    return out;
}

SelectionReport ClassifierBank::selection(const std::string& name) const {
    std::lock_guard lock(impl_->mutex);
    return impl_->get(name, "ClassifierBank::selection").selection;
}

std::function<SelectionReport(const std::string&, const std::vector<TrainingSample>&)> ClassifierBank::selector() const {
    return [this](const std::string& name, const std::vector<TrainingSample>& s) {
        return select_training_samples(s, impl_->params.training, impl_->params.classifier.ehmm, this, name);
    };
}

void ClassifierBank::train(const std::string& name) {
    if (impl_->joint_kind()) {
        {
            std::lock_guard lock(impl_->mutex);
            if (impl_->get(name, "ClassifierBank::train").faces.empty())
                detail::fail("ClassifierBank::train", "training faces for '" + name + "'", "none");
        }
        impl_->train_joint(selector());
        return;
    }
    const std::vector<std::string> only{name};
    impl_->train_ehmm(&only, selector());
}

std::vector<std::string> ClassifierBank::train() {
    if (impl_->joint_kind()) {
        if (stale().empty()) return {};
        return impl_->train_joint(selector());
    }
    return impl_->train_ehmm(nullptr, selector());
}

std::vector<std::string> ClassifierBank::train_background() {
    if (impl_->joint_kind() || impl_->params.classifier.ehmm_training != EhmmTraining::Adapted) return {};
    return impl_->train_ehmm(nullptr, selector(), true);
}

bool ClassifierBank::has_background() const {
    std::lock_guard lock(impl_->mutex);
    return !impl_->background.empty();
}

bool ClassifierBank::is_trained(const std::string& name) const {
    std::lock_guard lock(impl_->mutex);
    const Person& p = impl_->get(name, "ClassifierBank::is_trained");
    return p.trained_version == p.version;
}

std::vector<std::string> ClassifierBank::trained_people() const { return impl_->current()->names; }

std::vector<std::string> ClassifierBank::stale() const {
    std::lock_guard lock(impl_->mutex);
    std::vector<std::string> out;
    for (const Person& p : impl_->people)
        if (p.trained_version != p.version) out.push_back(p.name);
    return out;
}

BankScores ClassifierBank::scores(const cv::Mat& face) const {
    impl_->check_face(face, "ClassifierBank::scores");
    const std::shared_ptr<const Snapshot> snap = impl_->current();
    BankScores out;
    out.names = snap->names;
    out.scores.resize(snap->names.size());
    if (snap->names.empty()) return out;
    if (snap->joint) {
        const std::vector<double> all = snap->joint->scores(face);
        for (std::size_t i = 0; i < snap->names.size(); ++i) out.scores[i] = all[snap->joint_index[i]];
        return out;
    }
    const Observations o = extract_observations(face, impl_->params.classifier.ehmm.observations);
    RowMatrixF F;  // the [x^2, x, 1] features are the same for every person: built once
    EmbeddedHmm::Impl::features(o, F);
    // Below about 8 people the task overhead outweighs the work of splitting.
    const int threads = snap->models.size() < 8 ? 1 : impl_->params.classifier.num_threads;
    detail::parallel_for(
        snap->models.size(), [&](std::size_t i) { out.scores[i] = snap->models[i].impl().score_features(F, o.grid); },
        threads);
    return out;
}

std::vector<Candidate> ClassifierBank::rank(const cv::Mat& face, std::size_t top_k) const {
    const BankScores s = scores(face);
    return rank_candidates(s.names, s.scores, top_k);
}

Decision ClassifierBank::decide(const cv::Mat& face) const { return decide(scores(face)); }

Decision ClassifierBank::decide(const BankScores& scores) const {
    return facesocial::decide(scores.names, scores.scores, unknown_rule());
}

// ---------------------------------------------------------------------------------------------
// Bank file: magic (16 bytes) | format version u32 | payload size u64 | payload | FNV-1a-64 of
// the payload. Little-endian. The payload holds the params, then per person the name, the
// versions, the normalised training faces and (EHMM) the model. Joint classifiers are retrained
// from the saved training sets when the file is loaded.

namespace {

constexpr char kMagic[16] = {'F', 'A', 'C', 'E', 'S', 'O', 'C', 'I', 'A', 'L', '-', 'B', 'A', 'N', 'K', '\n'};
constexpr const char* kWhat = "bank";
/// The EHMM layout inside a bank file of `version`: bank 1 holds layout 1, banks 2 and 3
/// layout 2, bank 4 layout 3.
uint32_t ehmm_layout(uint32_t version) { return version <= 1 ? 1 : version <= 3 ? 2 : 3; }
static_assert(EmbeddedHmm::kLayoutVersion == 3, "a new EHMM layout needs a new bank version and ehmm_layout()");
constexpr uint64_t kMaxFaces = 1u << 20;

using detail::get;
using detail::put;

void write_params(std::ostream& out, const ClassifierBankParams& p) {
    const ClassifierParams& c = p.classifier;
    put<int32_t>(out, int32_t(c.kind));
    write_ehmm_params(out, c.ehmm);
    for (int v : {c.eigen_components, c.fisher_components, c.lbph_radius, c.lbph_neighbors, c.lbph_grid, c.num_threads})
        put<int32_t>(out, v);
    const NormalizerParams& n = p.normalizer;
    put<int32_t>(out, n.output_size.width);
    put<int32_t>(out, n.output_size.height);
    put<double>(out, n.ellipse_width);
    put<double>(out, n.ellipse_height);
    put<uint8_t>(out, n.elliptical_mask);
    put<uint8_t>(out, n.equalize);
    put<double>(out, n.vertical_margin);
    put<double>(out, p.unknown.min_variance);
    put<double>(out, p.unknown.min_score);
    put<double>(out, p.unknown.min_margin);
    put<uint64_t>(out, p.training.max_size);  // since version 3
    put<uint8_t>(out, p.training.prefer_recent);
    put<double>(out, p.training.prune_sigma);
    put<uint64_t>(out, p.training.min_after_pruning);
    put<uint8_t>(out, uint8_t(c.ehmm_training));  // since version 4
    put<int32_t>(out, c.background_mixtures);
    put<double>(out, c.adaptation.relevance);
    put<int32_t>(out, c.adaptation.iterations);
    put<uint8_t>(out, c.adaptation.adapt_variances);
    put<uint8_t>(out, c.adaptation.adapt_weights);
    put<uint8_t>(out, c.adaptation.adapt_transitions);
}

ClassifierBankParams read_params(std::istream& in, uint32_t version) {
    ClassifierBankParams p;
    ClassifierParams& c = p.classifier;
    const int32_t kind = get<int32_t>(in, kWhat);
    if (kind < 0 || kind > int32_t(ClassifierKind::Lbph))
        throw ModelFormatError("<stream>", "bank with unknown classifier kind " + std::to_string(kind));
    c.kind = ClassifierKind(kind);
    c.ehmm = read_ehmm_params(in, ehmm_layout(version));
    for (int* v : {&c.eigen_components, &c.fisher_components, &c.lbph_radius, &c.lbph_neighbors, &c.lbph_grid, &c.num_threads})
        *v = get<int32_t>(in, kWhat);
    NormalizerParams& n = p.normalizer;
    n.output_size.width = get<int32_t>(in, kWhat);
    n.output_size.height = get<int32_t>(in, kWhat);
    n.ellipse_width = get<double>(in, kWhat);
    n.ellipse_height = get<double>(in, kWhat);
    n.elliptical_mask = get<uint8_t>(in, kWhat) != 0;
    n.equalize = get<uint8_t>(in, kWhat) != 0;
    n.vertical_margin = get<double>(in, kWhat);
    p.unknown.min_variance = get<double>(in, kWhat);
    p.unknown.min_score = get<double>(in, kWhat);
    p.unknown.min_margin = get<double>(in, kWhat);
    if (version >= 3) {
        p.training.max_size = std::size_t(get<uint64_t>(in, kWhat));
        p.training.prefer_recent = get<uint8_t>(in, kWhat) != 0;
        p.training.prune_sigma = get<double>(in, kWhat);
        p.training.min_after_pruning = std::size_t(get<uint64_t>(in, kWhat));
    }
    if (version >= 4) {
        const uint8_t training = get<uint8_t>(in, kWhat);
        if (training > uint8_t(EhmmTraining::Adapted))
            throw ModelFormatError("<stream>", "bank with unknown EHMM training " + std::to_string(training));
        c.ehmm_training = EhmmTraining(training);
        c.background_mixtures = get<int32_t>(in, kWhat);
        c.adaptation.relevance = get<double>(in, kWhat);
        c.adaptation.iterations = get<int32_t>(in, kWhat);
        c.adaptation.adapt_variances = get<uint8_t>(in, kWhat) != 0;
        c.adaptation.adapt_weights = get<uint8_t>(in, kWhat) != 0;
        c.adaptation.adapt_transitions = get<uint8_t>(in, kWhat) != 0;
    } else {
        c.ehmm_training = EhmmTraining::Independent;  // how the models of older files were trained
    }
    try {
        p.validate();
    } catch (const std::invalid_argument& e) {
        throw ModelFormatError("<stream>", std::string("bank with invalid parameters: ") + e.what());
    }
    return p;
}

}  // namespace

void ClassifierBank::save(const std::string& path) const {
    std::ostringstream body;
    {
        std::lock_guard lock(impl_->mutex);
        write_params(body, impl_->params);
        put<uint64_t>(body, impl_->people.size());
        for (const Person& p : impl_->people) {
            detail::put_string(body, p.name);
            put<uint64_t>(body, p.version);
            put<uint64_t>(body, p.trained_version);
            put<uint64_t>(body, p.faces.size());
            for (std::size_t i = 0; i < p.faces.size(); ++i) {
                const cv::Mat& f = p.faces[i];
                CV_Assert(f.isContinuous() && f.type() == CV_32FC1);
                detail::put_bytes(body, f.ptr<float>(), f.total() * sizeof(float));
                put<uint8_t>(body, uint8_t(p.provenance[i].source));  // since version 3
                put<double>(body, p.provenance[i].time);
                detail::put_string(body, p.provenance[i].session);
            }
            put<uint8_t>(body, !impl_->joint_kind() && !p.model.empty());
            if (!impl_->joint_kind() && !p.model.empty()) p.model.write(body);
        }
        const bool background = !impl_->joint_kind() && !impl_->background.empty();  // since version 4
        put<uint8_t>(body, background);
        if (background) {
            put<uint64_t>(body, impl_->background_people);
            impl_->background.write(body);
        }
    }
    const std::string payload = body.str();

    const fs::path target(path);
    const fs::path tmp = target.parent_path() / (target.filename().string() + ".tmp-" + std::to_string(::getpid()));
    {
        std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
        if (!out) throw FileError(path, "cannot create the temporary file " + tmp.string());
        out.write(kMagic, sizeof kMagic);
        put<uint32_t>(out, kFormatVersion);
        put<uint64_t>(out, payload.size());
        out.write(payload.data(), std::streamsize(payload.size()));
        put<uint64_t>(out, detail::fnv1a64(payload.data(), payload.size()));
        out.flush();
        if (!out) {
            out.close();
            std::error_code ec;
            fs::remove(tmp, ec);
            throw FileError(path, "writing the bank failed (disk full?); the previous file is unchanged");
        }
    }
    std::error_code ec;
    fs::rename(tmp, target, ec);
    if (ec) {
        fs::remove(tmp, ec);
        throw FileError(path, "cannot replace the bank file: " + ec.message());
    }
}

ClassifierBank ClassifierBank::load(const std::string& path) {
    std::error_code ec;
    if (!fs::is_regular_file(path, ec)) throw FileError(path, "no such bank file");
    std::ifstream in(path, std::ios::binary);
    if (!in) throw FileError(path, "cannot open the bank file");
    const std::string data((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const std::size_t head = sizeof kMagic + sizeof(uint32_t) + sizeof(uint64_t);
    if (data.size() < sizeof kMagic || !std::equal(kMagic, kMagic + sizeof kMagic, data.begin()))
        throw ModelFormatError(path, "not a FaceSocial bank file (wrong magic)");
    if (data.size() < head) throw ModelFormatError(path, "bank file truncated in its header");
    uint32_t version = 0;
    uint64_t size = 0;
    std::memcpy(&version, data.data() + sizeof kMagic, sizeof version);
    std::memcpy(&size, data.data() + sizeof kMagic + sizeof version, sizeof size);
    if (version == 0 || version > kFormatVersion)
        throw ModelFormatError(path, "bank format version " + std::to_string(version) + "; this library reads versions 1 to " +
                                         std::to_string(kFormatVersion));
    if (data.size() - head < size + sizeof(uint64_t))
        throw ModelFormatError(path, "bank file truncated: expected " + std::to_string(head + size + 8) + " bytes, found " +
                                         std::to_string(data.size()));
    if (data.size() - head > size + sizeof(uint64_t))
        throw ModelFormatError(path, "bank file has " + std::to_string(data.size() - head - size - 8) + " trailing bytes");
    uint64_t checksum = 0;
    std::memcpy(&checksum, data.data() + head + size, sizeof checksum);
    if (checksum != detail::fnv1a64(data.data() + head, size))
        throw ModelFormatError(path, "bank file corrupt: checksum mismatch");

    try {
        std::istringstream body(data.substr(head, size));
        ClassifierBank bank(read_params(body, version));
        Impl& m = *bank.impl_;
        const cv::Size face_size = m.params.normalizer.output_size;
        const uint64_t count = get<uint64_t>(body, kWhat);
        if (count > kMaxFaces) throw ModelFormatError("<stream>", "bank with " + std::to_string(count) + " people");
        for (uint64_t i = 0; i < count; ++i) {
            Person p;
            p.name = detail::get_string(body, kWhat, 4096);
            require_name(p.name, "ClassifierBank::load");
            if (m.find(p.name)) throw ModelFormatError("<stream>", "bank lists '" + p.name + "' twice");
            p.version = get<uint64_t>(body, kWhat);
            p.trained_version = get<uint64_t>(body, kWhat);
            const uint64_t n = get<uint64_t>(body, kWhat);
            if (n > kMaxFaces) throw ModelFormatError("<stream>", "bank with " + std::to_string(n) + " faces for one person");
            for (uint64_t k = 0; k < n; ++k) {
                cv::Mat f(face_size, CV_32FC1);
                detail::get_bytes(body, f.ptr<float>(), f.total() * sizeof(float), kWhat);
                if (!cv::checkRange(f)) throw ModelFormatError("<stream>", "bank face of '" + p.name + "' has non-finite pixels");
                p.faces.push_back(f);
                Provenance prov;
                if (version >= 3) {
                    const uint8_t source = get<uint8_t>(body, kWhat);
                    if (source > uint8_t(SampleSource::SocialPhoto))
                        throw ModelFormatError("<stream>", "bank sample of '" + p.name + "' with unknown source " + std::to_string(source));
                    prov.source = SampleSource(source);
                    prov.time = get<double>(body, kWhat);
                    prov.session = detail::get_string(body, kWhat, 4096);
                }
                p.provenance.push_back(std::move(prov));
            }
            if (get<uint8_t>(body, kWhat)) {
                if (m.joint_kind()) throw ModelFormatError("<stream>", "bank holds an EHMM for a joint classifier");
                p.model = EmbeddedHmm::read(body, ehmm_layout(version));
                if (p.model.params().observations.face_size != face_size)
                    throw ModelFormatError("<stream>", "model of '" + p.name + "' is for another face size");
            }
            m.people.push_back(std::move(p));
        }
        if (version >= 4 && get<uint8_t>(body, kWhat)) {
            if (m.joint_kind()) throw ModelFormatError("<stream>", "bank holds an EHMM background for a joint classifier");
            m.background_people = get<uint64_t>(body, kWhat);
            m.background = EmbeddedHmm::read(body, ehmm_layout(version));
            if (m.background.params().observations.face_size != face_size)
                throw ModelFormatError("<stream>", "background model is for another face size");
        }
        if (body.peek() != std::char_traits<char>::eof()) throw ModelFormatError("<stream>", "bank payload has unread bytes");
        if (m.joint_kind()) {
            // The joint models are rebuilt from the saved training sets.
            if (std::any_of(m.people.begin(), m.people.end(), [](const Person& p) { return p.trained_version > 0; }))
                m.train_joint(bank.selector());
        } else {
            m.publish_models();
        }
        return bank;
    } catch (const ModelFormatError& e) {
        if (e.path() == "<stream>") {
            const std::string what = e.what();
            throw ModelFormatError(path, what.substr(what.find(": ") + 2));
        }
        throw;
    } catch (const std::invalid_argument& e) {
        throw ModelFormatError(path, std::string("bank with invalid content: ") + e.what());
    }
}

}  // namespace facesocial
