// The tracker on real faces: two ORL faces rendered into frames cross each other and are found
// by the real detector; identities must survive the crossing. Also: a face that leaves and comes
// back, the assignment solver, and bad inputs.
#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include "facesocial/detection.hpp"
#include "facesocial/face_detector.hpp"
#include "facesocial/face_normalizer.hpp"
#include "facesocial/face_tracker.hpp"
#include "facesocial/image_io.hpp"
#include "support/test_data.hpp"

using namespace facesocial;

namespace {

cv::Mat orl_face_2x(int person, int image) {
    const cv::Mat f = load_image(test::data() / "orl" / ("s" + std::to_string(person)) / (std::to_string(image) + ".pgm"),
                                 ImageColor::Bgr);
    cv::Mat big;
    cv::resize(f, big, {}, 2.0, 2.0, cv::INTER_LINEAR);
    return big;
}

struct Scene {
    cv::Mat frame;
    cv::Rect a, b;  // where the two faces are drawn (b on top)
};

/// Frame t of a crossing: A moves right, B moves left, at the same height; B is drawn over A.
Scene crossing_frame(const cv::Mat& fa, const cv::Mat& fb, int t, int frames) {
    Scene s;
    s.frame = cv::Mat(480, 640, CV_8UC3, cv::Scalar(120, 125, 130));
    const int span = 640 - fa.cols;
    const int xa = span * t / (frames - 1), xb = span - xa;
    s.a = cv::Rect(xa, 120, fa.cols, fa.rows);
    s.b = cv::Rect(xb, 130, fb.cols, fb.rows);
    fa.copyTo(s.frame(s.a));
    fb.copyTo(s.frame(s.b));
    return s;
}

/// Runs the detector over the crossing and returns, per frame, the track id of the detection
/// that matches each face's drawn box best (0 when that face was not detected).
std::vector<std::pair<int, int>> track_crossing(double appearance_weight) {
    const cv::Mat fa = orl_face_2x(1, 1), fb = orl_face_2x(5, 1);
    const auto detector = FaceDetector::create(CascadeDetectorParams::fast_frontal());
    const FaceNormalizer normalizer;
    TrackerParams p;
    p.appearance_weight = appearance_weight;
    FaceTracker tracker(p);
    const int frames = 40;
    std::vector<std::pair<int, int>> ids;
    for (int t = 0; t < frames; ++t) {
        const Scene s = crossing_frame(fa, fb, t, frames);
        std::vector<TrackerInput> in;
        for (const Detection& d : detector->detect(s.frame))
            in.push_back({d.box, appearance_signature(normalizer.normalize(s.frame, d.box).pixels)});
        const TrackerUpdate up = tracker.update(in);
        // Each detection belongs to the drawn face it overlaps most, if by IoU >= 0.5; while the
        // drawn faces overlap each other much, a detection cannot be attributed.
        int id_a = 0, id_b = 0;
        for (std::size_t i = 0; i < in.size() && iou(s.a, s.b) < 0.3; ++i) {
            const double oa = iou(in[i].box, s.a), ob = iou(in[i].box, s.b);
            if (std::max(oa, ob) < 0.5) continue;
            (oa > ob ? id_a : id_b) = up.track_of[i];
        }
        ids.emplace_back(id_a, id_b);
    }
    return ids;
}

void expect_identities_kept(const std::vector<std::pair<int, int>>& ids) {
    const int a0 = ids.front().first, b0 = ids.front().second;
    ASSERT_GT(a0, 0);
    ASSERT_GT(b0, 0);
    ASSERT_NE(a0, b0);
    int a_seen_after = 0, b_seen_after = 0;
    for (std::size_t t = 0; t < ids.size(); ++t) {
        if (ids[t].first) EXPECT_EQ(ids[t].first, a0) << "face A at frame " << t;
        if (ids[t].second) EXPECT_EQ(ids[t].second, b0) << "face B at frame " << t;
        if (t > ids.size() * 3 / 4) a_seen_after += ids[t].first != 0, b_seen_after += ids[t].second != 0;
    }
    // Both faces are found again well after the crossing, so the check above has teeth.
    EXPECT_GE(a_seen_after, 5);
    EXPECT_GE(b_seen_after, 5);
}

}  // namespace

TEST(FaceTracker, KeepsIdentitiesThroughACrossingOfTwoRealFaces) {
    expect_identities_kept(track_crossing(1.0));
}

TEST(FaceTracker, KeepsIdentitiesThroughACrossingOnMotionAlone) {
    expect_identities_kept(track_crossing(0.0));
}

TEST(FaceTracker, AFaceThatLeavesBrieflyKeepsItsTrackAndOneGoneLongerGetsANewOne) {
    TrackerParams p;
    p.max_missed = 5;
    FaceTracker tracker(p);
    const cv::Rect box(100, 100, 80, 80);
    const int first = tracker.update({{box, {}}}).track_of[0];
    EXPECT_EQ(tracker.update({{box + cv::Point(4, 0), {}}}).track_of[0], first);
    for (int i = 0; i < 4; ++i) EXPECT_TRUE(tracker.update({}).ended.empty());
    ASSERT_EQ(tracker.tracks().size(), 1u);
    EXPECT_EQ(tracker.tracks()[0].missed, 4);
    // Back where its motion predicted (4 px per frame for 5 more frames).
    EXPECT_EQ(tracker.update({{box + cv::Point(4 + 5 * 4, 0), {}}}).track_of[0], first);
    for (int i = 0; i < 5; ++i) EXPECT_TRUE(tracker.update({}).ended.empty());
    const TrackerUpdate gone = tracker.update({});
    ASSERT_EQ(gone.ended.size(), 1u);
    EXPECT_EQ(gone.ended[0], first);
    const TrackerUpdate back = tracker.update({{box, {}}});
    ASSERT_EQ(back.started.size(), 1u);
    EXPECT_GT(back.track_of[0], first);
}

TEST(FaceTracker, EveryFaceGetsItsOwnTrackAndFarFacesStartNewOnes) {
    FaceTracker tracker;
    const TrackerUpdate one = tracker.update({{{0, 0, 50, 50}, {}}, {{300, 0, 50, 50}, {}}});
    ASSERT_EQ(one.started.size(), 2u);
    EXPECT_NE(one.track_of[0], one.track_of[1]);
    const TrackerUpdate two = tracker.update({{{302, 0, 50, 50}, {}}, {{2, 0, 50, 50}, {}}, {{150, 300, 50, 50}, {}}});
    EXPECT_EQ(two.track_of[0], one.track_of[1]);
    EXPECT_EQ(two.track_of[1], one.track_of[0]);
    EXPECT_EQ(two.started.size(), 1u);
}

TEST(FaceTracker, AssignmentIsOptimalAndRespectsForbiddenPairs) {
    // Greedy would take (0,0)=1 then be forced into (1,1)=10; the optimum is 2 + 3.
    cv::Mat cost = (cv::Mat_<double>(2, 2) << 1, 2, 3, 10);
    EXPECT_EQ(assign_min_cost(cost, 100), (std::vector<int>{1, 0}));
    cv::Mat wide = (cv::Mat_<double>(2, 3) << 5, 1, 100, 100, 100, 100);
    EXPECT_EQ(assign_min_cost(wide, 100), (std::vector<int>{1, -1}));
    cv::Mat tall = (cv::Mat_<double>(3, 1) << 4, 2, 9);
    EXPECT_EQ(assign_min_cost(tall, 100), (std::vector<int>{-1, 0, -1}));
    EXPECT_TRUE(assign_min_cost(cv::Mat(0, 3, CV_64F), 1).empty());
}

TEST(FaceTracker, AppearanceSignaturesSeparatePeople) {
    const FaceNormalizer n(NormalizerParams::cropped());
    auto sig = [&](int person, int image) {
        return appearance_signature(
            n.normalize(load_image(test::data() / "orl" / ("s" + std::to_string(person)) / (std::to_string(image) + ".pgm"),
                                   ImageColor::Grey))
                .pixels);
    };
    const cv::Mat a1 = sig(1, 1), a2 = sig(1, 2), b1 = sig(5, 1);
    EXPECT_EQ(a1.cols, 168);
    EXPECT_NEAR(cv::norm(a1), 1.0, 1e-5);
    EXPECT_GT(a1.dot(a2), a1.dot(b1));
}

TEST(FaceTracker, BadInputsGiveClearErrors) {
    TrackerParams p;
    p.velocity_smoothing = 1.0;
    EXPECT_THROW(FaceTracker{p}, std::invalid_argument);
    FaceTracker tracker;
    EXPECT_THROW(tracker.update({{{0, 0, 0, 10}, {}}}), std::invalid_argument);
    EXPECT_THROW(tracker.update({{{0, 0, 10, 10}, cv::Mat::ones(1, 4, CV_32F)}, {{50, 0, 10, 10}, cv::Mat::ones(1, 5, CV_32F)}}),
                 std::invalid_argument);
    EXPECT_THROW(appearance_signature(cv::Mat()), std::invalid_argument);
    EXPECT_THROW(appearance_signature(cv::Mat(10, 10, CV_8UC3)), std::invalid_argument);
    EXPECT_THROW(assign_min_cost(cv::Mat(2, 2, CV_32F), 1), std::invalid_argument);
}
