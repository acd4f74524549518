#include <gtest/gtest.h>

#include "facesocial/detection.hpp"
#include "facesocial/detection_eval.hpp"

using namespace facesocial;

TEST(Detection, IouOfIdenticalDisjointAndHalfOverlappingBoxes) {
    EXPECT_DOUBLE_EQ(iou({0, 0, 10, 10}, {0, 0, 10, 10}), 1.0);
    EXPECT_DOUBLE_EQ(iou({0, 0, 10, 10}, {20, 20, 10, 10}), 0.0);
    EXPECT_NEAR(iou({0, 0, 10, 10}, {5, 0, 10, 10}), 50.0 / 150.0, 1e-12);
    EXPECT_DOUBLE_EQ(iou({0, 0, 0, 0}, {0, 0, 0, 0}), 0.0);
    EXPECT_DOUBLE_EQ(containment({0, 0, 100, 100}, {10, 10, 20, 20}), 1.0);
}

TEST(Detection, MergeKeepsStrongestOfOverlappingGroupAndDisjointBoxes) {
    std::vector<Detection> d = {{{0, 0, 50, 50}, FacePose::Frontal, 0.5f},
                                {{5, 5, 50, 50}, FacePose::Frontal, 0.9f},
                                {{200, 0, 40, 40}, FacePose::Frontal, 0.4f}};
    const auto merged = merge_detections(d);
    ASSERT_EQ(merged.size(), 2u);
    EXPECT_EQ(merged[0].box, cv::Rect(5, 5, 50, 50));
    EXPECT_EQ(merged[1].box, cv::Rect(200, 0, 40, 40));
}

TEST(Detection, MergePrefersFrontalOverOverlappingProfile) {
    std::vector<Detection> d = {{{0, 0, 50, 50}, FacePose::ProfileLeft, 0.9f},
                                {{3, 3, 50, 50}, FacePose::Frontal, 0.6f}};
    auto merged = merge_detections(d);
    ASSERT_EQ(merged.size(), 1u);
    EXPECT_EQ(merged[0].pose, FacePose::Frontal);
    MergeParams p;
    p.prefer_frontal = false;
    merged = merge_detections(d, p);
    ASSERT_EQ(merged.size(), 1u);
    EXPECT_EQ(merged[0].pose, FacePose::ProfileLeft);
}

TEST(Detection, MergeRejectsBadThresholds) {
    MergeParams p;
    p.iou_threshold = 0;
    EXPECT_THROW(merge_detections({}, p), std::invalid_argument);
    p.iou_threshold = 0.3;
    p.containment_threshold = 1.5;
    EXPECT_THROW(p.validate(), std::invalid_argument);
}

TEST(DetectionEval, MatchesOneToOneAtIouThreshold) {
    const std::vector<cv::Rect> truth = {{0, 0, 10, 10}, {100, 100, 10, 10}};
    const std::vector<Detection> det = {{{1, 1, 10, 10}, FacePose::Frontal, 1.f},
                                        {{0, 0, 10, 10}, FacePose::Frontal, 1.f},  // duplicate of the first truth
                                        {{300, 300, 10, 10}, FacePose::Frontal, 1.f}};
    const DetectionCounts c = match_detections(truth, det, 0.5);
    EXPECT_EQ(c.true_positives, 1);
    EXPECT_EQ(c.false_positives, 2);
    EXPECT_EQ(c.false_negatives, 1);
    EXPECT_DOUBLE_EQ(c.recall(), 0.5);
    EXPECT_NEAR(c.precision(), 1.0 / 3.0, 1e-12);
}
