#include <cmath>

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include "facesocial/face_detector.hpp"
#include "facesocial/face_normalizer.hpp"
#include "facesocial/image_io.hpp"
#include "support/test_data.hpp"

using namespace facesocial;

TEST(FaceNormalizer, ZeroMeanUnitStdInsideEllipseZeroOutside) {
    const cv::Mat image = load_image(test::data() / "caltech_faces1999_partial" / "images" / "image_0001.jpg");
    const auto faces = FaceDetector::create()->detect(image);
    ASSERT_FALSE(faces.empty());
    NormalizerParams p;
    p.output_size = {64, 80};
    const FaceNormalizer n(p);
    const NormalizedFace f = n.normalize(image, faces[0].box);
    ASSERT_EQ(f.pixels.type(), CV_32FC1);
    ASSERT_EQ(f.pixels.size(), cv::Size(64, 80));
    cv::Scalar mean, sd;
    cv::meanStdDev(f.pixels, mean, sd, f.mask);
    EXPECT_NEAR(mean[0], 0.0, 1e-4);
    EXPECT_NEAR(sd[0], 1.0, 1e-4);
    EXPECT_EQ(f.mask.at<uchar>(0, 0), 0);
    EXPECT_EQ(f.mask.at<uchar>(40, 32), 255);
    EXPECT_EQ(f.pixels.at<float>(0, 0), 0.f);
    EXPECT_EQ(f.pixels.at<float>(79, 63), 0.f);
    EXPECT_TRUE(cv::checkRange(f.pixels));
    const double inside = cv::countNonZero(f.mask) / double(64 * 80);
    EXPECT_NEAR(inside, M_PI / 4, 0.03);  // an inscribed ellipse covers pi/4 of its box
}

TEST(FaceNormalizer, SameFaceUnderDifferentBrightnessNormalisesAlike) {
    const cv::Mat grey = load_image(test::data() / "orl" / "s3" / "4.pgm", ImageColor::Grey);
    cv::Mat darker;
    grey.convertTo(darker, CV_8U, 0.5, 10);
    const FaceNormalizer n;
    const NormalizedFace a = n.normalize(grey), b = n.normalize(darker);
    const double diff = cv::norm(a.pixels, b.pixels, cv::NORM_L2) / std::sqrt(double(cv::countNonZero(a.mask)));
    EXPECT_LT(diff, 0.2);
    // Without normalisation the pixels differ a lot.
    EXPECT_GT(cv::norm(grey, darker, cv::NORM_L2) / std::sqrt(double(grey.total())), 20.0);
}

TEST(FaceNormalizer, FlatImageGivesZerosNotNaN) {
    const FaceNormalizer n;
    const NormalizedFace f = n.normalize(cv::Mat(50, 50, CV_8UC1, cv::Scalar(77)));
    EXPECT_TRUE(cv::checkRange(f.pixels));
    EXPECT_EQ(cv::countNonZero(f.pixels != 0), 0);
}

TEST(FaceNormalizer, VerticalMarginReplicatesBorderAtImageEdge) {
    const cv::Mat grey = load_image(test::data() / "orl" / "s1" / "1.pgm", ImageColor::Grey);
    NormalizerParams p;
    p.vertical_margin = 0.2;
    const NormalizedFace f = FaceNormalizer(p).normalize(grey, cv::Rect(0, 0, 92, 112));
    EXPECT_TRUE(cv::checkRange(f.pixels));
    EXPECT_EQ(f.pixels.size(), cv::Size(92, 112));
}

TEST(FaceNormalizer, BadInputsGiveClearErrors) {
    const FaceNormalizer n;
    const cv::Mat image(100, 100, CV_8UC3, cv::Scalar(1, 2, 3));
    EXPECT_THROW(n.normalize(cv::Mat()), std::invalid_argument);
    EXPECT_THROW(n.normalize(cv::Mat(100, 100, CV_16UC1, cv::Scalar(0))), std::invalid_argument);
    EXPECT_THROW(n.normalize(cv::Mat(100, 100, CV_32FC3, cv::Scalar(0))), std::invalid_argument);
    EXPECT_THROW(n.normalize(cv::Mat(100, 100, CV_8UC4, cv::Scalar(0))), std::invalid_argument);
    EXPECT_THROW(n.normalize(image, cv::Rect(90, 90, 20, 20)), std::invalid_argument);
    EXPECT_THROW(n.normalize(image, cv::Rect(200, 200, 20, 20)), std::invalid_argument);
    EXPECT_THROW(n.normalize(image, cv::Rect(0, 0, 4, 4)), std::invalid_argument);
    try {
        n.normalize(cv::Mat(100, 100, CV_16UC1, cv::Scalar(0)));
        FAIL();
    } catch (const std::invalid_argument& e) {
        EXPECT_STREQ(e.what(), "FaceNormalizer::normalize: expected an 8-bit 1- or 3-channel image, got CV_16UC1");
    }
    NormalizerParams p;
    p.output_size = {8, 8};
    EXPECT_THROW(FaceNormalizer{p}, std::invalid_argument);
    p = {};
    p.vertical_margin = -0.1;
    EXPECT_THROW(FaceNormalizer{p}, std::invalid_argument);
    EXPECT_THROW(FaceNormalizer::to_8bit({}), std::invalid_argument);
}
