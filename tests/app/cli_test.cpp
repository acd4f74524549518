// Runs the facesocial command-line tool as a user would.
#include <array>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>

#include <sstream>

#include <gtest/gtest.h>
#include <opencv2/videoio.hpp>

#include "support/test_data.hpp"

namespace {

struct CliRun {
    int code;
    std::string out;
};

CliRun run(const std::string& args) {
    const std::string cmd = std::string(FACESOCIAL_CLI_PATH) + " " + args + " 2>&1";
    FILE* pipe = popen(cmd.c_str(), "r");
    if (!pipe) return {-1, ""};
    std::string out;
    std::array<char, 4096> buf;
    while (std::size_t n = fread(buf.data(), 1, buf.size(), pipe)) out.append(buf.data(), n);
    const int status = pclose(pipe);
    return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, out};
}

}  // namespace

TEST(Cli, DetectPrintsJsonLinesAndWritesCropsAndAnnotations) {
    facesocial::test::TempDir out;
    const auto image = facesocial::test::data() / "caltech_faces1999_partial" / "images" / "image_0001.jpg";
    const CliRun r = run("detect " + image.string() + " --profile --json --out " + out.path().string());
    ASSERT_EQ(r.code, 0) << r.out;
    EXPECT_NE(r.out.find("\"faces\":[{\"box\""), std::string::npos) << r.out;
    EXPECT_TRUE(std::filesystem::exists(out / "image_0001_annotated.jpg"));
    EXPECT_TRUE(std::filesystem::exists(out / "image_0001_face0.png"));
}

TEST(Cli, NonImageFileIsAClearErrorNotACrash) {
    facesocial::test::TempDir dir;
    std::ofstream(dir / "readme.jpg") << "plain text";
    const CliRun r = run("detect " + (dir / "readme.jpg").string());
    EXPECT_EQ(r.code, 1) << r.out;
    EXPECT_NE(r.out.find("not an image"), std::string::npos) << r.out;
    const CliRun missing = run("detect " + (dir / "absent.jpg").string());
    EXPECT_EQ(missing.code, 1);
    EXPECT_NE(missing.out.find("no such file"), std::string::npos) << missing.out;
}

TEST(Cli, UsageErrorsExitWithTwo) {
    EXPECT_EQ(run("").code, 2);
    EXPECT_EQ(run("frobnicate").code, 2);
    EXPECT_EQ(run("detect").code, 2);
    EXPECT_EQ(run("detect x.jpg --bogus").code, 2);
    EXPECT_EQ(run("eval nothing").code, 2);
}

TEST(Cli, EnrolTrainRecognizeForgetRoundTrip) {
    facesocial::test::TempDir dir;
    const auto orl = facesocial::test::data() / "orl";
    const std::string bank = (dir / "people.fsb").string();
    for (const char* person : {"s1", "s2", "s3"}) {
        std::string files;
        for (int i = 1; i <= 5; ++i) files += " " + (orl / person / (std::to_string(i) + ".pgm")).string();
        const CliRun r = run("enrol --bank " + bank + " --person " + person + files);
        ASSERT_EQ(r.code, 0) << r.out;
        EXPECT_NE(r.out.find("need training"), std::string::npos) << r.out;
    }
    const CliRun trained = run("train --bank " + bank + " --json");
    ASSERT_EQ(trained.code, 0) << trained.out;
    EXPECT_NE(trained.out.find("\"trained\":[\"s1\",\"s2\",\"s3\"]"), std::string::npos) << trained.out;

    const CliRun rec = run("recognize --bank " + bank + " " + (orl / "s2" / "8.pgm").string() + " --top 2 --json");
    ASSERT_EQ(rec.code, 0) << rec.out;
    EXPECT_NE(rec.out.find("\"known\":true,\"name\":\"s2\""), std::string::npos) << rec.out;
    EXPECT_NE(rec.out.find("\"candidates\":[{\"name\":\"s2\""), std::string::npos) << rec.out;
    // A margin no one reaches makes every face unknown, but the candidates stay.
    const CliRun strict = run("recognize --bank " + bank + " " + (orl / "s2" / "8.pgm").string() + " --min-margin 1000");
    ASSERT_EQ(strict.code, 0) << strict.out;
    EXPECT_NE(strict.out.find(": unknown"), std::string::npos) << strict.out;

    ASSERT_EQ(run("forget --bank " + bank + " --person s2").code, 0);
    const CliRun after = run("recognize --bank " + bank + " " + (orl / "s2" / "8.pgm").string() + " --json");
    EXPECT_EQ(after.out.find("\"name\":\"s2\""), std::string::npos) << after.out;
    EXPECT_EQ(run("forget --bank " + bank + " --person s2").code, 2);  // not enrolled any more
}

TEST(Cli, BankCommandsRejectDamagedBanksAndMissingArguments) {
    facesocial::test::TempDir dir;
    std::ofstream(dir / "bad.fsb") << "not a bank";
    const auto face = facesocial::test::data() / "orl" / "s1" / "1.pgm";
    const CliRun bad = run("recognize --bank " + (dir / "bad.fsb").string() + " " + face.string());
    EXPECT_EQ(bad.code, 1);
    EXPECT_NE(bad.out.find("not a FaceSocial bank file"), std::string::npos) << bad.out;
    // Enrolling into a damaged bank must not overwrite it.
    EXPECT_EQ(run("enrol --bank " + (dir / "bad.fsb").string() + " --person x " + face.string()).code, 1);
    std::ifstream in(dir / "bad.fsb");
    EXPECT_EQ(std::string(std::istreambuf_iterator<char>(in), {}), "not a bank");
    EXPECT_EQ(run("enrol --person x " + face.string()).code, 2);
    EXPECT_EQ(run("enrol --bank b.fsb " + face.string()).code, 2);
    EXPECT_EQ(run("train").code, 2);
    EXPECT_EQ(run("recognize --bank " + (dir / "missing.fsb").string() + " " + face.string()).code, 1);
}

TEST(Cli, EvalIdentifyOnEssexFolders) {
    const auto essex = facesocial::test::data() / "essex_faces94_subset";
    const CliRun r = run("eval identify --train " + (essex / "train").string() + " --test " + (essex / "test").string() +
                         " --methods ehmm --json");
    ASSERT_EQ(r.code, 0) << r.out;
    EXPECT_NE(r.out.find("\"method\":\"ehmm\",\"accuracy\":1,\"faces\":68"), std::string::npos) << r.out;
}

TEST(Cli, EvalUnknownReportsEveryRuleAndTheMarginRuleSeparatesStrangersBest) {
    const CliRun r = run("eval unknown --json");
    ASSERT_EQ(r.code, 0) << r.out;
    const std::string& j = r.out;
    auto eer = [&](const std::string& rule) {
        const auto at = j.find("\"" + rule + "\":{");
        EXPECT_NE(at, std::string::npos) << rule;
        const auto e = j.find("\"eer\":", at);
        return std::stod(j.substr(e + 6));
    };
    EXPECT_NE(j.find("\"known_probes\":1400,\"unknown_probes\":400"), std::string::npos) << j;
    EXPECT_LT(eer("min_margin"), eer("min_score"));
    EXPECT_LT(eer("min_margin"), eer("min_variance"));
    EXPECT_LT(eer("min_margin"), 0.15);
}

namespace {

/// The number after "key": in a JSON text, from position `from`.
double json_number(const std::string& j, const std::string& key, std::size_t from = 0) {
    const auto at = j.find("\"" + key + "\":", from);
    if (at == std::string::npos) {
        ADD_FAILURE() << key << " not in " << j;
        return NAN;
    }
    return std::stod(j.substr(at + key.size() + 3));
}

}  // namespace

TEST(Cli, WatchWritesAnAnnotatedVideoAndTrackEvents) {
    facesocial::test::TempDir dir;
    const auto orl = facesocial::test::data() / "orl";
    const std::string bank = (dir / "bank.fsb").string();
    for (const char* p : {"s1", "s2"}) ASSERT_EQ(run("enrol --bank " + bank + " --person " + p + " " + (orl / p).string()).code, 0);
    ASSERT_EQ(run("train --bank " + bank).code, 0);
    const auto clip = facesocial::test::data() / "video_hamilton" / "short_hamilton_clip.mp4";
    const CliRun r = run("watch --bank " + bank + " " + clip.string() + " --window 10 --out " + (dir / "out.mp4").string() +
                         " --events " + (dir / "events.jsonl").string() + " --json");
    ASSERT_EQ(r.code, 0) << r.out;
    EXPECT_EQ(json_number(r.out, "frames"), 275);
    EXPECT_GE(json_number(r.out, "tracks"), 2);
    cv::VideoCapture video((dir / "out.mp4").string());
    ASSERT_TRUE(video.isOpened());
    EXPECT_EQ(int(video.get(cv::CAP_PROP_FRAME_COUNT)), 275);
    std::ifstream events(dir / "events.jsonl");
    std::string line, last;
    int started = 0, lost = 0;
    while (std::getline(events, line)) {
        EXPECT_EQ(line.front(), '{');
        EXPECT_EQ(line.back(), '}');
        started += line.find("\"event\":\"track_started\"") != std::string::npos;
        lost += line.find("\"event\":\"track_lost\"") != std::string::npos;
        last = line;
    }
    EXPECT_GE(started, 2);
    EXPECT_EQ(started, lost);
    EXPECT_NE(last.find("\"event\":\"stream_ended\",\"frame\":275"), std::string::npos) << last;

    // A missing camera and a file that is no video: clear errors, exit code 1.
    const CliRun camera = run("watch --bank " + bank + " 7");
    EXPECT_EQ(camera.code, 1);
    EXPECT_NE(camera.out.find("camera 7"), std::string::npos) << camera.out;
    const CliRun garbage = run("watch --bank " + bank + " " + (dir / "events.jsonl").string());
    EXPECT_EQ(garbage.code, 1);
    EXPECT_NE(garbage.out.find("not a video"), std::string::npos) << garbage.out;
    EXPECT_EQ(run("watch " + clip.string()).code, 2);
}

TEST(Cli, EvalWindowShowsAccumulationBeatingSingleFrames) {
    facesocial::test::TempDir dir;
    const CliRun r = run("eval window --out " + dir.path().string() + " --json");
    ASSERT_EQ(r.code, 0) << r.out;
    // windows: 1, 2, 3, 4, 5, 6, 8, 10, 12, 15, 20, 25 (index 11), ...
    auto curve = [&](const std::string& set) {
        const auto at = r.out.find("\"set\":\"" + set + "\",\"mode\":\"average\",\"accuracy\":[");
        EXPECT_NE(at, std::string::npos) << r.out;
        std::vector<double> v;
        std::stringstream ss(r.out.substr(r.out.find('[', at) + 1));
        for (double x; ss >> x;) {
            v.push_back(x);
            if (ss.peek() == ']') break;
            ss.ignore();
        }
        return v;
    };
    for (const char* set : {"essex", "orl"}) {
        const auto acc = curve(set);
        ASSERT_GE(acc.size(), 12u) << set;
        EXPECT_GT(acc[11], acc[0] + 0.04) << set;
    }
    EXPECT_TRUE(std::filesystem::exists(dir / "window.csv"));
    EXPECT_GT(std::filesystem::file_size(dir / "window.png"), 5000u);
}

TEST(Cli, EvalThresholdAccumulationLowersFalsePositives) {
    facesocial::test::TempDir dir;
    const CliRun r = run("eval threshold --out " + dir.path().string() + " --json");
    ASSERT_EQ(r.code, 0) << r.out;
    // The paper's rule (variance of the score vector): accumulation lowers the false positives
    // at the threshold that keeps 95% of known frames. With the margin rule, per-frame false
    // positives are already few (about 5% on ORL) and accumulation lowers its equal-error rate.
    const auto var = r.out.find("\"set\":\"orl\",\"rule\":\"min_variance\"");
    ASSERT_NE(var, std::string::npos) << r.out;
    EXPECT_LT(json_number(r.out, "false_positive_accumulated", var), json_number(r.out, "false_positive_frame", var));
    const auto at = r.out.find("\"set\":\"orl\",\"rule\":\"min_margin\"");
    ASSERT_NE(at, std::string::npos) << r.out;
    EXPECT_LT(json_number(r.out, "eer_accumulated", at), json_number(r.out, "eer_frame", at));
    EXPECT_LT(json_number(r.out, "false_positive_frame", at), 0.10);
    EXPECT_TRUE(std::filesystem::exists(dir / "threshold_orl_min_margin.png"));
}

TEST(Cli, TagResolvesTagsEnrolsThemAndNamesTheOtherFaces) {
    facesocial::test::TempDir dir;
    const auto data = facesocial::test::data();
    const std::string bank = (dir / "bank.fsb").string();
    for (const char* p : {"s1", "s2", "s3"})
        ASSERT_EQ(run("enrol --bank " + bank + " --person " + p + " " + (data / "orl" / p).string()).code, 0);
    ASSERT_EQ(run("train --bank " + bank).code, 0);
    const std::string photo = (data / "dlib_faces" / "2008_002470.jpg").string();
    const CliRun faces = run("detect " + photo + " --json");
    ASSERT_EQ(faces.code, 0) << faces.out;
    // Tag the first detected face at its centre.
    const auto box = faces.out.find("\"box\"");
    const double x = json_number(faces.out, "x", box), y = json_number(faces.out, "y", box), w = json_number(faces.out, "w", box),
                 h = json_number(faces.out, "h", box);
    std::ofstream(dir / "tags.json") << "[{\"person\": \"s2\", \"x\": " << x + w / 2 << ", \"y\": " << y + h / 2 << "}]";
    std::ofstream(dir / "graph.json") << "{\"friendships\": [[\"s1\", \"s2\"], [\"s2\", \"s3\"]]}";
    const CliRun r = run("tag --bank " + bank + " " + photo + " --tags " + (dir / "tags.json").string() + " --graph " +
                         (dir / "graph.json").string() + " --enrol --out " + (dir / "tagged.jpg").string() + " --json");
    ASSERT_EQ(r.code, 0) << r.out;
    EXPECT_NE(r.out.find("\"person\":\"s2\",\"outcome\":\"resolved\""), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("\"name_with_friends\":"), std::string::npos) << r.out;
    EXPECT_TRUE(std::filesystem::exists(dir / "tagged.jpg"));
    const CliRun trained = run("train --bank " + bank + " --json");
    EXPECT_NE(trained.out.find("s2"), std::string::npos) << trained.out;  // the tagged face made s2 stale

    // Bad tags: outside the photo, a person twice, someone not in the graph, malformed JSON.
    auto tag_with = [&](const std::string& json) {
        std::ofstream(dir / "bad.json") << json;
        return run("tag --bank " + bank + " " + photo + " --tags " + (dir / "bad.json").string() + " --graph " +
                   (dir / "graph.json").string());
    };
    const CliRun outside = tag_with("[{\"person\": \"s1\", \"x\": 5000, \"y\": 10}]");
    EXPECT_EQ(outside.code, 2);
    EXPECT_NE(outside.out.find("inside the"), std::string::npos) << outside.out;
    EXPECT_EQ(tag_with("[{\"person\": \"s1\", \"x\": 5, \"y\": 5}, {\"person\": \"s1\", \"x\": 50, \"y\": 5}]").code, 2);
    const CliRun stranger = tag_with("[{\"person\": \"zed\", \"x\": 5, \"y\": 5}]");
    EXPECT_EQ(stranger.code, 2);
    EXPECT_NE(stranger.out.find("zed"), std::string::npos) << stranger.out;
    EXPECT_EQ(tag_with("[{\"person\": \"s1\", \"x\": 5").code, 1);
}

TEST(Cli, EvalTaggingFriendPriorHelpsAndAShuffledGraphDoesNotHurt) {
    const CliRun r = run("eval tagging --photos 80 --json");
    ASSERT_EQ(r.code, 0) << r.out;
    const double unique = json_number(r.out, "accuracy_one_person_per_face");
    EXPECT_GT(json_number(r.out, "accuracy_friend_prior"), unique + 0.01);
    EXPECT_GE(json_number(r.out, "accuracy_shuffled_graph"), unique - 0.005);
    EXPECT_GT(json_number(r.out, "lift"), 2.0);
    EXPECT_LT(json_number(r.out, "lift_shuffled"), 1.3);
    const auto dlib = r.out.find("\"dlib_tag_to_face\"");
    EXPECT_GE(json_number(r.out, "right_face", dlib), 38);
    EXPECT_EQ(json_number(r.out, "wrong_face", dlib), 0);
}

TEST(Cli, EvalTrainingPolicyPrunesWrongTagsAndReportsEveryPolicy) {
    const CliRun r = run("eval training-policy --samples 20 --wrong 0.2 --json");
    ASSERT_EQ(r.code, 0) << r.out;
    auto field = [&](const std::string& policy, const std::string& key) {
        const auto at = r.out.find("\"policy\":\"" + policy + "\"");
        EXPECT_NE(at, std::string::npos) << policy << " in " << r.out;
        return json_number(r.out, key, at);
    };
    const double wrong = json_number(r.out, "wrong_tags");
    EXPECT_GT(wrong, 80);
    EXPECT_EQ(field("all", "wrong_kept"), wrong);
    EXPECT_LT(field("all, pruned (2 sigma)", "wrong_kept"), 0.25 * wrong);  // 100 samples: 3 of 1184 kept
    EXPECT_GT(field("cap 10, spread", "accuracy"), field("cap 5, newest", "accuracy"));
    EXPECT_GT(field("all", "train_seconds"), field("cap 5, newest", "train_seconds"));
}
