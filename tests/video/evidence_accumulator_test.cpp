// Accumulator arithmetic: moving average, exponential decay, majority vote, name alignment, the
// unknown rule on accumulated scores, and accumulation beating single frames on real faces.
#include <gtest/gtest.h>

#include "facesocial/classifier_bank.hpp"
#include "facesocial/datasets.hpp"
#include "facesocial/evidence_accumulator.hpp"
#include "support/test_data.hpp"

using namespace facesocial;

namespace {

BankScores frame(std::vector<std::string> names, std::vector<double> scores) { return {std::move(names), std::move(scores)}; }

double score_of(const BankScores& s, const std::string& name) {
    for (std::size_t i = 0; i < s.names.size(); ++i)
        if (s.names[i] == name) return s.scores[i];
    ADD_FAILURE() << name << " missing";
    return 0;
}

}  // namespace

TEST(EvidenceAccumulator, MovingAverageOverTheWindowWithEqualWeights) {
    AccumulatorParams p;
    p.window = 3;
    EvidenceAccumulator acc(p);
    EXPECT_TRUE(acc.accumulated().names.empty());
    EXPECT_FALSE(acc.decide({}).known);
    acc.add(frame({"ann", "bob"}, {-10, -12}));
    acc.add(frame({"ann", "bob"}, {-14, -11}));
    acc.add(frame({"ann", "bob"}, {-12, -13}));
    EXPECT_EQ(acc.frames(), 3);
    EXPECT_DOUBLE_EQ(score_of(acc.accumulated(), "ann"), -12.0);
    EXPECT_DOUBLE_EQ(score_of(acc.accumulated(), "bob"), -12.0);
    acc.add(frame({"ann", "bob"}, {-20, -10}));  // the first frame leaves the window
    EXPECT_EQ(acc.frames(), 3);
    EXPECT_DOUBLE_EQ(score_of(acc.accumulated(), "ann"), -46.0 / 3);
    EXPECT_DOUBLE_EQ(score_of(acc.accumulated(), "bob"), -34.0 / 3);
    const Decision d = acc.decide({});
    EXPECT_EQ(d.name, "bob");
    EXPECT_DOUBLE_EQ(d.margin, 4.0);
    acc.reset();
    EXPECT_EQ(acc.frames(), 0);
}

TEST(EvidenceAccumulator, PeopleEnrolledMidwayAreAveragedOverTheFramesThatScoredThem) {
    AccumulatorParams p;
    p.window = 10;
    EvidenceAccumulator acc(p);
    acc.add(frame({"ann"}, {-10}));
    acc.add(frame({"ann", "cy"}, {-12, -8}));
    const BankScores s = acc.accumulated();
    EXPECT_EQ(s.names, (std::vector<std::string>{"ann", "cy"}));
    EXPECT_DOUBLE_EQ(s.scores[0], -11);
    EXPECT_DOUBLE_EQ(s.scores[1], -8);
}

TEST(EvidenceAccumulator, ExponentialDecayWeighsRecentFramesMore) {
    AccumulatorParams p;
    p.mode = AccumulationMode::ExponentialDecay;
    p.decay = 0.5;
    EvidenceAccumulator acc(p);
    acc.add(frame({"ann"}, {-10}));
    EXPECT_DOUBLE_EQ(score_of(acc.accumulated(), "ann"), -10);
    acc.add(frame({"ann"}, {-20}));
    // weights 0.25 (old) and 0.5 (new), normalised: (-2.5 - 10) / 0.75
    EXPECT_DOUBLE_EQ(score_of(acc.accumulated(), "ann"), -12.5 / 0.75);
    EXPECT_EQ(acc.frames(), 2);
}

TEST(EvidenceAccumulator, MajorityVoteCountsPerFrameWinners) {
    AccumulatorParams p;
    p.mode = AccumulationMode::MajorityVote;
    p.window = 4;
    EvidenceAccumulator acc(p);
    // Each wins two frames; ann's fourth-frame win is by far, so the mean will favour ann.
    acc.add(frame({"ann", "bob"}, {-10, -10.1}));
    acc.add(frame({"ann", "bob"}, {-10.1, -10}));
    acc.add(frame({"ann", "bob"}, {-10.1, -10}));
    acc.add(frame({"ann", "bob"}, {-5, -15}));
    const BankScores votes = acc.accumulated();
    EXPECT_DOUBLE_EQ(score_of(votes, "bob"), 0.5);
    EXPECT_DOUBLE_EQ(score_of(votes, "ann"), 0.5);  // a tie: names break it
    acc.add(frame({"ann", "bob"}, {-10.1, -10}));    // window: bob 3, ann 1
    const Decision d = acc.decide({});
    EXPECT_TRUE(d.known);
    EXPECT_EQ(d.name, "bob");
    EXPECT_DOUBLE_EQ(d.ranked[0].score, 0.75);
    // The rule looks at the mean scores of the window (ann -8.825, bob -11.25: margin 2.425).
    UnknownRule strict;
    strict.min_margin = 5;
    EXPECT_FALSE(acc.decide(strict).known);
}

TEST(EvidenceAccumulator, UnknownRuleAppliesToTheAccumulatedVector) {
    EvidenceAccumulator acc;
    UnknownRule rule;
    rule.min_variance = 1.0;
    acc.add(frame({"ann", "bob", "cy"}, {-10, -13, -13}));  // variance 2: known
    EXPECT_TRUE(acc.decide(rule).known);
    acc.add(frame({"ann", "bob", "cy"}, {-14, -13, -13}));  // mean -12, -13, -13: variance 2/9
    EXPECT_FALSE(acc.decide(rule).known);
}

TEST(EvidenceAccumulator, BadInputsGiveClearErrors) {
    AccumulatorParams p;
    p.window = 0;
    EXPECT_THROW(EvidenceAccumulator{p}, std::invalid_argument);
    p = {};
    p.decay = 1.0;
    EXPECT_THROW(EvidenceAccumulator{p}, std::invalid_argument);
    EvidenceAccumulator acc;
    EXPECT_THROW(acc.add(frame({"ann"}, {-1, -2})), std::invalid_argument);
    EXPECT_THROW(acc.add(frame({"ann", "ann"}, {-1, -2})), std::invalid_argument);
    EXPECT_THROW(acc.add(frame({"ann"}, {NAN})), std::invalid_argument);
    EXPECT_THROW(accumulation_mode_from_string("median"), std::invalid_argument);
    EXPECT_EQ(accumulation_mode_from_string("vote"), AccumulationMode::MajorityVote);
}

TEST(EvidenceAccumulator, AccumulationBeatsSingleFramesOnRealFaces) {
    // ORL people enrolled from one image each; the other nine images of a person, in order,
    // are a sequence. Single-frame accuracy is well under perfect; a 9-frame average is better.
    const FaceSet set = load_cropped_faces(test::data() / "orl");
    ClassifierBankParams bp;
    bp.normalizer = NormalizerParams::cropped();
    ClassifierBank bank(bp);
    const std::size_t people = 15;
    for (std::size_t p = 0; p < people; ++p) bank.add_faces(set.names[p], {set.faces[p][0]});
    bank.train();
    int single = 0, accumulated = 0, total = 0;
    for (std::size_t p = 0; p < people; ++p) {
        AccumulatorParams ap;
        ap.window = 9;
        EvidenceAccumulator acc(ap);
        for (std::size_t i = 1; i < set.faces[p].size(); ++i) {
            const BankScores s = bank.scores(set.faces[p][i]);
            single += bank.decide(s).name == set.names[p];
            acc.add(s);
            ++total;
        }
        accumulated += acc.decide({}).name == set.names[p];
    }
    const double single_acc = double(single) / total, acc_acc = double(accumulated) / people;
    EXPECT_LT(single_acc, 0.95);
    EXPECT_GT(acc_acc, single_acc);
}
