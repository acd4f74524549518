// Front-end stages on one core: detection on a 640x480 frame, skin filter per box,
// normalisation per face. Frames are real Caltech photos scaled to 640x480.
#include <benchmark/benchmark.h>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "facesocial/datasets.hpp"
#include "facesocial/face_detector.hpp"
#include "facesocial/face_normalizer.hpp"
#include "facesocial/image_io.hpp"
#include "facesocial/skin_filter.hpp"

using namespace facesocial;

namespace {

const cv::Mat& frame640() {
    static const cv::Mat frame = [] {
        cv::Mat f = load_image(data_root() / "caltech_faces1999_partial" / "images" / "image_0001.jpg");
        cv::resize(f, f, cv::Size(640, 480), 0, 0, cv::INTER_LINEAR);
        return f;
    }();
    return frame;
}

void run_detector(benchmark::State& state, const FaceDetector& d) {
    const cv::Mat& f = frame640();
    std::size_t faces = 0;
    for (auto _ : state) {
        auto found = d.detect(f);
        faces = found.size();
        benchmark::DoNotOptimize(found);
    }
    state.counters["faces"] = double(faces);
}

void BM_FrontalDetect640x480(benchmark::State& state) {
    cv::setNumThreads(1);
    run_detector(state, *FaceDetector::create());
}
BENCHMARK(BM_FrontalDetect640x480)->Unit(benchmark::kMillisecond);

void BM_FrontalDetectFast640x480(benchmark::State& state) {
    cv::setNumThreads(1);
    run_detector(state, *FaceDetector::create(CascadeDetectorParams::fast_frontal()));
}
BENCHMARK(BM_FrontalDetectFast640x480)->Unit(benchmark::kMillisecond);

void BM_FrontalProfileDetect640x480(benchmark::State& state) {
    cv::setNumThreads(1);
    run_detector(state, *create_default_detector(true));
}
BENCHMARK(BM_FrontalProfileDetect640x480)->Unit(benchmark::kMillisecond);

void BM_FrontalProfileDetectFast640x480(benchmark::State& state) {
    cv::setNumThreads(1);
    auto d = FaceDetector::combine({FaceDetector::create(CascadeDetectorParams::fast_frontal()),
                                    FaceDetector::create(CascadeDetectorParams::fast_profile())});
    run_detector(state, *d);
}
BENCHMARK(BM_FrontalProfileDetectFast640x480)->Unit(benchmark::kMillisecond);

cv::Rect face_box() {
    const auto found = FaceDetector::create()->detect(frame640());
    return found.empty() ? cv::Rect(200, 100, 200, 200) : found[0].box;
}

void BM_SkinFractionPerBox(benchmark::State& state) {
    const SkinFilter filter;
    const cv::Rect box = face_box();
    for (auto _ : state) benchmark::DoNotOptimize(filter.skin_fraction(frame640(), box));
    state.counters["box_px"] = double(box.area());
}
BENCHMARK(BM_SkinFractionPerBox)->Unit(benchmark::kMicrosecond);

void BM_NormalizePerFace(benchmark::State& state) {
    const FaceNormalizer normalizer;
    const cv::Rect box = face_box();
    for (auto _ : state) benchmark::DoNotOptimize(normalizer.normalize(frame640(), box));
}
BENCHMARK(BM_NormalizePerFace)->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
