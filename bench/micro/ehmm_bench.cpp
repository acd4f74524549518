// Embedded-HMM stages on one core: DCT observation extraction, emissions of all Gaussians,
// doubly embedded Viterbi, scoring one face against a 40-person bank, training one person.
#include <benchmark/benchmark.h>
#include <opencv2/core.hpp>

#include "../../libfacesocial/src/ehmm_impl.hpp"
#include "facesocial/classifier_bank.hpp"
#include "facesocial/datasets.hpp"
#include "facesocial/face_augment.hpp"
#include "facesocial/face_classifier.hpp"
#include "facesocial/face_normalizer.hpp"
#include "facesocial/image_io.hpp"

using namespace facesocial;

namespace {

const std::vector<std::vector<cv::Mat>>& orl_faces() {
    static const auto faces = load_cropped_faces(data_root() / "orl").faces;
    return faces;
}

std::vector<cv::Mat> first5(int person) {
    return {orl_faces()[person].begin(), orl_faces()[person].begin() + 5};
}

void BM_DctObservations(benchmark::State& state) {
    const EhmmParams p;
    for (auto _ : state) benchmark::DoNotOptimize(extract_observations(orl_faces()[0][0], p.observations));
}
BENCHMARK(BM_DctObservations)->Unit(benchmark::kMicrosecond);

/// Person 0's model and the features of one of their test faces.
struct ModelAndFace {
    EmbeddedHmm model = EmbeddedHmm::train(first5(0));
    Observations obs = extract_observations(orl_faces()[0][6], model.params().observations);
    RowMatrixF F;
    ModelAndFace() { EmbeddedHmm::Impl::features(obs, F); }
};

void BM_Emissions(benchmark::State& state) {
    const ModelAndFace x;
    const EmbeddedHmm& m = x.model;
    const RowMatrixF& F = x.F;
    RowMatrixF E;
    for (auto _ : state) {
        m.impl().emissions(F, E);
        benchmark::DoNotOptimize(E.data());
    }
}
BENCHMARK(BM_Emissions)->Unit(benchmark::kMicrosecond);

/// Training's variant: also keeps the winning mixture of every state.
void BM_EmissionsWithBestMixture(benchmark::State& state) {
    const ModelAndFace x;
    RowMatrixF E;
    std::vector<int> best;
    for (auto _ : state) {
        x.model.impl().emissions(x.F, E, &best);
        benchmark::DoNotOptimize(best.data());
    }
}
BENCHMARK(BM_EmissionsWithBestMixture)->Unit(benchmark::kMicrosecond);

void BM_Viterbi(benchmark::State& state) {
    const ModelAndFace x;
    RowMatrixF E;
    x.model.impl().emissions(x.F, E);
    for (auto _ : state) benchmark::DoNotOptimize(x.model.impl().viterbi(E, x.obs.grid, nullptr));
}
BENCHMARK(BM_Viterbi)->Unit(benchmark::kMicrosecond);

void BM_ScoreAgainst40People(benchmark::State& state) {
    ClassifierParams p;
    p.num_threads = 1;
    auto c = FaceClassifier::create(p);
    std::vector<std::vector<cv::Mat>> train;
    for (int i = 0; i < 40; ++i) train.push_back(first5(i));
    c->train(train);
    for (auto _ : state) benchmark::DoNotOptimize(c->scores(orl_faces()[3][7]));
}
BENCHMARK(BM_ScoreAgainst40People)->Unit(benchmark::kMillisecond);

void BM_TrainOnePersonFrom5(benchmark::State& state) {
    const auto faces = first5(0);
    for (auto _ : state) benchmark::DoNotOptimize(EmbeddedHmm::train(faces));
}
BENCHMARK(BM_TrainOnePersonFrom5)->Unit(benchmark::kMillisecond);

void BM_Train40PeopleBank(benchmark::State& state) {
    std::vector<std::vector<cv::Mat>> train;
    for (int i = 0; i < 40; ++i) train.push_back(first5(i));
    auto c = FaceClassifier::create();
    for (auto _ : state) c->train(train);
}
BENCHMARK(BM_Train40PeopleBank)->Unit(benchmark::kMillisecond)->UseRealTime();

/// The bank's path: per-person models scored in parallel over people (Arg = threads).
void BM_BankScore40People(benchmark::State& state) {
    ClassifierBankParams p;
    p.normalizer = NormalizerParams::cropped();
    p.classifier.num_threads = int(state.range(0));
    ClassifierBank bank(p);
    for (int i = 0; i < 40; ++i) bank.add_faces("s" + std::to_string(i + 1), first5(i));
    bank.train();
    for (auto _ : state) benchmark::DoNotOptimize(bank.scores(orl_faces()[3][7]));
}
BENCHMARK(BM_BankScore40People)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();

/// The paper's Fig. 4: training time of one person against the training-set size. The set is
/// person s1's 10 real ORL images followed by small random variations of them (augment_faces).
void BM_TrainOnePersonFromN(benchmark::State& state) {
    const auto faces = augment_faces(orl_faces()[0], std::size_t(state.range(0)), AugmentParams{}, 7);
    EhmmTrainingReport report;
    for (auto _ : state) benchmark::DoNotOptimize(EmbeddedHmm::train(faces, EhmmParams{}, &report));
    state.counters["iterations"] = report.iterations;
}
BENCHMARK(BM_TrainOnePersonFromN)->Arg(10)->Arg(30)->Arg(50)->Arg(100)->Arg(200)->Arg(400)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
