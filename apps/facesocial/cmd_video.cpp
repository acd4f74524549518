// facesocial watch (the live pipeline on a camera, file, stream or frame folder) and the video
// evaluations: eval window (paper Fig. 3), eval threshold (Fig. 2), eval throughput.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <numeric>

#include <opencv2/imgproc.hpp>
#include <opencv2/videoio.hpp>

#include "cli.hpp"
#include "commands.hpp"
#include "facesocial/classifier_bank.hpp"
#include "facesocial/datasets.hpp"
#include "facesocial/error.hpp"
#include "facesocial/evidence_accumulator.hpp"
#include "facesocial/face_augment.hpp"
#include "facesocial/front_end.hpp"
#include "facesocial/image_io.hpp"
#include "facesocial/open_set_eval.hpp"
#include "facesocial/pipeline_runner.hpp"
#include "facesocial/vision_pipeline.hpp"
#include "plot.hpp"

namespace facesocial::cli {

namespace fs = std::filesystem;

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

// ---------------------------------------------------------------------------------------------
// watch

std::string event_json(const PipelineEvent& e) {
    JsonObject o;
    o.add("event", to_string(e.kind)).add("frame", long(e.frame)).add("time", e.timestamp);
    if (e.track_id) o.add("track", e.track_id);
    switch (e.kind) {
    case PipelineEventKind::DecisionMade:
    case PipelineEventKind::DecisionChanged:
        o.add("name", e.name.empty() ? std::string("unknown") : e.name).add("score", e.score).add("frames", e.frames);
        if (e.kind == PipelineEventKind::DecisionChanged)
            o.add("previous", e.previous.empty() ? std::string("unknown") : e.previous);
        break;
    case PipelineEventKind::TrackLost:
        o.add("name", e.name.empty() ? std::string("unknown") : e.name).add("frames", e.frames);
        break;
    case PipelineEventKind::FrameSkipped:
    case PipelineEventKind::StreamEnded:
    case PipelineEventKind::SourceLost: o.add("message", e.message); break;
    case PipelineEventKind::TrackStarted: break;
    }
    return o.str();
}

void annotate(cv::Mat& frame, const PipelineResult& r, int min_frames) {
    for (const TrackReport& t : r.tracks) {
        if (!t.seen) continue;
        const bool decided = t.frames >= min_frames;
        const cv::Scalar colour = !decided ? cv::Scalar(0, 220, 255) : t.decision.known ? cv::Scalar(60, 200, 60)
                                                                                         : cv::Scalar(40, 40, 230);
        cv::rectangle(frame, t.detection.box, colour, 2);
        std::string label = "#" + std::to_string(t.track_id) + " ";
        if (!decided)
            label += "...";
        else if (t.decision.known) {
            char buf[64];
            std::snprintf(buf, sizeof buf, " %.2f", std::isfinite(t.decision.margin) ? t.decision.margin : 0.0);
            label += t.decision.name + buf;
        } else
            label += "unknown";
        const cv::Point at(t.detection.box.x, std::max(14, t.detection.box.y - 6));
        cv::putText(frame, label, at, cv::FONT_HERSHEY_SIMPLEX, 0.5, cv::Scalar(0, 0, 0), 3, cv::LINE_AA);
        cv::putText(frame, label, at, cv::FONT_HERSHEY_SIMPLEX, 0.5, colour, 1, cv::LINE_AA);
    }
}

void progress(const VideoSource& source, long long frames, double fps, std::size_t tracks) {
    if (source.frame_count() > 0) {
        const double share = std::min(1.0, double(frames) / double(source.frame_count()));
        const int bar = int(share * 30);
        std::cerr << "\r[" << std::string(std::size_t(bar), '#') << std::string(std::size_t(30 - bar), ' ') << "] " << frames
                  << "/" << source.frame_count() << " frames, " << std::fixed << std::setprecision(1) << fps << " fps   "
                  << std::flush;
    } else {
        std::cerr << "\rframe " << frames << ", " << std::fixed << std::setprecision(1) << fps << " fps, " << tracks
                  << " faces   " << std::flush;
    }
}

}  // namespace

int cmd_watch(const std::vector<std::string>& argv) {
    const Args args(argv, {"--bank", "--window", "--out", "--events", "--max-frames", "--mode"},
                    {"--json", "--profile", "--quiet"});
    if (!args.has("--bank") || args.positional().size() != 1)
        throw UsageError("watch: expected --bank FILE and one SOURCE (camera index, video file, URL or frame folder)");
    auto bank = std::make_shared<ClassifierBank>(ClassifierBank::load(args.get("--bank")));
    if (bank->trained_people().empty()) throw std::invalid_argument("watch: the bank has nobody trained (facesocial train)");
    PipelineParams params;
    params.accumulator.window = args.get_int("--window", params.accumulator.window);
    if (args.has("--mode")) params.accumulator.mode = accumulation_mode_from_string(args.get("--mode"));
    params.front_end.use_profile = args.flag("--profile");
    auto pipeline = std::make_shared<VisionPipeline>(bank, params);
    auto source = VideoSource::open(args.positional()[0]);
    const VideoSource& src = *source;
    const double fps_out = src.fps() > 0 ? src.fps() : 5.0;
    const long long max_frames = args.get_int("--max-frames", 0);
    const bool json = args.flag("--json"), quiet = args.flag("--quiet") || json;

    std::ofstream events;
    if (args.has("--events")) {
        events.open(args.get("--events"));
        if (!events) throw FileError(args.get("--events"), "cannot write the events file");
    }
    cv::VideoWriter writer;
    RunnerParams rp;
    if (!src.is_live()) rp.result_queue = 64;  // a file: keep up to 64 results for the writer
    if (!quiet) std::cerr << "watch: " << src.description() << ", " << bank->trained_people().size() << " people\n";
    PipelineRunner runner(pipeline, std::move(source), rp);

    const auto t0 = Clock::now();
    long long frames = 0, faces = 0;
    std::set<int> tracks;
    std::map<std::string, int> decisions;
    PipelineResult r;
    std::string end_message;
    cv::Size out_size;
    while (!runner.finished()) {
        if (!runner.next(r, std::chrono::milliseconds(500))) continue;
        for (const PipelineEvent& e : r.events) {
            if (events.is_open()) events << event_json(e) << "\n";
            if (e.kind == PipelineEventKind::TrackStarted) tracks.insert(e.track_id);
            if (e.kind == PipelineEventKind::DecisionMade || e.kind == PipelineEventKind::DecisionChanged)
                ++decisions[e.name.empty() ? "unknown" : e.name];
            if (e.kind == PipelineEventKind::StreamEnded || e.kind == PipelineEventKind::SourceLost) end_message = e.message;
        }
        if (r.status != FrameStatus::Ok) continue;
        ++frames;
        faces += r.faces_detected;
        if (args.has("--out")) {
            cv::Mat canvas;
            if (r.image.channels() == 1)
                cv::cvtColor(r.image, canvas, cv::COLOR_GRAY2BGR);
            else
                canvas = r.image.clone();
            annotate(canvas, r, params.min_frames);
            if (!writer.isOpened()) {
                out_size = canvas.size();
                writer.open(args.get("--out"), cv::VideoWriter::fourcc('m', 'p', '4', 'v'), fps_out, out_size);
                if (!writer.isOpened()) throw FileError(args.get("--out"), "cannot write the video (mp4v codec)");
            }
            if (canvas.size() != out_size) cv::resize(canvas, canvas, out_size);  // frame folders may mix sizes
            writer.write(canvas);
        }
        if (!quiet && frames % 5 == 0) progress(src, frames, double(frames) / seconds_since(t0), r.tracks.size());
        if (max_frames > 0 && frames >= max_frames) runner.stop();
    }
    if (auto err = runner.error()) std::rethrow_exception(err);
    writer.release();
    const double wall = seconds_since(t0);
    const RunnerStats st = runner.stats();
    if (!quiet) std::cerr << "\n";
    JsonObject summary;
    summary.add("frames", long(frames)).add("faces", long(faces)).add("tracks", tracks.size()).add("seconds", wall);
    summary.add("fps", wall > 0 ? frames / wall : 0.0).add("frames_dropped", long(st.frames_dropped));
    summary.add("results_dropped", long(st.results_dropped));
    JsonObject dec;
    for (const auto& [name, n] : decisions) dec.add(name, n);
    summary.add("decisions", dec);
    if (!end_message.empty()) summary.add("end", end_message);
    if (json)
        std::cout << summary.str() << "\n";
    else
        std::cout << frames << " frames, " << faces << " faces, " << tracks.size() << " tracks, " << std::fixed
                  << std::setprecision(1) << (wall > 0 ? frames / wall : 0.0) << " fps" << (st.frames_dropped ? ", " : "")
                  << (st.frames_dropped ? std::to_string(st.frames_dropped) + " frames dropped to stay live" : "") << "\n";
    return 0;
}

// ---------------------------------------------------------------------------------------------
// Shared by the evaluations

namespace {

/// One person's probe sequence: per-frame scores against a bank, in frame order.
struct Sequence {
    std::string truth;  ///< enrolled name, or "" for a stranger
    std::vector<BankScores> frames;
};

ClassifierBank cropped_bank() {
    ClassifierBankParams p;
    p.normalizer = NormalizerParams::cropped();
    return ClassifierBank(p);
}

Sequence score_sequence(const ClassifierBank& bank, const std::string& truth, const std::vector<cv::Mat>& faces) {
    Sequence s;
    s.truth = truth;
    for (const cv::Mat& f : faces) s.frames.push_back(bank.scores(f));
    return s;
}

/// Share of frames whose running decision (accumulated from the start of the sequence within
/// the window) names the right person.
double running_accuracy(const std::vector<Sequence>& seqs, const AccumulatorParams& ap) {
    int ok = 0, total = 0;
    for (const Sequence& s : seqs) {
        EvidenceAccumulator acc(ap);
        for (const BankScores& f : s.frames) {
            acc.add(f);
            const Decision d = acc.decide({});
            ok += d.known && d.name == s.truth;
            ++total;
        }
    }
    return total ? double(ok) / total : 0.0;
}

AccumulatorParams accumulator(AccumulationMode mode, int window) {
    AccumulatorParams ap;
    ap.mode = mode;
    ap.window = window;
    ap.decay = double(window - 1) / double(window + 1);  // the same mean age of evidence as the window
    return ap;
}

fs::path out_dir(const Args& args) {
    const fs::path dir = args.get("--out", ".");
    std::error_code ec;
    fs::create_directories(dir, ec);
    if (!fs::is_directory(dir, ec)) throw FileError(dir.string(), "(--out) cannot be created");
    return dir;
}

/// Essex faces94 subset through the front end (frontal detector, skin filter, elliptical mask),
/// as the robot would see it: each person's train then test images in natural order, frames
/// without a detected face dropped; the first `enrol` faces are enrolled, the rest is the
/// sequence.
struct EssexSplit {
    std::vector<std::string> names;
    std::vector<std::vector<cv::Mat>> enrol, sequence;
    int images = 0, without_face = 0;
};

EssexSplit essex_split(const fs::path& root, std::size_t enrol) {
    const FrontEnd front_end;
    EssexSplit out;
    const auto test = load_identity_folders(root / "essex_faces94_subset" / "test");
    for (const PersonImages& p : load_identity_folders(root / "essex_faces94_subset" / "train")) {
        std::vector<fs::path> files = p.images;
        for (const PersonImages& t : test)
            if (t.name == p.name) files.insert(files.end(), t.images.begin(), t.images.end());
        std::vector<cv::Mat> faces;
        for (const fs::path& f : files) {
            ++out.images;
            const FrontEndResult r = front_end.process(load_image(f));
            if (r.faces.empty()) {
                ++out.without_face;
                continue;
            }
            faces.push_back(r.faces.front().face.pixels);
        }
        if (faces.size() <= enrol) continue;
        out.names.push_back(p.name);
        out.enrol.emplace_back(faces.begin(), faces.begin() + long(enrol));
        out.sequence.emplace_back(faces.begin() + long(enrol), faces.end());
    }
    return out;
}

ClassifierBank masked_bank() { return ClassifierBank(ClassifierBankParams{}); }

/// A probe frame as a robot a few metres away sees it: small random pose and lighting changes
/// (augment_faces with twice its default ranges), the face at `pixels` wide (blur of distance),
/// and sensor noise. Deterministic for a seed.
std::vector<cv::Mat> far_away(const std::vector<cv::Mat>& faces, int pixels, uint32_t seed) {
    AugmentParams ap;
    ap.max_rotation_deg *= 2, ap.max_shift *= 2, ap.max_scale *= 2, ap.max_gain *= 2, ap.max_bias *= 2;
    ap.mirror = false;
    std::vector<cv::Mat> out = augment_faces(faces, faces.size() * 2, ap, seed);
    out.erase(out.begin(), out.begin() + long(faces.size()));  // only the varied copies
    cv::RNG rng(seed);
    for (cv::Mat& f : out) {
        cv::Mat small, noise(f.size(), CV_32F);
        cv::resize(f, small, {pixels, pixels * f.rows / f.cols}, 0, 0, cv::INTER_AREA);
        cv::resize(small, f, f.size(), 0, 0, cv::INTER_LINEAR);
        rng.fill(noise, cv::RNG::NORMAL, 0, 0.35);
        f += noise;
    }
    return out;
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// eval window: accuracy against the evidence window (paper Fig. 3)

int cmd_eval_window(const std::vector<std::string>& argv) {
    const Args args(argv, {"--data", "--out", "--enrol", "--far"}, {"--json"});
    const fs::path root = data_dir(args.get("--data"));
    const bool json = args.flag("--json");
    const int enrol = args.get_int("--enrol", 1);
    if (enrol < 1 || enrol > 8) throw UsageError("eval window: expected --enrol in [1, 8]");
    const std::vector<int> windows{1, 2, 3, 4, 5, 6, 8, 10, 12, 15, 20, 25, 30, 35, 40, 45, 50};
    const std::vector<AccumulationMode> modes{AccumulationMode::MovingAverage, AccumulationMode::ExponentialDecay,
                                              AccumulationMode::MajorityVote};

    // Essex: real talking sequences.
    const EssexSplit essex = essex_split(root, std::size_t(enrol));
    ClassifierBank essex_bank = masked_bank();
    for (std::size_t p = 0; p < essex.names.size(); ++p) essex_bank.add_faces(essex.names[p], essex.enrol[p]);
    essex_bank.train();
    std::vector<Sequence> essex_seqs;
    std::size_t essex_frames = 0;
    const int far = args.get_int("--far", 16);
    for (std::size_t p = 0; p < essex.names.size(); ++p) {
        const auto seq = far > 0 ? far_away(essex.sequence[p], far, uint32_t(7 + p)) : essex.sequence[p];
        essex_seqs.push_back(score_sequence(essex_bank, essex.names[p], seq));
        essex_frames += seq.size();
    }

    // ORL: the held-out images of each person, grown to 50 frames with small augmentations.
    const FaceSet orl = load_cropped_faces(root / "orl");
    ClassifierBank orl_bank = cropped_bank();
    for (std::size_t p = 0; p < orl.names.size(); ++p)
        orl_bank.add_faces(orl.names[p], {orl.faces[p].begin(), orl.faces[p].begin() + enrol});
    orl_bank.train();
    std::vector<Sequence> orl_seqs;
    for (std::size_t p = 0; p < orl.names.size(); ++p) {
        const std::vector<cv::Mat> held(orl.faces[p].begin() + enrol, orl.faces[p].end());
        std::vector<cv::Mat> seq = augment_faces(held, 50, AugmentParams{}, uint32_t(100 + p));
        for (cv::Mat& f : seq) f = orl_bank.normalize(FaceNormalizer::to_8bit({f, cv::Mat(f.size(), CV_8U, cv::Scalar(255))}));
        orl_seqs.push_back(score_sequence(orl_bank, orl.names[p], seq));
    }

    Chart chart;
    chart.title = "Accuracy vs evidence window (" + std::to_string(enrol) + " enrolment image(s) per person)";
    chart.x_label = "window (frames)";
    chart.y_label = "accuracy";
    chart.y_min = 0.5;
    for (int w : windows) chart.x.push_back(w);
    JsonObject result;
    result.add("enrol_per_person", enrol).add("essex_people", essex.names.size()).add("essex_frames", essex_frames);
    result.add("essex_images", essex.images).add("essex_images_without_face", essex.without_face);
    result.add("orl_people", orl.names.size()).add("orl_frames", orl.names.size() * 50);
    std::vector<JsonObject> curves;
    for (const auto& [set, seqs] : {std::pair<std::string, const std::vector<Sequence>*>{"essex", &essex_seqs},
                                    std::pair<std::string, const std::vector<Sequence>*>{"orl", &orl_seqs}}) {
        for (AccumulationMode m : modes) {
            Series s{set + " " + to_string(m), {}};
            for (int w : windows) s.y.push_back(running_accuracy(*seqs, accumulator(m, w)));
            JsonObject c;
            c.add("set", set).add("mode", to_string(m)).add("accuracy", s.y);
            curves.push_back(c);
            chart.series.push_back(s);
        }
    }
    std::vector<double> wx(windows.begin(), windows.end());
    result.add("windows", wx).add("curves", curves);
    const fs::path dir = out_dir(args);
    write_csv(dir / "window.csv", chart);
    write_png(dir / "window.png", chart);
    if (!json) {
        std::cout << "Essex: " << essex.names.size() << " people enrolled from " << enrol << " detected face(s), "
                  << essex_frames << " sequence frames (" << essex.without_face << " of " << essex.images
                  << " images without a detected face); ORL: 40 people enrolled from " << enrol << " image(s), 50-frame sequences\n"
                  << std::left << std::setw(16) << "curve";
        for (int w : windows) std::cout << std::right << std::setw(6) << w;
        std::cout << "\n";
        for (const Series& s : chart.series) {
            std::cout << std::left << std::setw(16) << s.label << std::right << std::fixed << std::setprecision(3);
            for (double v : s.y) std::cout << std::setw(6) << std::setprecision(1) << v * 100;
            std::cout << "\n";
        }
        std::cout << "wrote " << (dir / "window.csv").string() << " and " << (dir / "window.png").string() << "\n";
    } else {
        std::cout << result.str() << "\n";
    }
    return 0;
}

// ---------------------------------------------------------------------------------------------
// eval threshold: accuracy and false positives against the unknown threshold (paper Fig. 2)

namespace {

struct Probe {
    double stat;   // the statistic of the (frame or accumulated) score vector
    bool correct;  // known probe: the winner is the right person
};

double statistic(const Decision& d, int which) {
    return which == 0 ? d.variance : which == 1 ? d.score : d.margin;
}

/// Per-frame and accumulated probes of known and stranger sequences, for one statistic.
void collect(const std::vector<Sequence>& seqs, int which, int window, std::vector<Probe>& known_frame,
             std::vector<Probe>& known_acc, std::vector<double>& unknown_frame, std::vector<double>& unknown_acc) {
    for (const Sequence& s : seqs) {
        EvidenceAccumulator acc(accumulator(AccumulationMode::MovingAverage, window));
        for (const BankScores& f : s.frames) {
            acc.add(f);
            const Decision one = decide(f.names, f.scores, {});
            const Decision many = acc.decide({});
            if (s.truth.empty()) {
                unknown_frame.push_back(statistic(one, which));
                unknown_acc.push_back(statistic(many, which));
            } else {
                known_frame.push_back({statistic(one, which), one.name == s.truth});
                known_acc.push_back({statistic(many, which), many.name == s.truth});
            }
        }
    }
}

double correct_and_accepted(const std::vector<Probe>& p, double t) {
    int n = 0;
    for (const Probe& x : p) n += x.correct && x.stat >= t;
    return p.empty() ? 0 : double(n) / double(p.size());
}

}  // namespace

int cmd_eval_threshold(const std::vector<std::string>& argv) {
    const Args args(argv, {"--data", "--out", "--window"}, {"--json"});
    const fs::path root = data_dir(args.get("--data"));
    const bool json = args.flag("--json");
    const int window = args.get_int("--window", 25);
    if (window < 1) throw UsageError("eval threshold: expected --window >= 1");

    // ORL: 35 enrolled (images 1-5), 5 strangers (all 10 images), rotated through 8 groups.
    const FaceSet orl = load_cropped_faces(root / "orl");
    std::vector<Sequence> orl_seqs;
    for (std::size_t g = 0; g < 8; ++g) {
        ClassifierBank bank = cropped_bank();
        for (std::size_t p = 0; p < 40; ++p)
            if (p / 5 != g) bank.add_faces(orl.names[p], {orl.faces[p].begin(), orl.faces[p].begin() + 5});
        bank.train();
        for (std::size_t p = 0; p < 40; ++p)
            orl_seqs.push_back(p / 5 == g ? score_sequence(bank, "", orl.faces[p])
                                          : score_sequence(bank, orl.names[p], {orl.faces[p].begin() + 5, orl.faces[p].end()}));
    }
    // Essex: 18 enrolled from 4 frames each; the rest of each sequence is known; the unlabelled
    // person11 (4 frames) and five single images of other people are strangers.
    const EssexSplit essex = essex_split(root, 4);
    ClassifierBank essex_bank = masked_bank();
    for (std::size_t p = 0; p < essex.names.size(); ++p) essex_bank.add_faces(essex.names[p], essex.enrol[p]);
    essex_bank.train();
    std::vector<Sequence> essex_seqs;
    for (std::size_t p = 0; p < essex.names.size(); ++p)
        essex_seqs.push_back(score_sequence(essex_bank, essex.names[p], essex.sequence[p]));
    const fs::path unlabelled = root / "essex_faces94_subset" / "unlabelled";
    {
        const FrontEnd front_end;
        auto faces_of = [&](const std::vector<fs::path>& files) {
            std::vector<cv::Mat> faces;
            for (const fs::path& f : files) {
                const FrontEndResult r = front_end.process(load_image(f));
                if (!r.faces.empty()) faces.push_back(r.faces.front().face.pixels);
            }
            return faces;
        };
        essex_seqs.push_back(score_sequence(essex_bank, "", faces_of(list_images(unlabelled / "person11"))));
        for (const fs::path& f : list_images(unlabelled))
            if (auto one = faces_of({f}); !one.empty()) essex_seqs.push_back(score_sequence(essex_bank, "", one));
    }

    const char* stat_names[] = {"variance", "min_score", "min_margin"};
    const char* stat_fields[] = {"min_variance", "min_score", "min_margin"};
    const fs::path dir = out_dir(args);
    JsonObject result;
    result.add("window", window);
    std::vector<JsonObject> rows;
    if (!json)
        std::cout << "threshold keeping 95% of known frames accepted (per frame); window " << window << "\n"
                  << std::left << std::setw(7) << "set" << std::setw(13) << "rule" << std::right << std::setw(10)
                  << "threshold" << std::setw(12) << "acc frame" << std::setw(12) << "acc accum" << std::setw(11)
                  << "FP frame" << std::setw(11) << "FP accum" << std::setw(11) << "EER frame" << std::setw(11) << "EER accum"
                  << "\n";
    for (const auto& [set, seqs] : {std::pair<std::string, const std::vector<Sequence>*>{"orl", &orl_seqs},
                                    std::pair<std::string, const std::vector<Sequence>*>{"essex", &essex_seqs}}) {
        for (int which = 0; which < 3; ++which) {
            std::vector<Probe> kf, ka;
            std::vector<double> uf, ua;
            collect(*seqs, which, window, kf, ka, uf, ua);
            std::vector<double> kf_stats, ka_stats;
            for (const Probe& p : kf) kf_stats.push_back(p.stat);
            for (const Probe& p : ka) ka_stats.push_back(p.stat);
            const double chosen = threshold_for_acceptance(kf_stats, 0.95);
            // Curves over the thresholds spanned by all probes.
            std::vector<double> all = kf_stats;
            all.insert(all.end(), uf.begin(), uf.end());
            std::sort(all.begin(), all.end());
            const double lo = all[all.size() / 100], hi = all[all.size() - 1 - all.size() / 100];
            Chart chart;
            chart.title = set + ": " + stat_names[which] + " threshold (window " + std::to_string(window) + ")";
            chart.x_label = std::string(stat_fields[which]) + " threshold";
            chart.y_label = "share of probes";
            Series acc_f{"accuracy, frame", {}}, acc_a{"accuracy, accumulated", {}}, fp_f{"false pos., frame", {}},
                fp_a{"false pos., accumulated", {}};
            for (int i = 0; i <= 40; ++i) {
                const double t = lo + (hi - lo) * i / 40;
                chart.x.push_back(t);
                acc_f.y.push_back(correct_and_accepted(kf, t));
                acc_a.y.push_back(correct_and_accepted(ka, t));
                fp_f.y.push_back(acceptance_rate(uf, t));
                fp_a.y.push_back(acceptance_rate(ua, t));
            }
            chart.series = {acc_f, acc_a, fp_f, fp_a};
            const std::string base = "threshold_" + set + "_" + stat_names[which];
            write_csv(dir / (base + ".csv"), chart);
            write_png(dir / (base + ".png"), chart);
            const EqualErrorRate eer_f = equal_error_rate(kf_stats, uf), eer_a = equal_error_rate(ka_stats, ua);
            JsonObject row;
            row.add("set", set).add("rule", stat_fields[which]).add("known_frames", kf.size()).add("unknown_frames", uf.size());
            row.add("threshold", chosen).add("accuracy_frame", correct_and_accepted(kf, chosen));
            row.add("accuracy_accumulated", correct_and_accepted(ka, chosen));
            row.add("false_positive_frame", acceptance_rate(uf, chosen)).add("false_positive_accumulated", acceptance_rate(ua, chosen));
            row.add("eer_frame", eer_f.rate).add("eer_accumulated", eer_a.rate);
            row.add("eer_threshold_frame", eer_f.threshold).add("eer_threshold_accumulated", eer_a.threshold);
            rows.push_back(row);
            if (!json)
                std::cout << std::left << std::setw(7) << set << std::setw(13) << stat_fields[which] << std::right << std::fixed
                          << std::setprecision(3) << std::setw(10) << chosen << std::setw(12) << correct_and_accepted(kf, chosen)
                          << std::setw(12) << correct_and_accepted(ka, chosen) << std::setw(11) << acceptance_rate(uf, chosen)
                          << std::setw(11) << acceptance_rate(ua, chosen) << std::setw(11) << eer_f.rate << std::setw(11)
                          << eer_a.rate << "\n";
        }
    }
    result.add("results", rows);
    if (json)
        std::cout << result.str() << "\n";
    else
        std::cout << "curves: " << (dir / "threshold_*.csv").string() << " and .png\n";
    return 0;
}

// ---------------------------------------------------------------------------------------------
// eval throughput: frames per second of the whole pipeline

namespace {

/// Frames held in memory, replayed as a file-like source (no decoding cost in the figure).
class MemorySource : public VideoSource {
public:
    MemorySource(std::vector<cv::Mat> frames, std::size_t count) : frames_(std::move(frames)), count_(count) {}
    FrameStatus read(Frame& f) override {
        if (next_ >= count_) return FrameStatus::End;
        f.image = frames_[next_ % frames_.size()];
        f.index = static_cast<long long>(next_);
        f.timestamp = double(next_++) / 30.0;
        return FrameStatus::Ok;
    }
    bool is_live() const override { return false; }
    long long frame_count() const override { return static_cast<long long>(count_); }
    double fps() const override { return 30; }
    std::string description() const override { return "memory"; }

private:
    std::vector<cv::Mat> frames_;
    std::size_t count_, next_ = 0;
};

struct Throughput {
    long long frames = 0, faces = 0;
    double seconds = 0, front_end_ms = 0, scoring_ms = 0;
};

Throughput run_through(const std::shared_ptr<VisionPipeline>& pipeline, std::unique_ptr<VideoSource> source) {
    RunnerParams rp;
    rp.result_queue = 100000;
    const auto t0 = Clock::now();
    PipelineRunner runner(pipeline, std::move(source), rp);
    Throughput t;
    PipelineResult r;
    while (!runner.finished())
        if (runner.next(r, std::chrono::milliseconds(1000)) && r.status == FrameStatus::Ok) {
            ++t.frames;
            t.faces += r.faces_detected;
            t.front_end_ms += r.front_end_ms;
            t.scoring_ms += r.scoring_ms;
        }
    t.seconds = seconds_since(t0);
    if (auto err = runner.error()) std::rethrow_exception(err);
    return t;
}

JsonObject throughput_json(const std::string& name, const Throughput& t) {
    JsonObject o;
    o.add("input", name).add("frames", long(t.frames)).add("faces", long(t.faces)).add("seconds", t.seconds);
    o.add("fps", t.frames / t.seconds).add("faces_per_second", t.faces / t.seconds);
    o.add("front_end_ms_per_frame", t.front_end_ms / std::max(1LL, t.frames));
    o.add("scoring_ms_per_frame", t.scoring_ms / std::max(1LL, t.frames));
    return o;
}

}  // namespace

int cmd_eval_throughput(const std::vector<std::string>& argv) {
    const Args args(argv, {"--data", "--frames"}, {"--json", "--profile"});
    const fs::path root = data_dir(args.get("--data"));
    const bool json = args.flag("--json");
    const int frames = args.get_int("--frames", 300);
    if (frames < 1) throw UsageError("eval throughput: expected --frames >= 1");

    // 40 ORL people enrolled (images 1-5) with the pipeline's normaliser.
    auto bank = std::make_shared<ClassifierBank>();
    for (const PersonImages& p : load_identity_folders(root / "orl")) {
        std::vector<cv::Mat> faces;
        for (std::size_t i = 0; i < 5 && i < p.images.size(); ++i) {
            const cv::Mat img = load_image(p.images[i], ImageColor::Grey);
            faces.push_back(bank->normalize(img, {0, 0, img.cols, img.rows}));
        }
        bank->add_faces(p.name, faces);
    }
    bank->train();
    PipelineParams params;
    params.front_end.use_profile = args.flag("--profile");

    std::vector<JsonObject> rows;
    auto report = [&](const std::string& name, const Throughput& t) {
        rows.push_back(throughput_json(name, t));
        if (!json)
            std::cout << std::left << std::setw(34) << name << std::right << std::setw(6) << t.frames << " frames "
                      << std::fixed << std::setprecision(1) << std::setw(7) << t.frames / t.seconds << " fps "
                      << std::setw(7) << t.faces / t.seconds << " faces/s   front end " << std::setprecision(2)
                      << t.front_end_ms / std::max(1LL, t.frames) << " ms, scoring " << t.scoring_ms / std::max(1LL, t.frames)
                      << " ms per frame\n";
    };
    if (!json) std::cout << "40 people enrolled; " << (params.front_end.use_profile ? "frontal + profile" : "frontal") << " detection\n";
    const fs::path clip = root / "video_hamilton" / "short_hamilton_clip.mp4";
    report("short_hamilton_clip.mp4 (640x360)",
           run_through(std::make_shared<VisionPipeline>(bank, params), VideoSource::open(clip.string())));
    std::vector<cv::Mat> caltech;
    for (const fs::path& f : list_images(root / "caltech_faces1999_partial" / "images")) {
        cv::Mat img = load_image(f), resized;
        cv::resize(img, resized, {640, 480});
        caltech.push_back(resized);
        if (caltech.size() == 30) break;
    }
    report("Caltech frames at 640x480", run_through(std::make_shared<VisionPipeline>(bank, params),
                                                  std::make_unique<MemorySource>(caltech, std::size_t(frames))));
    if (json) {
        JsonObject result;
        result.add("people", 40).add("profile", params.front_end.use_profile).add("inputs", rows);
        std::cout << result.str() << "\n";
    }
    return 0;
}

}  // namespace facesocial::cli
