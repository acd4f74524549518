// Training-set policies on real ORL faces (size cap, recency, even spread, pruning of wrongly
// tagged faces) and retraining in the background while scoring.
#include <atomic>
#include <thread>

#include <gtest/gtest.h>

#include "facesocial/background_trainer.hpp"
#include "facesocial/datasets.hpp"
#include "facesocial/face_augment.hpp"
#include "facesocial/training_set.hpp"
#include "support/test_data.hpp"

using namespace facesocial;

namespace {

const FaceSet& orl() {
    static const FaceSet set = load_cropped_faces(test::data() / "orl");
    return set;
}

/// Person p's ten images as samples taken one minute apart, in shuffled time order.
std::vector<TrainingSample> samples_of(std::size_t p) {
    std::vector<TrainingSample> s;
    const int times[10] = {5, 2, 9, 0, 7, 1, 8, 3, 6, 4};
    for (std::size_t i = 0; i < 10; ++i) s.push_back({orl().faces[p][i], SampleSource::Camera, 60.0 * times[i], "s"});
    return s;
}

}  // namespace

TEST(TrainingSet, CapKeepsTheNewestOrSpreadsOverTime) {
    const auto s = samples_of(0);
    TrainingPolicy p;
    p.max_size = 4;
    const SelectionReport recent = select_training_samples(s, p);
    EXPECT_EQ(recent.kept, (std::vector<std::size_t>{8, 4, 6, 2}));  // times 6, 7, 8, 9 minutes
    EXPECT_EQ(recent.capped.size(), 6u);
    p.prefer_recent = false;
    const SelectionReport spread = select_training_samples(s, p);
    EXPECT_EQ(spread.kept, (std::vector<std::size_t>{3, 7, 8, 2}));  // times 0, 3, 6, 9
    p.max_size = 0;
    EXPECT_EQ(select_training_samples(s, p).kept.size(), 10u);
}

TEST(TrainingSet, PruningDropsWronglyTaggedFaces) {
    // Eight real faces of person 3 and two faces of other people tagged as person 3.
    std::vector<TrainingSample> s;
    for (std::size_t i = 0; i < 8; ++i) s.push_back({orl().faces[3][i], SampleSource::Camera, double(i), "a"});
    s.push_back({orl().faces[17][0], SampleSource::SocialPhoto, 8, "b"});
    s.push_back({orl().faces[29][0], SampleSource::SocialPhoto, 9, "b"});
    // The bank of the other people the robot knows (including the two whose faces were mistagged).
    ClassifierBankParams bp;
    bp.normalizer = NormalizerParams::cropped();
    ClassifierBank others(bp);
    for (std::size_t q : {std::size_t(10), std::size_t(17), std::size_t(22), std::size_t(29)})
        others.add_faces(orl().names[q], {orl().faces[q].begin() + 5, orl().faces[q].end()});
    others.train();
    TrainingPolicy p;
    p.max_size = 0;
    p.prune_sigma = 2.0;
    const SelectionReport r = select_training_samples(s, p, {}, &others, orl().names[3]);
    EXPECT_EQ(r.pruned, (std::vector<std::size_t>{8, 9}));
    EXPECT_EQ(r.kept.size(), 8u);
    p.prune_sigma = 0;
    EXPECT_TRUE(select_training_samples(s, p, {}, &others, orl().names[3]).pruned.empty());
}

TEST(TrainingSet, BadInputsGiveClearErrors) {
    TrainingPolicy p;
    p.prune_sigma = -1;
    EXPECT_THROW(select_training_samples({}, p), std::invalid_argument);
    EXPECT_THROW(select_training_samples({TrainingSample{}}, {}), std::invalid_argument);
    p = {};
    p.min_after_pruning = 0;
    EXPECT_THROW(p.validate(), std::invalid_argument);
    EXPECT_TRUE(select_training_samples({}, {}).kept.empty());
}

TEST(BackgroundTrainer, RetrainsALargeSetWhileScoringGoesOn) {
    ClassifierBankParams bp;
    bp.normalizer = NormalizerParams::cropped();
    auto bank = std::make_shared<ClassifierBank>(bp);
    for (std::size_t p = 0; p < 4; ++p) bank->add_faces(orl().names[p], {orl().faces[p].begin(), orl().faces[p].begin() + 3});
    bank->train();
    const cv::Mat probe = orl().faces[1][9];
    const double before = bank->scores(probe).scores[1];
    bank->add_faces(orl().names[1], augment_faces({orl().faces[1].begin(), orl().faces[1].begin() + 5}, 30, {}, 3));
    BackgroundTrainer trainer(bank);
    std::atomic<bool> stop{false};
    std::atomic<int> scored{0};
    std::thread scorer([&] {
        while (!stop) {
            const BankScores s = bank->scores(probe);
            EXPECT_EQ(s.names.size(), 4u);
            ++scored;
        }
    });
    trainer.request(orl().names[1]);
    trainer.request(orl().names[1]);  // queued once while waiting (again if the first already started)
    trainer.request("nobody");
    trainer.wait_idle();
    stop = true;
    scorer.join();
    EXPECT_GE(trainer.trained(), 1u);
    EXPECT_LE(trainer.trained(), 2u);
    EXPECT_EQ(trainer.pending(), 0u);
    ASSERT_EQ(trainer.errors().size(), 1u);
    EXPECT_NE(trainer.errors()[0].find("nobody"), std::string::npos);
    EXPECT_TRUE(bank->is_trained(orl().names[1]));
    EXPECT_NE(bank->scores(probe).scores[1], before);
    EXPECT_GT(scored.load(), 0);
    EXPECT_THROW(BackgroundTrainer(nullptr), std::invalid_argument);
}
