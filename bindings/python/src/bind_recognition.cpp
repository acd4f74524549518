// Recognition: observations, the embedded HMM's parameters, the pluggable classifiers, the
// classifier bank with its unknown rule, and the open-set threshold analysis.
#include <limits>

#include "common.hpp"
#include "facesocial/classifier_bank.hpp"
#include "facesocial/decision.hpp"
#include "facesocial/face_classifier.hpp"
#include "facesocial/observations.hpp"
#include "facesocial/open_set_eval.hpp"
#include "facesocial/training_set.hpp"

namespace facesocial::python {

namespace {

std::string candidates_repr(const std::vector<Candidate>& c, std::size_t max = 3) {
    std::string s = "[";
    for (std::size_t i = 0; i < c.size() && i < max; ++i) {
        if (i) s += ", ";
        s += c[i].name + ": " + py::repr(py::float_(c[i].score)).cast<std::string>();
    }
    if (c.size() > max) s += ", ...";
    return s + "]";
}

}  // namespace

void bind_recognition(py::module_& m) {
    // --- observations and the embedded HMM's parameters ----------------------------------------
    ParamsClass<ObservationParams>(m, "ObservationParams", "How a face becomes a grid of block-DCT observations.")
        .property(
            "face_size", [](const ObservationParams& p) { return tuple_from_size(p.face_size); },
            [](ObservationParams& p, const py::tuple& t) { p.face_size = size_from_tuple(t, "ObservationParams.face_size"); },
            "(width, height) the face is resized to")
        .field("block_size", &ObservationParams::block_size, "side of the square blocks, pixels")
        .field("block_step", &ObservationParams::block_step, "distance between neighbouring blocks")
        .field("coefficients", &ObservationParams::coefficients, "the n x n lowest DCT frequencies are kept")
        .field("drop_dc", &ObservationParams::drop_dc, "leave out the DC coefficient")
        .done()
        .def_property_readonly("dimension", &ObservationParams::dimension, "length of one observation vector")
        .def_property_readonly(
            "grid", [](const ObservationParams& p) { return tuple_from_size(p.grid()); }, "(columns, rows) of blocks");
    m.def(
        "extract_observations",
        [](const py::array& face, const ObservationParams& params) {
            const cv::Mat img = mat_from_array(face, ArrayKind::Grey, "extract_observations");
            Observations o;
            {
                py::gil_scoped_release release;
                o = extract_observations(img, params);
            }
            return array_from_mat(o.vectors);
        },
        py::arg("face"), py::arg("params") = ObservationParams{},
        "float32 (rows * columns, dimension) observation vectors of a face, row-major over the block grid.");

    ParamsClass<EhmmParams>(m, "EhmmParams", "Topology and training parameters of an embedded HMM.")
        .field("observations", &EhmmParams::observations, "how faces become observation vectors")
        .field("states", &EhmmParams::states, "embedded states of each super-state, top to bottom")
        .field("mixtures", &EhmmParams::mixtures, "diagonal Gaussians per embedded state")
        .field("max_iterations", &EhmmParams::max_iterations, "cap on Viterbi re-estimation rounds")
        .field("tolerance", &EhmmParams::tolerance, "stop when the mean log-likelihood gains less")
        .field("variance_floor", &EhmmParams::variance_floor, "share of the data's variance")
        .field("min_transition", &EhmmParams::min_transition, "transition probabilities kept in [min, 1 - min]")
        .field("recluster_mixtures", &EhmmParams::recluster_mixtures, "re-cluster mixtures by k-means in round 2")
        .done();

    // --- classifiers ---------------------------------------------------------------------------
    py::enum_<ClassifierKind>(m, "ClassifierKind", "Which classifier a FaceClassifier or bank uses.")
        .value("EHMM", ClassifierKind::Ehmm)
        .value("EIGENFACES", ClassifierKind::Eigenfaces)
        .value("FISHERFACES", ClassifierKind::Fisherfaces)
        .value("LBPH", ClassifierKind::Lbph);
    m.def("classifier_kind", &classifier_kind_from_string, py::arg("name"),
          "ClassifierKind from 'ehmm', 'eigen', 'fisher' or 'lbph'.");
    ParamsClass<ClassifierParams>(m, "ClassifierParams", "Parameters of every classifier kind.")
        .field("kind", &ClassifierParams::kind, "the classifier")
        .field("ehmm", &ClassifierParams::ehmm, "EHMM topology and training")
        .field("eigen_components", &ClassifierParams::eigen_components, "Eigenfaces components kept (0 = all)")
        .field("fisher_components", &ClassifierParams::fisher_components, "Fisherfaces discriminants (0 = people - 1)")
        .field("lbph_radius", &ClassifierParams::lbph_radius, "LBPH pattern radius")
        .field("lbph_neighbors", &ClassifierParams::lbph_neighbors, "LBPH sample points")
        .field("lbph_grid", &ClassifierParams::lbph_grid, "LBPH cells per side")
        .field("num_threads", &ClassifierParams::num_threads, "training and scoring threads (-1 = all cores)")
        .done();
    py::class_<FaceClassifier, std::shared_ptr<FaceClassifier>>(
        m, "FaceClassifier", "A classifier over people 0..P-1 (EHMM or an OpenCV face recogniser).")
        .def_static(
            "create", [](const ClassifierParams& p) { return std::shared_ptr<FaceClassifier>(FaceClassifier::create(p)); },
            py::arg("params") = ClassifierParams{})
        .def_property_readonly("name", &FaceClassifier::name)
        .def(
            "train",
            [](FaceClassifier& c, const std::vector<std::vector<py::array>>& faces) {
                std::vector<std::vector<cv::Mat>> in;
                for (std::size_t p = 0; p < faces.size(); ++p)
                    in.push_back(mats_from_list(faces[p], ArrayKind::Grey, "FaceClassifier.train: faces[" + std::to_string(p) + "]"));
                py::gil_scoped_release release;
                c.train(in);
            },
            py::arg("faces"), "Trains on faces[p] = person p's normalised faces (2-D uint8 or float32 arrays).")
        .def(
            "scores",
            [](const FaceClassifier& c, const py::array& face) {
                const cv::Mat f = mat_from_array(face, ArrayKind::Grey, "FaceClassifier.scores");
                std::vector<double> s;
                {
                    py::gil_scoped_release release;
                    s = c.scores(f);
                }
                return array_from_vector(s);
            },
            py::arg("face"), "float64 score per person, higher = more alike.")
        .def("__len__", &FaceClassifier::size)
        .def("__repr__", [](const FaceClassifier& c) {
            return "FaceClassifier('" + c.name() + "', " + std::to_string(c.size()) + " people)";
        });

    // --- decisions -----------------------------------------------------------------------------
    ParamsClass<UnknownRule>(m, "UnknownRule", "Thresholds of the unknown rule; any enabled test makes a face unknown.")
        .field("min_variance", &UnknownRule::min_variance, "unknown when the score variance is below (0 = off)")
        .field("min_score", &UnknownRule::min_score, "unknown when the best score is below (-inf = off)")
        .field("min_margin", &UnknownRule::min_margin, "unknown when best - runner-up is below (0 = off)")
        .done();
    py::class_<Candidate>(m, "Candidate", "One person's standing for a face.")
        .def_readonly("name", &Candidate::name)
        .def_readonly("score", &Candidate::score)
        .def("__repr__", [](const Candidate& c) {
            return "Candidate('" + c.name + "', " + py::repr(py::float_(c.score)).cast<std::string>() + ")";
        });
    py::class_<Decision>(m, "Decision", "The outcome for one face.")
        .def_readonly("known", &Decision::known, "False: nobody enrolled, or the unknown rule fired")
        .def_readonly("name", &Decision::name, "the winner when known, '' otherwise")
        .def_readonly("score", &Decision::score, "the best score")
        .def_readonly("variance", &Decision::variance, "variance of the score vector")
        .def_readonly("margin", &Decision::margin, "best minus second-best score")
        .def_readonly("ranked", &Decision::ranked, "everyone, best first")
        .def("__bool__", [](const Decision& d) { return d.known; })
        .def("__repr__", [](const Decision& d) {
            return std::string("Decision(") + (d.known ? "'" + d.name + "'" : "unknown") +
                   ", ranked=" + candidates_repr(d.ranked) + ")";
        });
    m.def("score_variance", &score_variance, py::arg("scores"));
    m.def("rank_candidates", &rank_candidates, py::arg("names"), py::arg("scores"), py::arg("top_k") = 0,
          "The top_k best candidates (0 = all), ties by name.");
    m.def("decide", py::overload_cast<const std::vector<std::string>&, const std::vector<double>&, const UnknownRule&>(&decide),
          py::arg("names"), py::arg("scores"), py::arg("rule") = UnknownRule{}, "Ranks and applies the unknown rule.");

    // --- training sets -------------------------------------------------------------------------
    py::enum_<SampleSource>(m, "SampleSource").value("CAMERA", SampleSource::Camera).value("SOCIAL_PHOTO", SampleSource::SocialPhoto);
    py::class_<TrainingSample>(m, "TrainingSample", "A normalised face with its provenance.")
        .def(py::init([](const py::array& face, SampleSource source, double time, std::string session) {
                 return TrainingSample{mat_from_array(face, ArrayKind::Grey, "TrainingSample").clone(), source, time,
                                       std::move(session)};
             }),
             py::arg("face"), py::arg("source") = SampleSource::Camera, py::arg("capture_time") = 0.0,
             py::arg("session") = "")
        .def_property_readonly("face", [](const TrainingSample& s) { return array_from_mat(s.face); })
        .def_readwrite("source", &TrainingSample::source)
        .def_readwrite("capture_time", &TrainingSample::capture_time)
        .def_readwrite("session", &TrainingSample::session);
    ParamsClass<TrainingPolicy>(m, "TrainingPolicy", "Which samples train a person's classifier.")
        .field("max_size", &TrainingPolicy::max_size, "cap (0 = all)")
        .field("prefer_recent", &TrainingPolicy::prefer_recent, "over the cap: newest (True) or spread over time")
        .field("prune_sigma", &TrainingPolicy::prune_sigma, "outlier pruning threshold in robust deviations (0 = off)")
        .field("min_after_pruning", &TrainingPolicy::min_after_pruning, "never prune below this")
        .done();
    py::class_<SelectionReport>(m, "SelectionReport")
        .def_readonly("kept", &SelectionReport::kept)
        .def_readonly("pruned", &SelectionReport::pruned)
        .def_readonly("capped", &SelectionReport::capped);
    m.def(
        "select_training_samples",
        [](const std::vector<TrainingSample>& samples, const TrainingPolicy& policy, const EhmmParams& ehmm,
           const std::shared_ptr<ClassifierBank>& others, const std::string& person) {
            py::gil_scoped_release release;
            return select_training_samples(samples, policy, ehmm, others.get(), person);
        },
        py::arg("samples"), py::arg("policy") = TrainingPolicy{}, py::arg("ehmm") = EhmmParams{}, py::arg("others") = nullptr,
        py::arg("person") = "");

    // --- the bank ------------------------------------------------------------------------------
    ParamsClass<ClassifierBankParams>(m, "ClassifierBankParams", "Everything that shapes a bank; saved with it.")
        .field("classifier", &ClassifierBankParams::classifier, "the classifier kind and its parameters")
        .field("normalizer", &ClassifierBankParams::normalizer, "how normalize() prepares faces")
        .field("unknown", &ClassifierBankParams::unknown, "the rule decide() applies")
        .field("training", &ClassifierBankParams::training, "which samples train a person's model (TrainingPolicy)")
        .done();
    py::class_<BankScores>(m, "BankScores", "Scores of one face against the trained people.")
        .def(py::init([](std::vector<std::string> names, std::vector<double> scores) {
                 if (names.size() != scores.size())
                     throw std::invalid_argument("BankScores: expected as many scores as names, got " +
                                                 std::to_string(scores.size()) + " for " + std::to_string(names.size()));
                 return BankScores{std::move(names), std::move(scores)};
             }),
             py::arg("names"), py::arg("scores"))
        .def_readonly("names", &BankScores::names)
        .def_property_readonly("scores", [](const BankScores& s) { return array_from_vector(s.scores); }, "float64 array")
        .def("__len__", [](const BankScores& s) { return s.names.size(); })
        .def("__repr__", [](const BankScores& s) { return "BankScores(" + std::to_string(s.names.size()) + " people)"; });

    py::class_<ClassifierBank, std::shared_ptr<ClassifierBank>>(m, "ClassifierBank",
                               "Per-person training sets and classifiers; scoring, ranking, the unknown rule, "
                               "one checksummed file. Every method may be called from several threads.")
        .def(py::init<const ClassifierBankParams&>(), py::arg("params") = ClassifierBankParams{})
        .def_property_readonly("params", &ClassifierBank::params)
        .def_property("unknown_rule", &ClassifierBank::unknown_rule, &ClassifierBank::set_unknown_rule)
        .def(
            "normalize",
            [](const ClassifierBank& b, const py::array& image, const std::optional<py::tuple>& box) {
                const cv::Mat img = mat_from_array(image, ArrayKind::Image, "ClassifierBank.normalize");
                const std::optional<cv::Rect> r =
                    box ? std::optional<cv::Rect>(rect_from_tuple(*box, "ClassifierBank.normalize")) : std::nullopt;
                cv::Mat f;
                {
                    py::gil_scoped_release release;
                    f = r ? b.normalize(img, *r) : b.normalize(img);
                }
                return array_from_mat(f);
            },
            py::arg("image"), py::arg("box") = py::none(),
            "The bank's normalised float32 face of a uint8 image (whole image, or the (x, y, w, h) box).")
        .def("add_person", &ClassifierBank::add_person, py::arg("name"))
        .def(
            "add_faces",
            [](ClassifierBank& b, const std::string& name, const std::vector<py::array>& faces) {
                const std::vector<cv::Mat> in = mats_from_list(faces, ArrayKind::Grey, "ClassifierBank.add_faces");
                py::gil_scoped_release release;
                b.add_faces(name, in);
            },
            py::arg("name"), py::arg("faces"), "Appends normalised faces (copied), creating the person if needed.")
        .def(
            "add_samples",
            [](ClassifierBank& b, const std::string& name, const std::vector<TrainingSample>& samples) {
                py::gil_scoped_release release;
                b.add_samples(name, samples);
            },
            py::arg("name"), py::arg("samples"), "Appends TrainingSamples with their provenance.")
        .def("samples", &ClassifierBank::samples, py::arg("name"), "The person's samples with their provenance.")
        .def("selection", &ClassifierBank::selection, py::arg("name"),
             "Which samples the current model was trained from (a SelectionReport).")
        .def("clear_faces", &ClassifierBank::clear_faces, py::arg("name"))
        .def("remove_person", &ClassifierBank::remove_person, py::arg("name"))
        .def("__contains__", &ClassifierBank::contains)
        .def("__len__", [](const ClassifierBank& b) { return b.people().size(); })
        .def_property_readonly("people", &ClassifierBank::people, "everyone with a training set, in enrolment order")
        .def("face_count", &ClassifierBank::face_count, py::arg("name"))
        .def(
            "faces", [](const ClassifierBank& b, const std::string& name) { return list_from_mats(b.faces(name)); },
            py::arg("name"), "Copies of the person's normalised training faces.")
        .def(
            "train",
            [](ClassifierBank& b, const std::optional<std::string>& name) {
                py::gil_scoped_release release;
                if (!name) return b.train();
                b.train(*name);
                return std::vector<std::string>{*name};
            },
            py::arg("name") = py::none(), "Retrains one person, or (None) everyone stale in parallel; returns who.")
        .def("is_trained", &ClassifierBank::is_trained, py::arg("name"))
        .def_property_readonly("trained_people", &ClassifierBank::trained_people)
        .def_property_readonly("stale", &ClassifierBank::stale)
        .def(
            "scores",
            [](const ClassifierBank& b, const py::array& face) {
                const cv::Mat f = mat_from_array(face, ArrayKind::Grey, "ClassifierBank.scores");
                py::gil_scoped_release release;
                return b.scores(f);
            },
            py::arg("face"), "Scores of a normalised face against every trained person.")
        .def(
            "rank",
            [](const ClassifierBank& b, const py::array& face, std::size_t top_k) {
                const cv::Mat f = mat_from_array(face, ArrayKind::Grey, "ClassifierBank.rank");
                py::gil_scoped_release release;
                return b.rank(f, top_k);
            },
            py::arg("face"), py::arg("top_k") = 0, "The top_k best candidates (0 = all), best first.")
        .def(
            "decide",
            [](const ClassifierBank& b, const py::array& face) {
                const cv::Mat f = mat_from_array(face, ArrayKind::Grey, "ClassifierBank.decide");
                py::gil_scoped_release release;
                return b.decide(f);
            },
            py::arg("face"), "Ranked candidates and the decision under the bank's unknown rule.")
        .def(
            "decide_scores", [](const ClassifierBank& b, const BankScores& s) { return b.decide(s); }, py::arg("scores"),
            "The same for a score vector computed elsewhere (e.g. accumulated over frames).")
        .def(
            "save",
            [](const ClassifierBank& b, const std::filesystem::path& path) {
                py::gil_scoped_release release;
                b.save(path.string());
            },
            py::arg("path"), "Atomic write (temporary file + rename). Raises FileError.")
        .def_static(
            "load",
            [](const std::filesystem::path& path) {
                py::gil_scoped_release release;
                return ClassifierBank::load(path.string());
            },
            py::arg("path"), "Raises FileError, or ModelFormatError for a truncated, corrupt, foreign or newer file.")
        .def_readonly_static("FORMAT_VERSION", &ClassifierBank::kFormatVersion)
        .def("__repr__", [](const ClassifierBank& b) {
            return "ClassifierBank(" + to_string(b.params().classifier.kind) + ", " + std::to_string(b.people().size()) +
                   " people, " + std::to_string(b.trained_people().size()) + " trained)";
        });

    // --- open-set threshold analysis -----------------------------------------------------------
    m.def("acceptance_rate", &acceptance_rate, py::arg("stats"), py::arg("threshold"), "Share of stats >= threshold.");
    m.def("threshold_for_acceptance", &threshold_for_acceptance, py::arg("known"), py::arg("share"),
          "The highest threshold accepting at least `share` of `known`.");
    m.def(
        "equal_error_rate",
        [](const std::vector<double>& known, const std::vector<double>& unknown) {
            const EqualErrorRate e = equal_error_rate(known, unknown);
            return py::make_tuple(e.threshold, e.rate);
        },
        py::arg("known"), py::arg("unknown"), "(threshold, rate) where false rejects of known = false accepts of unknown.");
}

}  // namespace facesocial::python
