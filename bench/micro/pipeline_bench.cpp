// The whole vision pipeline per frame (front end, 40-person EHMM bank, tracker, accumulators),
// synchronously on one 640x480 frame, with and without profile detection, and the tracker and
// accumulator alone. The threaded figure (capture overlapped with processing) is
// `facesocial eval throughput`.
#include <benchmark/benchmark.h>
#include <opencv2/imgproc.hpp>

#include "facesocial/datasets.hpp"
#include "facesocial/evidence_accumulator.hpp"
#include "facesocial/face_tracker.hpp"
#include "facesocial/image_io.hpp"
#include "facesocial/vision_pipeline.hpp"

using namespace facesocial;

namespace {

std::shared_ptr<ClassifierBank> bank40() {
    static const std::shared_ptr<ClassifierBank> bank = [] {
        auto b = std::make_shared<ClassifierBank>();
        for (const PersonImages& p : load_identity_folders(data_root() / "orl")) {
            std::vector<cv::Mat> faces;
            for (std::size_t i = 0; i < 5; ++i) {
                const cv::Mat img = load_image(p.images[i], ImageColor::Grey);
                faces.push_back(b->normalize(img, {0, 0, img.cols, img.rows}));
            }
            b->add_faces(p.name, faces);
        }
        b->train();
        return b;
    }();
    return bank;
}

Frame frame640() {
    cv::Mat img = load_image(list_images(data_root() / "caltech_faces1999_partial" / "images").front()), out;
    cv::resize(img, out, {640, 480});
    Frame f;
    f.image = out;
    f.index = 0;
    return f;
}

void run_pipeline(benchmark::State& state, bool profile) {
    PipelineParams p;
    p.front_end.use_profile = profile;
    VisionPipeline pipeline(bank40(), p);
    Frame f = frame640();
    int faces = 0;
    for (auto _ : state) {
        const PipelineResult r = pipeline.process(f);
        faces += r.faces_detected;
        ++f.index;
    }
    state.counters["faces_per_frame"] = benchmark::Counter(double(faces) / double(state.iterations()));
    state.counters["fps"] = benchmark::Counter(double(state.iterations()), benchmark::Counter::kIsRate);
}

void BM_PipelineFrame640x480(benchmark::State& state) { run_pipeline(state, false); }
BENCHMARK(BM_PipelineFrame640x480)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_PipelineFrame640x480WithProfile(benchmark::State& state) { run_pipeline(state, true); }
BENCHMARK(BM_PipelineFrame640x480WithProfile)->Unit(benchmark::kMillisecond)->UseRealTime();

/// Tracker update with N faces moving right by 3 px per frame, appearance signatures on.
void BM_TrackerUpdate(benchmark::State& state) {
    const int n = int(state.range(0));
    FaceTracker tracker;
    cv::RNG rng(1);
    std::vector<TrackerInput> in(static_cast<std::size_t>(n));
    for (int i = 0; i < n; ++i) {
        in[std::size_t(i)].box = {i * 120, 50, 100, 100};
        cv::Mat a(1, 168, CV_32F);
        rng.fill(a, cv::RNG::NORMAL, 0, 1);
        in[std::size_t(i)].appearance = a / cv::norm(a);
    }
    for (auto _ : state) {
        for (TrackerInput& t : in) t.box.x += 3;
        benchmark::DoNotOptimize(tracker.update(in));
    }
}
BENCHMARK(BM_TrackerUpdate)->Arg(1)->Arg(5)->Arg(10)->Unit(benchmark::kMicrosecond);

/// One frame into a 25-frame moving average over 40 people, then the decision.
void BM_AccumulateAndDecide40(benchmark::State& state) {
    BankScores frame;
    for (int i = 0; i < 40; ++i) frame.names.push_back("s" + std::to_string(i + 1)), frame.scores.push_back(-12.0 - 0.01 * i);
    EvidenceAccumulator acc;
    for (auto _ : state) {
        acc.add(frame);
        benchmark::DoNotOptimize(acc.decide({}));
    }
}
BENCHMARK(BM_AccumulateAndDecide40)->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
