// The classifier bank on real ORL faces: enrolment, per-person retraining, ranking and the
// unknown rule, order independence, save / load, corrupt files, concurrent scoring.
#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstring>
#include <fstream>
#include <thread>

#include <gtest/gtest.h>

#include "facesocial/classifier_bank.hpp"
#include "facesocial/datasets.hpp"
#include "facesocial/error.hpp"
#include "support/test_data.hpp"

using namespace facesocial;

namespace {

const FaceSet& orl() {
    static const FaceSet set = load_cropped_faces(test::data() / "orl");
    return set;
}

std::vector<cv::Mat> train_faces(std::size_t p) { return {orl().faces[p].begin(), orl().faces[p].begin() + 5}; }

ClassifierBankParams cropped_params(ClassifierKind kind = ClassifierKind::Ehmm) {
    ClassifierBankParams p;
    p.classifier.kind = kind;
    p.normalizer = NormalizerParams::cropped();
    return p;
}

/// A bank of the first `people` ORL people (images 1-5), enrolled in the given order.
ClassifierBank make_bank(const std::vector<std::size_t>& order, ClassifierKind kind = ClassifierKind::Ehmm) {
    ClassifierBank bank(cropped_params(kind));
    for (std::size_t p : order) bank.add_faces(orl().names[p], train_faces(p));
    bank.train();
    return bank;
}

std::vector<std::size_t> first(std::size_t n) {
    std::vector<std::size_t> v(n);
    for (std::size_t i = 0; i < n; ++i) v[i] = i;
    return v;
}

double score_of(const BankScores& s, const std::string& name) {
    for (std::size_t i = 0; i < s.names.size(); ++i)
        if (s.names[i] == name) return s.scores[i];
    ADD_FAILURE() << name << " not scored";
    return NAN;
}

}  // namespace

TEST(Decision, RanksByScoreThenNameAndAppliesTheRule) {
    const std::vector<std::string> names{"carol", "alice", "bob"};
    const std::vector<double> scores{-1.0, -3.0, -1.0};
    const auto ranked = rank_candidates(names, scores);
    ASSERT_EQ(ranked.size(), 3u);
    EXPECT_EQ(ranked[0].name, "bob");  // tie with carol broken by name
    EXPECT_EQ(ranked[1].name, "carol");
    EXPECT_EQ(ranked[2].name, "alice");
    EXPECT_EQ(rank_candidates(names, scores, 1).size(), 1u);
    EXPECT_NEAR(score_variance(scores), 8.0 / 9.0, 1e-12);

    UnknownRule rule;
    EXPECT_TRUE(decide(names, scores, rule).known);
    rule.min_variance = 1.0;  // 0.889 < 1: too flat
    EXPECT_FALSE(decide(names, scores, rule).known);
    rule.min_variance = 0.5;
    rule.min_score = -0.5;  // winner -1 too weak
    const Decision d = decide(names, scores, rule);
    EXPECT_FALSE(d.known);
    EXPECT_TRUE(d.name.empty());
    EXPECT_EQ(d.ranked.front().name, "bob");  // second guesses stay available
    rule.min_score = -2;
    EXPECT_EQ(decide(names, scores, rule).name, "bob");
    EXPECT_EQ(decide(names, scores, rule).margin, 0.0);  // bob and carol tie
    rule.min_margin = 0.1;
    EXPECT_FALSE(decide(names, scores, rule).known);
    UnknownRule margin_only;
    margin_only.min_margin = 0.1;
    EXPECT_TRUE(decide({"solo"}, {-5.0}, margin_only).known);  // one person: no runner-up to compare
    EXPECT_FALSE(decide({"solo"}, {-5.0}, rule).known);        // but the variance test rejects
    EXPECT_FALSE(decide({}, {}, UnknownRule{}).known);

    EXPECT_THROW(rank_candidates(names, {1.0}), std::invalid_argument);
    EXPECT_THROW(rank_candidates({"a"}, {NAN}), std::invalid_argument);
    EXPECT_THROW(decide(names, scores, UnknownRule{-1.0}), std::invalid_argument);
    UnknownRule negative_margin;
    negative_margin.min_margin = -1;
    EXPECT_THROW(negative_margin.validate(), std::invalid_argument);
}

TEST(ClassifierBank, RecognisesOrlPeopleAndRanksTheTruePersonFirst) {
    const ClassifierBank bank = make_bank(first(10));
    EXPECT_TRUE(bank.stale().empty());
    int correct = 0, total = 0;
    for (std::size_t p = 0; p < 10; ++p)
        for (std::size_t i = 5; i < 10; ++i) {
            const Decision d = bank.decide(orl().faces[p][i]);
            ASSERT_EQ(d.ranked.size(), 10u);
            correct += d.known && d.name == orl().names[p];
            ++total;
        }
    EXPECT_GE(double(correct) / total, 0.94) << correct << "/" << total;
    const auto top3 = bank.rank(orl().faces[3][7], 3);
    ASSERT_EQ(top3.size(), 3u);
    EXPECT_GE(top3[0].score, top3[1].score);
    EXPECT_GE(top3[1].score, top3[2].score);
}

TEST(ClassifierBank, ScoresDoNotDependOnTheOrderOfPeople) {
    std::vector<std::size_t> order = first(8);
    const ClassifierBank a = make_bank(order);
    std::reverse(order.begin(), order.end());
    const ClassifierBank b = make_bank(order);
    for (std::size_t p : {0u, 4u, 7u}) {
        const BankScores sa = a.scores(orl().faces[p][8]), sb = b.scores(orl().faces[p][8]);
        for (const std::string& name : sa.names) EXPECT_EQ(score_of(sa, name), score_of(sb, name)) << name;
        EXPECT_EQ(a.decide(orl().faces[p][8]).name, b.decide(orl().faces[p][8]).name);
    }
}

TEST(ClassifierBank, RetrainingOnePersonLeavesTheOthersUntouched) {
    ClassifierBank bank = make_bank(first(5));
    const cv::Mat probe = orl().faces[1][6];
    const BankScores before = bank.scores(probe);
    bank.add_faces(orl().names[0], {orl().faces[0][5]});
    EXPECT_EQ(bank.stale(), std::vector<std::string>{orl().names[0]});
    EXPECT_FALSE(bank.is_trained(orl().names[0]));
    EXPECT_EQ(bank.face_count(orl().names[0]), 6u);
    // The stale model still scores until it is replaced.
    EXPECT_EQ(score_of(bank.scores(probe), orl().names[0]), score_of(before, orl().names[0]));
    EXPECT_EQ(bank.train(), std::vector<std::string>{orl().names[0]});
    const BankScores after = bank.scores(probe);
    for (std::size_t p = 1; p < 5; ++p) EXPECT_EQ(score_of(after, orl().names[p]), score_of(before, orl().names[p]));
    EXPECT_NE(score_of(after, orl().names[0]), score_of(before, orl().names[0]));

    bank.remove_person(orl().names[2]);
    EXPECT_FALSE(bank.contains(orl().names[2]));
    EXPECT_EQ(bank.scores(probe).names.size(), 4u);
    EXPECT_EQ(bank.people().size(), 4u);
}

TEST(ClassifierBank, UnknownRuleRejectsAStrangerAtATightMinimumScore) {
    ClassifierBank bank = make_bank(first(10));
    // Threshold just under the weakest winning score of the enrolled people's held-out faces.
    double weakest = INFINITY;
    for (std::size_t p = 0; p < 10; ++p) weakest = std::min(weakest, bank.decide(orl().faces[p][5]).score);
    UnknownRule rule;
    rule.min_score = weakest - 1e-9;
    bank.set_unknown_rule(rule);
    for (std::size_t p = 0; p < 10; ++p) EXPECT_TRUE(bank.decide(orl().faces[p][5]).known);
    rule.min_score = 0;  // log-likelihoods per observation are negative: nothing passes
    bank.set_unknown_rule(rule);
    EXPECT_FALSE(bank.decide(orl().faces[20][0]).known);
    EXPECT_THROW(bank.set_unknown_rule(UnknownRule{NAN}), std::invalid_argument);
}

TEST(ClassifierBank, SaveThenLoadGivesIdenticalScores) {
    test::TempDir dir;
    ClassifierBank bank = make_bank(first(6));
    bank.add_person("newcomer");  // enrolled, no faces yet
    UnknownRule rule;
    rule.min_variance = 0.25;
    rule.min_margin = 0.5;
    bank.set_unknown_rule(rule);
    const std::string path = (dir / "bank.fsb").string();
    bank.save(path);
    const ClassifierBank loaded = ClassifierBank::load(path);
    EXPECT_EQ(loaded.people(), bank.people());
    EXPECT_EQ(loaded.unknown_rule().min_variance, 0.25);
    EXPECT_EQ(loaded.unknown_rule().min_margin, 0.5);
    EXPECT_EQ(loaded.stale(), bank.stale());
    EXPECT_EQ(loaded.face_count(orl().names[3]), 5u);
    for (std::size_t p : {0u, 5u, 30u}) {
        const BankScores a = bank.scores(orl().faces[p][9]), b = loaded.scores(orl().faces[p][9]);
        EXPECT_EQ(a.names, b.names);
        EXPECT_EQ(a.scores, b.scores);
    }
    // The loaded bank keeps working: retrain one person.
    ClassifierBank again = ClassifierBank::load(path);
    again.add_faces(orl().names[1], {orl().faces[1][5]});
    again.train(orl().names[1]);
    EXPECT_TRUE(again.is_trained(orl().names[1]));
}

TEST(ClassifierBank, JointClassifiersSaveAndLoadToo) {
    test::TempDir dir;
    for (ClassifierKind kind : {ClassifierKind::Lbph, ClassifierKind::Eigenfaces}) {
        const ClassifierBank bank = make_bank(first(5), kind);
        bank.save((dir / "joint.fsb").string());
        const ClassifierBank loaded = ClassifierBank::load((dir / "joint.fsb").string());
        const BankScores a = bank.scores(orl().faces[2][7]), b = loaded.scores(orl().faces[2][7]);
        EXPECT_EQ(a.names, b.names);
        for (std::size_t i = 0; i < a.scores.size(); ++i) EXPECT_NEAR(a.scores[i], b.scores[i], 1e-6 * std::abs(a.scores[i]));
        EXPECT_EQ(loaded.decide(orl().faces[2][7]).name, orl().names[2]) << to_string(kind);
    }
}

TEST(ClassifierBank, DamagedFilesGiveClearErrorsAndFailedSavesKeepTheOldFile) {
    test::TempDir dir;
    const ClassifierBank bank = make_bank(first(2));
    const std::string path = (dir / "bank.fsb").string();
    bank.save(path);
    std::string bytes;
    {
        std::ifstream in(path, std::ios::binary);
        bytes.assign(std::istreambuf_iterator<char>(in), {});
    }
    auto write = [&](const std::string& name, const std::string& content) {
        std::ofstream(dir / name, std::ios::binary) << content;
        return (dir / name).string();
    };
    auto message = [](const std::string& p) {
        try {
            ClassifierBank::load(p);
        } catch (const ModelFormatError& e) {
            return std::string(e.what());
        }
        return std::string("no error");
    };
    EXPECT_NE(message(write("truncated.fsb", bytes.substr(0, bytes.size() / 2))).find("truncated"), std::string::npos);
    EXPECT_NE(message(write("header.fsb", bytes.substr(0, 20))).find("truncated"), std::string::npos);
    std::string flipped = bytes;
    flipped[flipped.size() / 2] ^= 0x40;
    EXPECT_NE(message(write("flipped.fsb", flipped)).find("checksum"), std::string::npos);
    EXPECT_NE(message(write("foreign.fsb", "P5\n92 112\n255\n" + std::string(100, 'x'))).find("magic"), std::string::npos);
    std::string newer = bytes;
    newer[16] = 9;  // format version 9
    EXPECT_NE(message(write("newer.fsb", newer)).find("version 9"), std::string::npos);
    EXPECT_NE(message(write("trailing.fsb", bytes + "x")).find("trailing"), std::string::npos);
    EXPECT_THROW(ClassifierBank::load((dir / "missing.fsb").string()), FileError);

    // A save that cannot complete leaves the previous file as it was: block the temporary file.
    ClassifierBank bigger = make_bank(first(3));
    std::filesystem::create_directory(path + ".tmp-" + std::to_string(::getpid()));
    EXPECT_THROW(bigger.save(path), FileError);
    EXPECT_EQ(ClassifierBank::load(path).people().size(), 2u);
    std::filesystem::remove(path + ".tmp-" + std::to_string(::getpid()));
    EXPECT_THROW(bank.save((dir / "no_such_folder" / "bank.fsb").string()), FileError);
}

TEST(ClassifierBank, ReadsOlderFormatVersions) {
    // Rewrites a version-4 file of a joint (Eigenfaces) bank, whose layout is fixed, into the
    // older layouts. Version 3 has no EHMM band margin (the last 4 bytes of the EHMM
    // parameters), no adapted-training parameters (20 bytes after the training policy) and no
    // background flag at the end; version 2 also has no training policy (25 bytes) and no
    // provenance after each face (source u8, time f64, session string); version 1 also lacks the
    // EhmmParams::recluster_mixtures byte at offset 84 (kind 4 + EHMM parameters 80).
    test::TempDir dir;
    ClassifierBank bank = make_bank(first(3), ClassifierKind::Eigenfaces);
    const std::string path = (dir / "v4.fsb").string();
    bank.save(path);
    std::string bytes;
    {
        std::ifstream in(path, std::ios::binary);
        bytes.assign(std::istreambuf_iterator<char>(in), {});
    }
    const std::size_t head = 16 + 4 + 8;
    ASSERT_EQ(bytes[16], char(4));
    const std::string v4 = bytes.substr(head, bytes.size() - head - 8);
    auto u32 = [&](std::size_t at) { uint32_t v; std::memcpy(&v, v4.data() + at, 4); return std::size_t(v); };
    auto u64 = [&](std::size_t at) { uint64_t v; std::memcpy(&v, v4.data() + at, 8); return std::size_t(v); };
    auto older = [&](uint32_t version) {
        std::string out = v4.substr(0, 85);  // kind + EHMM parameters up to recluster_mixtures
        if (version == 1) out.erase(84, 1);
        std::size_t at = 89;                 // past band_margin
        out += v4.substr(at, 24 + 34 + 24);  // workers, normaliser, unknown rule
        at += 24 + 34 + 24;
        if (version == 3) out += v4.substr(at, 25);  // the training policy
        at += 25 + 20;                               // ... and the adapted-training parameters
        const std::size_t people = u64(at);
        out += v4.substr(at, 8);
        at += 8;
        for (std::size_t p = 0; p < people; ++p) {
            const std::size_t head_len = 4 + u32(at) + 8 + 8;
            out += v4.substr(at, head_len + 8);
            at += head_len;
            const std::size_t faces = u64(at);
            at += 8;
            for (std::size_t f = 0; f < faces; ++f) {
                const std::size_t start = at;
                at += 112 * 92 * 4 + 1 + 8;
                at += 4 + u32(at);  // the session
                out += version == 3 ? v4.substr(start, at - start) : v4.substr(start, 112 * 92 * 4);
            }
            EXPECT_EQ(v4[at], char(0));  // no EHMM in a joint bank
            out += v4.substr(at, 1);
            at += 1;
        }
        EXPECT_EQ(v4[at], char(0));  // no background model
        at += 1;
        EXPECT_EQ(at, v4.size());
        uint64_t hash = 0xcbf29ce484222325ull;  // FNV-1a 64
        for (unsigned char c : out) hash = (hash ^ c) * 0x100000001b3ull;
        const uint64_t size = out.size();
        std::string file = bytes.substr(0, 16);
        file.append(reinterpret_cast<const char*>(&version), 4).append(reinterpret_cast<const char*>(&size), 8);
        file += out;
        file.append(reinterpret_cast<const char*>(&hash), 8);
        const auto name = dir / ("v" + std::to_string(version) + ".fsb");
        std::ofstream(name, std::ios::binary) << file;
        return ClassifierBank::load(name.string());
    };
    const cv::Mat probe = orl().faces[1][8];
    for (uint32_t version : {1u, 2u, 3u}) {
        const ClassifierBank old = older(version);
        EXPECT_FALSE(old.params().classifier.ehmm.recluster_mixtures);
        EXPECT_EQ(old.params().classifier.ehmm.band_margin, -1) << "version " << version;
        EXPECT_EQ(old.params().classifier.ehmm_training, EhmmTraining::Independent) << "version " << version;
        EXPECT_TRUE(old.params().training.keeps_all());
        EXPECT_EQ(old.samples(orl().names[2]).size(), 5u);
        EXPECT_EQ(old.samples(orl().names[2])[0].source, version == 3 ? bank.samples(orl().names[2])[0].source
                                                                          : SampleSource::Camera);
        EXPECT_EQ(old.scores(probe).scores, bank.scores(probe).scores) << "version " << version;
    }
}

TEST(ClassifierBank, AdaptedTrainingKeepsOneBackgroundThroughRetrainsAndFiles) {
    // Adapted EHMM training (the default): the first training builds the background from
    // everyone; retraining one person adapts only them from the same background; save + load
    // keeps background and scores.
    test::TempDir dir;
    ClassifierBankParams params = cropped_params();
    ASSERT_EQ(params.classifier.ehmm_training, EhmmTraining::Adapted);
    ClassifierBank bank(params);
    for (std::size_t p = 0; p < 4; ++p) bank.add_faces(orl().names[p], train_faces(p));
    EXPECT_FALSE(bank.has_background());
    EXPECT_EQ(bank.train().size(), 4u);
    EXPECT_TRUE(bank.has_background());
    const cv::Mat probe = orl().faces[2][7];
    const BankScores before = bank.scores(probe);
    EXPECT_EQ(bank.rank(probe, 1).front().name, orl().names[2]);
    // One more face for person 0: only they are retrained, the others keep their scores.
    bank.add_faces(orl().names[0], {orl().faces[0][5]});
    EXPECT_EQ(bank.train(), std::vector<std::string>{orl().names[0]});
    const BankScores after = bank.scores(probe);
    for (std::size_t i = 1; i < 4; ++i) EXPECT_EQ(after.scores[i], before.scores[i]) << i;
    EXPECT_NE(after.scores[0], before.scores[0]);
    const std::string path = (dir / "adapted.fsb").string();
    bank.save(path);
    const ClassifierBank loaded = ClassifierBank::load(path);
    EXPECT_TRUE(loaded.has_background());
    EXPECT_EQ(loaded.scores(probe).scores, after.scores);
    // Doubling the bank rebuilds the background and retrains everyone.
    ClassifierBank grown = ClassifierBank::load(path);
    for (std::size_t p = 4; p < 8; ++p) grown.add_faces(orl().names[p], train_faces(p));
    EXPECT_EQ(grown.train().size(), 8u);
    EXPECT_NE(grown.scores(probe).scores[1], after.scores[1]);
    EXPECT_EQ(grown.train_background().size(), 8u);
}

TEST(ClassifierBank, SamplesKeepTheirProvenanceAndThePolicyChoosesTheTrainingFaces) {
    test::TempDir dir;
    ClassifierBankParams params = cropped_params();
    params.training.max_size = 3;  // the newest three
    ClassifierBank bank(params);
    std::vector<TrainingSample> samples;
    for (int i = 0; i < 6; ++i)
        samples.push_back({orl().faces[4][std::size_t(i)], i % 2 ? SampleSource::SocialPhoto : SampleSource::Camera,
                           100.0 - 10 * i, "visit " + std::to_string(i)});
    bank.add_samples(orl().names[4], samples);
    bank.add_faces(orl().names[5], {orl().faces[5].begin(), orl().faces[5].begin() + 4});
    bank.train();
    // Capture times fall with the index: the newest three are samples 0, 1, 2 (oldest first).
    EXPECT_EQ(bank.selection(orl().names[4]).kept, (std::vector<std::size_t>{2, 1, 0}));
    EXPECT_EQ(bank.selection(orl().names[4]).capped.size(), 3u);
    ClassifierBank same(cropped_params());
    same.add_faces(orl().names[4], {orl().faces[4][2], orl().faces[4][1], orl().faces[4][0]});
    same.add_faces(orl().names[5], {orl().faces[5].begin() + 1, orl().faces[5].begin() + 4});
    same.train();
    const cv::Mat probe = orl().faces[4][8];
    EXPECT_EQ(bank.scores(probe).scores[0], same.scores(probe).scores[0]);

    bank.save((dir / "bank.fsb").string());
    const ClassifierBank loaded = ClassifierBank::load((dir / "bank.fsb").string());
    EXPECT_EQ(loaded.params().training.max_size, 3u);
    const auto back = loaded.samples(orl().names[4]);
    ASSERT_EQ(back.size(), 6u);
    EXPECT_EQ(back[3].source, SampleSource::SocialPhoto);
    EXPECT_EQ(back[3].capture_time, 70.0);
    EXPECT_EQ(back[3].session, "visit 3");
    EXPECT_GT(loaded.samples(orl().names[5])[0].capture_time, 1e9);  // add_faces stamps the wall clock
    EXPECT_EQ(loaded.scores(probe).scores, bank.scores(probe).scores);
    EXPECT_THROW(bank.add_samples("x", {{orl().faces[0][0], SampleSource::Camera, NAN, ""}}), std::invalid_argument);
}

TEST(ClassifierBank, PruningPolicyLeavesWronglyTaggedFacesOut) {
    ClassifierBankParams params = cropped_params();
    params.training.max_size = 0;
    params.training.prune_sigma = 2.0;
    ClassifierBank bank(params);
    for (std::size_t q : {std::size_t(10), std::size_t(17), std::size_t(29)})
        bank.add_faces(orl().names[q], {orl().faces[q].begin(), orl().faces[q].begin() + 5});
    bank.train();
    std::vector<TrainingSample> s;
    for (std::size_t i = 0; i < 8; ++i) s.push_back({orl().faces[3][i], SampleSource::Camera, double(i), "a"});
    s.push_back({orl().faces[17][7], SampleSource::SocialPhoto, 8, "b"});
    s.push_back({orl().faces[29][7], SampleSource::SocialPhoto, 9, "b"});
    bank.add_samples(orl().names[3], s);
    bank.train(orl().names[3]);
    EXPECT_EQ(bank.selection(orl().names[3]).pruned, (std::vector<std::size_t>{8, 9}));
}

TEST(ClassifierBank, BadInputsGiveClearErrors) {
    ClassifierBank bank(cropped_params());
    EXPECT_THROW(bank.add_person(""), std::invalid_argument);
    EXPECT_THROW(bank.add_person("tab\tname"), std::invalid_argument);
    bank.add_person("ann");
    EXPECT_THROW(bank.add_person("ann"), std::invalid_argument);
    EXPECT_THROW(bank.train("ann"), std::invalid_argument);  // no faces
    EXPECT_THROW(bank.train("bob"), std::invalid_argument);  // not enrolled
    EXPECT_THROW(bank.remove_person("bob"), std::invalid_argument);
    EXPECT_THROW(bank.add_faces("ann", {cv::Mat(10, 10, CV_32F)}), std::invalid_argument);      // wrong size
    EXPECT_THROW(bank.add_faces("ann", {cv::Mat(112, 92, CV_8UC3)}), std::invalid_argument);    // colour
    EXPECT_THROW(bank.add_faces("ann", {cv::Mat(112, 92, CV_64F)}), std::invalid_argument);     // depth
    EXPECT_THROW(bank.scores(cv::Mat()), std::invalid_argument);
    EXPECT_TRUE(bank.scores(orl().faces[0][0]).names.empty());  // nobody trained yet
    EXPECT_FALSE(bank.decide(orl().faces[0][0]).known);
    try {
        bank.add_faces("ann", {cv::Mat(10, 10, CV_32F)});
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("92x112"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("10x10"), std::string::npos) << e.what();
    }
    ClassifierBankParams p = cropped_params();
    p.normalizer.output_size = {64, 64};  // differs from the EHMM face size
    EXPECT_THROW(ClassifierBank{p}, std::invalid_argument);
}

TEST(ClassifierBank, ScoringWhileRetrainingIsSafe) {
    ClassifierBank bank = make_bank(first(6));
    std::atomic<bool> stop{false};
    std::atomic<int> scored{0}, bad{0};
    std::vector<std::thread> readers;
    for (int t = 0; t < 3; ++t)
        readers.emplace_back([&, t] {
            std::size_t i = 0;
            while (!stop) {
                const cv::Mat& face = orl().faces[(t + i) % 6][5 + i % 5];
                const Decision d = bank.decide(face);
                if (d.ranked.size() < 5 || d.ranked.size() > 7 || !std::isfinite(d.score)) ++bad;
                ++scored, ++i;
            }
        });
    for (int round = 0; round < 4; ++round) {
        bank.add_faces(orl().names[round % 6], {orl().faces[round % 6][5 + round]});
        bank.train(orl().names[round % 6]);
        bank.add_faces(orl().names[6], train_faces(6));
        bank.train();
        bank.remove_person(orl().names[6]);
    }
    while (scored < 50) std::this_thread::yield();
    stop = true;
    for (auto& r : readers) r.join();
    EXPECT_EQ(bad, 0);
    EXPECT_EQ(bank.scores(orl().faces[0][0]).names.size(), 6u);
}
