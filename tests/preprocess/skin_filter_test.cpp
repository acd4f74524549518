#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include "facesocial/face_detector.hpp"
#include "facesocial/image_io.hpp"
#include "facesocial/skin_filter.hpp"
#include "support/test_data.hpp"

using namespace facesocial;

namespace {

cv::Mat caltech(const std::string& name) {
    return load_image(test::data() / "caltech_faces1999_partial" / "images" / name);
}

cv::Rect first_face(const cv::Mat& image) {
    const auto found = FaceDetector::create()->detect(image);
    if (found.empty()) throw std::runtime_error("no face found");
    return found[0].box;
}

}  // namespace

TEST(SkinFilter, PeerRuleOnKnownColours) {
    const SkinFilter f;
    cv::Mat px(1, 4, CV_8UC3);
    px.at<cv::Vec3b>(0, 0) = {120, 150, 210};  // BGR of a typical skin tone: R 210, G 150, B 120
    px.at<cv::Vec3b>(0, 1) = {40, 200, 40};    // green
    px.at<cv::Vec3b>(0, 2) = {128, 128, 128};  // grey
    px.at<cv::Vec3b>(0, 3) = {190, 225, 235};  // flash-lit skin: R 235, G 225, B 190
    const cv::Mat m = f.skin_mask(px);
    EXPECT_EQ(m.at<uchar>(0, 0), 255);
    EXPECT_EQ(m.at<uchar>(0, 1), 0);
    EXPECT_EQ(m.at<uchar>(0, 2), 0);
    EXPECT_EQ(m.at<uchar>(0, 3), 255);
    SkinFilterParams daylight;
    daylight.rule = SkinRule::PeerDaylight;
    EXPECT_EQ(SkinFilter(daylight).skin_mask(px).at<uchar>(0, 3), 0);
}

TEST(SkinFilter, RealFaceHasMuchMoreSkinThanBackground) {
    const cv::Mat image = caltech("image_0001.jpg");
    const cv::Rect face = first_face(image);
    const SkinFilter f;
    const double on_face = f.skin_fraction(image, face);
    const double corner = f.skin_fraction(image, cv::Rect(0, 0, 40, 40));
    EXPECT_GT(on_face, 0.4);
    EXPECT_LT(corner, on_face / 2);
    EXPECT_GE(on_face, 0.0);
    EXPECT_LE(on_face, 1.0);
}

TEST(SkinFilter, DropsCandidatesUnderTheThresholdAndKeepsFaces) {
    const cv::Mat image = caltech("image_0001.jpg");
    const cv::Rect face = first_face(image);
    std::vector<Detection> candidates = {{face, FacePose::Frontal, 0.9f},
                                         {cv::Rect(0, 0, 40, 40), FacePose::Frontal, 0.5f}};
    const SkinFilter f;
    const bool corner_is_skinless = f.skin_fraction(image, candidates[1].box) < 0.2;
    ASSERT_TRUE(corner_is_skinless);
    const SkinFilterResult r = f.filter(image, candidates);
    EXPECT_FALSE(r.skipped);
    ASSERT_EQ(r.kept.size(), 1u);
    EXPECT_EQ(r.kept[0].box, face);
    ASSERT_EQ(r.rejected.size(), 1u);
    EXPECT_LT(r.rejected_fraction[0], 0.2);
    EXPECT_GE(r.kept_fraction[0], 0.2);
}

TEST(SkinFilter, GreyImagesSkipTheFilterInsteadOfRejectingEverything) {
    const cv::Mat grey = load_image(test::data() / "orl" / "s1" / "1.pgm", ImageColor::Grey);
    const std::vector<Detection> c = {{cv::Rect(10, 10, 60, 60), FacePose::Frontal, 0.8f}};
    const SkinFilter f;
    EXPECT_TRUE(f.is_grey(grey));
    SkinFilterResult r = f.filter(grey, c);
    EXPECT_TRUE(r.skipped);
    EXPECT_EQ(r.kept.size(), 1u);
    // The same grey picture stored as a 3-channel image is still grey.
    cv::Mat bgr;
    cv::cvtColor(grey, bgr, cv::COLOR_GRAY2BGR);
    r = f.filter(bgr, c);
    EXPECT_TRUE(r.skipped);
    EXPECT_EQ(r.kept.size(), 1u);
    EXPECT_FALSE(f.is_grey(caltech("image_0001.jpg")));
}

TEST(SkinFilter, BadInputsGiveClearErrors) {
    const SkinFilter f;
    const cv::Mat image = caltech("image_0001.jpg");
    EXPECT_THROW(f.skin_fraction(image, cv::Rect(image.cols - 10, 0, 40, 40)), std::invalid_argument);
    EXPECT_THROW(f.skin_fraction(image, cv::Rect(image.cols + 5, 0, 10, 10)), std::invalid_argument);
    EXPECT_THROW(f.skin_fraction(image, cv::Rect(0, 0, 0, 10)), std::invalid_argument);
    EXPECT_THROW(f.skin_mask(cv::Mat()), std::invalid_argument);
    EXPECT_THROW(f.skin_mask(cv::Mat(10, 10, CV_8UC1)), std::invalid_argument);
    EXPECT_THROW(f.filter(cv::Mat(10, 10, CV_16UC3, cv::Scalar(0)), {}), std::invalid_argument);
    EXPECT_THROW(f.filter(cv::Mat(10, 10, CV_8UC4, cv::Scalar(0)), {}), std::invalid_argument);
    try {
        f.filter(image, {{cv::Rect(-5, 0, 20, 20), FacePose::Frontal, 1.f}});
        FAIL();
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("partly outside"), std::string::npos) << e.what();
    }
    SkinFilterParams p;
    p.min_skin_fraction = 1.5;
    EXPECT_THROW(SkinFilter{p}, std::invalid_argument);
}
