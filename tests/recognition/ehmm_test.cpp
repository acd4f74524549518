#include <random>
#include <sstream>

#include <gtest/gtest.h>

#include "facesocial/datasets.hpp"
#include "facesocial/ehmm.hpp"
#include "facesocial/error.hpp"
#include "facesocial/face_normalizer.hpp"
#include "facesocial/image_io.hpp"
#include "support/test_data.hpp"

using namespace facesocial;

namespace {

EhmmParams small_params() {
    EhmmParams p;
    p.observations.face_size = {48, 56};
    p.observations.block_size = 8;
    p.observations.block_step = 4;
    p.states = {3, 4, 3};
    p.mixtures = 2;
    return p;
}

std::vector<cv::Mat> orl_faces(int person, int from, int to) {
    const FaceNormalizer n(NormalizerParams::cropped());
    std::vector<cv::Mat> out;
    for (int i = from; i <= to; ++i)
        out.push_back(n.normalize(load_image(test::data() / "orl" / ("s" + std::to_string(person)) /
                                                 (std::to_string(i) + ".pgm"),
                                             ImageColor::Grey))
                          .pixels);
    return out;
}

}  // namespace

TEST(Observations, GridAndDctOfAConstantImage) {
    ObservationParams p;
    p.drop_dc = false;
    EXPECT_EQ(p.grid(), cv::Size(21, 26));
    const Observations o = extract_observations(cv::Mat(112, 92, CV_32F, cv::Scalar(2.0f)), p);
    ASSERT_EQ(o.vectors.rows, 21 * 26);
    ASSERT_EQ(o.vectors.cols, 9);
    // Orthonormal DCT of a constant 12x12 block: DC = 12 * value, every other coefficient 0.
    EXPECT_NEAR(o.vectors.at<float>(0, 0), 24.0f, 1e-4);
    for (int j = 1; j < 9; ++j) EXPECT_NEAR(o.vectors.at<float>(5, j), 0.0f, 1e-4);
    p.drop_dc = true;
    EXPECT_EQ(extract_observations(cv::Mat(112, 92, CV_8U, cv::Scalar(3)), p).vectors.cols, 8);
}

TEST(Observations, MatchesOpencvDctOfOneBlock) {
    const cv::Mat face = load_image(test::data() / "orl" / "s5" / "3.pgm", ImageColor::Grey);
    ObservationParams p;
    p.coefficients = 4;
    p.drop_dc = false;
    const Observations o = extract_observations(face, p);
    const int r = 7, c = 9;  // block (row 7, column 9)
    cv::Mat block;
    face(cv::Rect(c * 4, r * 4, 12, 12)).convertTo(block, CV_32F);
    cv::Mat ref;
    cv::dct(block, ref);
    for (int u = 0; u < 4; ++u)
        for (int v = 0; v < 4; ++v) EXPECT_NEAR(o.vectors.at<float>(r * 21 + c, u * 4 + v), ref.at<float>(u, v), 1e-2);
}

TEST(Observations, BadInputsGiveClearErrors) {
    const ObservationParams p;
    EXPECT_THROW(extract_observations(cv::Mat(), p), std::invalid_argument);
    EXPECT_THROW(extract_observations(cv::Mat(112, 92, CV_8UC3), p), std::invalid_argument);
    EXPECT_THROW(extract_observations(cv::Mat(112, 92, CV_16U), p), std::invalid_argument);
    EXPECT_THROW(extract_observations(cv::Mat(8, 8, CV_8U), p), std::invalid_argument);
    ObservationParams q;
    q.block_step = 0;
    EXPECT_THROW(q.validate(), std::invalid_argument);
}

TEST(Ehmm, TrainingRecoversAModelFromItsOwnSamples) {
    EhmmParams p = small_params();
    p.recluster_mixtures = true;
    std::mt19937 rng(7);
    const EmbeddedHmm truth = EmbeddedHmm::random(p, rng);
    const EmbeddedHmm other = EmbeddedHmm::random(p, rng);
    std::vector<Observations> train, test;
    std::vector<EhmmSegmentation> test_truth;
    for (int i = 0; i < 40; ++i) train.push_back(truth.sample(p.observations.grid(), rng).first);
    for (int i = 0; i < 5; ++i) {
        auto [o, seg] = truth.sample(p.observations.grid(), rng);
        test.push_back(o);
        test_truth.push_back(seg);
    }
    EhmmTrainingReport report;
    const EmbeddedHmm learned = EmbeddedHmm::train(train, p, &report);
    ASSERT_GE(report.iterations, 1);
    for (std::size_t i = 1; i < report.mean_log_likelihood.size(); ++i)
        EXPECT_GE(report.mean_log_likelihood[i], report.mean_log_likelihood[i - 1] - 1e-3);
    double total_gap = 0;
    for (std::size_t i = 0; i < test.size(); ++i) {
        // Likelihood ranking: the learned model prefers its own kind of data to another model's.
        const auto foreign = other.sample(p.observations.grid(), rng).first;
        EXPECT_GT(learned.score(test[i]), learned.score(foreign));
        // Per observation, the learned model explains the data about as well as the truth.
        const double gap = std::abs(learned.score(test[i]) - truth.score(test[i]));
        EXPECT_LT(gap, 1.5);
        total_gap += gap;
        // Segmentation: super-states of the rows and embedded states of the blocks.
        const EhmmSegmentation seg = learned.segment(test[i]);
        int rows_ok = 0, blocks_ok = 0;
        for (std::size_t r = 0; r < seg.super_state.size(); ++r) rows_ok += seg.super_state[r] == test_truth[i].super_state[r];
        for (std::size_t b = 0; b < seg.state.size(); ++b) blocks_ok += seg.state[b] == test_truth[i].state[b];
        EXPECT_GE(rows_ok, int(seg.super_state.size()) - 1);
        EXPECT_GE(double(blocks_ok) / seg.state.size(), 0.9);
    }
    EXPECT_LT(total_gap / test.size(), 0.75);
}

TEST(Ehmm, SingleAndIdenticalTrainingImagesGiveFiniteScores) {
    const auto faces = orl_faces(1, 1, 2);
    const EmbeddedHmm one = EmbeddedHmm::train(std::vector<cv::Mat>{faces[0]});
    const EmbeddedHmm same = EmbeddedHmm::train(std::vector<cv::Mat>{faces[0], faces[0], faces[0]});
    const EmbeddedHmm flat = EmbeddedHmm::train(std::vector<cv::Mat>{cv::Mat(112, 92, CV_32F, cv::Scalar(0))});
    for (const EmbeddedHmm* m : {&one, &same, &flat}) {
        EXPECT_TRUE(std::isfinite(m->score(faces[1])));
        EXPECT_TRUE(std::isfinite(m->score(faces[0])));
        EXPECT_TRUE(std::isfinite(m->score(cv::Mat(112, 92, CV_32F, cv::Scalar(0)))));
    }
    EXPECT_GT(one.score(faces[0]), one.score(faces[1]));
}

TEST(Ehmm, RecognisesOrlPeopleFromTheirOwnModels) {
    std::vector<EmbeddedHmm> models;
    for (int p = 1; p <= 5; ++p) models.push_back(EmbeddedHmm::train(orl_faces(p, 1, 5)));
    int correct = 0;
    for (int p = 1; p <= 5; ++p)
        for (const cv::Mat& f : orl_faces(p, 6, 10)) {
            int best = 0;
            for (int q = 1; q < 5; ++q)
                if (models[q].score(f) > models[best].score(f)) best = q;
            correct += best == p - 1;
        }
    EXPECT_GE(correct, 24);  // of 25
}

TEST(Ehmm, WriteReadGivesIdenticalScores) {
    const auto faces = orl_faces(2, 1, 6);
    EhmmParams p;
    p.recluster_mixtures = true;
    const EmbeddedHmm m = EmbeddedHmm::train(std::vector<cv::Mat>(faces.begin(), faces.begin() + 5), p);
    std::stringstream ss;
    m.write(ss);
    const EmbeddedHmm back = EmbeddedHmm::read(ss);
    EXPECT_EQ(m.score(faces[5]), back.score(faces[5]));
    EXPECT_TRUE(back.params().recluster_mixtures);
    std::string bytes = ss.str();
    std::stringstream truncated(bytes.substr(0, bytes.size() / 2));
    EXPECT_THROW(EmbeddedHmm::read(truncated), ModelFormatError);
    std::stringstream future(bytes);
    EXPECT_THROW(EmbeddedHmm::read(future, EmbeddedHmm::kLayoutVersion + 1), ModelFormatError);
}

TEST(Ehmm, BadInputsAndParamsGiveClearErrors) {
    EXPECT_THROW(EmbeddedHmm::train(std::vector<cv::Mat>{}), std::invalid_argument);
    EXPECT_THROW(EmbeddedHmm::train(std::vector<cv::Mat>{cv::Mat(112, 92, CV_8UC3)}), std::invalid_argument);
    EXPECT_THROW(EmbeddedHmm().score(cv::Mat(112, 92, CV_8U)), std::logic_error);
    EhmmParams p;
    p.states = {3, 30, 3};  // wider than the 21 block columns
    EXPECT_THROW(p.validate(), std::invalid_argument);
    p = {};
    p.states.assign(40, 2);  // more super-states than the 26 block rows
    EXPECT_THROW(p.validate(), std::invalid_argument);
    p = {};
    p.mixtures = 0;
    EXPECT_THROW(p.validate(), std::invalid_argument);
    p = {};
    p.variance_floor = 0;
    EXPECT_THROW(p.validate(), std::invalid_argument);
}

TEST(Ehmm, AdaptationFromABackgroundRecognisesBetterThanTheBackground) {
    // A background trained on five people, adapted to each: every adapted model prefers its
    // own held-out faces to the background's fit, and recognition over the five is at least as
    // good as with independent models. The background's row bands carry over.
    std::vector<cv::Mat> pooled;
    for (int p = 1; p <= 5; ++p)
        for (const cv::Mat& f : orl_faces(p, 1, 5)) pooled.push_back(f);
    EhmmParams bp;
    bp.mixtures = 8;
    const EmbeddedHmm background = EmbeddedHmm::train(pooled, bp);
    std::vector<EmbeddedHmm> models;
    EhmmTrainingReport report;
    for (int p = 1; p <= 5; ++p) models.push_back(EmbeddedHmm::adapt(background, orl_faces(p, 1, 5), {}, &report));
    EXPECT_EQ(report.iterations, EhmmAdaptParams{}.iterations);
    EXPECT_GT(report.mean_log_likelihood.back(), report.mean_log_likelihood.front());
    EXPECT_EQ(models[0].params().mixtures, 8);
    int correct = 0;
    for (int p = 1; p <= 5; ++p)
        for (const cv::Mat& f : orl_faces(p, 6, 10)) {
            EXPECT_GT(models[p - 1].score(f), background.score(f));
            int best = 0;
            for (int q = 1; q < 5; ++q)
                if (models[q].score(f) > models[best].score(f)) best = q;
            correct += best == p - 1;
        }
    EXPECT_GE(correct, 24);  // of 25
    // Saved and read back, an adapted model scores the same.
    std::stringstream ss;
    models[1].write(ss);
    EXPECT_EQ(EmbeddedHmm::read(ss).score(orl_faces(2, 6, 6)[0]), models[1].score(orl_faces(2, 6, 6)[0]));
}

TEST(Ehmm, BandsConfineSuperStatesAndCanBeTurnedOff) {
    const auto faces = orl_faces(3, 1, 5);
    EhmmParams p;
    const EmbeddedHmm banded = EmbeddedHmm::train(faces, p);
    p.band_margin = -1;
    const EmbeddedHmm open = EmbeddedHmm::train(faces, p);
    // The same training; the band can only remove alignments, so the open model scores at
    // least as high, and on the training faces (whose alignments lie in the band) the same.
    const cv::Mat probe = orl_faces(3, 7, 7)[0];
    EXPECT_GE(open.score(probe), banded.score(probe));
    EXPECT_DOUBLE_EQ(open.score(faces[0]), banded.score(faces[0]));
    // A segmentation under the banded model keeps every super-state inside its band: the
    // forehead super-state never reaches the last block row.
    const EhmmSegmentation seg = banded.segment(extract_observations(probe, p.observations));
    EXPECT_EQ(seg.super_state.front(), 0);
    EXPECT_EQ(seg.super_state.back(), int(p.states.size()) - 1);
}

TEST(Ehmm, AdaptationRejectsBadInputs) {
    const auto faces = orl_faces(1, 1, 2);
    EXPECT_THROW(EmbeddedHmm::adapt(EmbeddedHmm(), faces), std::invalid_argument);
    const EmbeddedHmm background = EmbeddedHmm::train(faces);
    EXPECT_THROW(EmbeddedHmm::adapt(background, std::vector<cv::Mat>{}), std::invalid_argument);
    EXPECT_THROW(EmbeddedHmm::adapt(background, std::vector<cv::Mat>{cv::Mat(112, 92, CV_16U)}), std::invalid_argument);
    EhmmAdaptParams ap;
    ap.relevance = -1;
    EXPECT_THROW(EmbeddedHmm::adapt(background, faces, ap), std::invalid_argument);
    ap = {};
    ap.iterations = 0;
    EXPECT_THROW(ap.validate(), std::invalid_argument);
    EhmmParams p;
    p.band_margin = -2;
    EXPECT_THROW(p.validate(), std::invalid_argument);
}
