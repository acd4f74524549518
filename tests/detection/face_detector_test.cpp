#include <fstream>

#include <gtest/gtest.h>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "facesocial/datasets.hpp"
#include "facesocial/detection_eval.hpp"
#include "facesocial/error.hpp"
#include "facesocial/face_detector.hpp"
#include "facesocial/image_io.hpp"
#include "support/test_data.hpp"

using namespace facesocial;

namespace {

const AnnotatedImage& group_photo() {
    // 2008_001322.jpg: three people, boxes from dlib's training.xml.
    static const std::vector<AnnotatedImage> all = load_dlib_faces(test::data());
    for (const auto& a : all)
        if (a.file.filename() == "2008_001322.jpg") return a;
    throw std::runtime_error("2008_001322.jpg not in dlib_faces");
}

const FaceDetector& frontal() {
    static const auto d = FaceDetector::create();
    return *d;
}

}  // namespace

TEST(FaceDetector, FindsTheHandLabelledFacesOfAGroupPhoto) {
    const auto& photo = group_photo();
    const cv::Mat image = load_image(photo.file);
    const auto found = frontal().detect(image);
    const DetectionCounts c = match_detections(photo.faces, found, 0.5);
    EXPECT_EQ(c.true_positives, int(photo.faces.size()));
    EXPECT_LE(c.false_positives, 1);
    for (const auto& d : found) {
        EXPECT_EQ(d.pose, FacePose::Frontal);
        EXPECT_GT(d.confidence, 0.f);
        EXPECT_LT(d.confidence, 1.f);
        EXPECT_EQ(d.box & cv::Rect(0, 0, image.cols, image.rows), d.box);
    }
}

TEST(FaceDetector, GreyAndColourInputGiveTheSameFaces) {
    const cv::Mat bgr = load_image(group_photo().file);
    cv::Mat grey;
    cv::cvtColor(bgr, grey, cv::COLOR_BGR2GRAY);
    const auto a = frontal().detect(bgr);
    const auto b = frontal().detect(grey);
    ASSERT_EQ(a.size(), b.size());
    for (std::size_t i = 0; i < a.size(); ++i) EXPECT_EQ(a[i].box, b[i].box);
}

TEST(FaceDetector, ProfileRunsOnBothSidesAndMirrorsPose) {
    // A real face turned sideways is found by the profile cascade on one side; mirroring the
    // image must find the same face with the opposite pose at the mirrored place.
    const cv::Mat frame = load_image(test::data() / "dlib_faces" / "2008_002470.jpg");
    CascadeDetectorParams p = profile_cascade_params();
    const auto profile = FaceDetector::create(p);
    const auto found = profile->detect(frame);
    ASSERT_FALSE(found.empty()) << "no profile face in 2008_002470.jpg";
    cv::Mat mirrored;
    cv::flip(frame, mirrored, 1);
    const auto found_m = profile->detect(mirrored);
    ASSERT_FALSE(found_m.empty());
    const Detection& d = found[0];
    bool matched = false;
    for (const auto& m : found_m) {
        const cv::Rect back(frame.cols - m.box.x - m.box.width, m.box.y, m.box.width, m.box.height);
        if (iou(back, d.box) > 0.5) {
            matched = true;
            EXPECT_NE(m.pose, d.pose);
            EXPECT_TRUE(is_profile(m.pose));
        }
    }
    EXPECT_TRUE(matched);
    p.mirror_profile = false;
    for (const auto& x : FaceDetector::create(p)->detect(frame)) EXPECT_EQ(x.pose, FacePose::ProfileLeft);
}

TEST(FaceDetector, CombinedDetectorMergesFrontalAndProfile) {
    const cv::Mat image = load_image(group_photo().file);
    std::vector<std::shared_ptr<FaceDetector>> parts = {FaceDetector::create(),
                                                       FaceDetector::create(profile_cascade_params())};
    const auto combined = FaceDetector::combine(parts);
    const auto all = combined->detect(image);
    for (std::size_t i = 0; i < all.size(); ++i)
        for (std::size_t j = i + 1; j < all.size(); ++j) EXPECT_LT(iou(all[i].box, all[j].box), 0.3);
    const DetectionCounts c = match_detections(group_photo().faces, all, 0.5);
    EXPECT_EQ(c.true_positives, int(group_photo().faces.size()));
    EXPECT_NE(combined->name().find("profile"), std::string::npos);
}

TEST(FaceDetector, DownscaledWorkingFrameMapsBoxesBack) {
    const cv::Mat image = load_image(test::data() / "caltech_faces1999_partial" / "images" / "image_0001.jpg");
    const auto full = frontal().detect(image);
    CascadeDetectorParams p;
    p.max_working_width = image.cols / 2;
    const auto half = FaceDetector::create(p)->detect(image);
    ASSERT_FALSE(full.empty());
    ASSERT_FALSE(half.empty());
    EXPECT_GT(iou(full[0].box, half[0].box), 0.6);
}

TEST(FaceDetector, BadImagesGiveClearErrors) {
    auto expect_message = [](const cv::Mat& m, const std::string& part) {
        try {
            frontal().detect(m);
            FAIL() << "no exception for " << part;
        } catch (const std::invalid_argument& e) {
            EXPECT_NE(std::string(e.what()).find(part), std::string::npos) << e.what();
            EXPECT_NE(std::string(e.what()).find("expected"), std::string::npos) << e.what();
        }
    };
    expect_message(cv::Mat(), "empty");
    expect_message(cv::Mat(100, 100, CV_16UC1, cv::Scalar(0)), "CV_16UC1");
    expect_message(cv::Mat(100, 100, CV_32FC1, cv::Scalar(0)), "CV_32FC1");
    expect_message(cv::Mat(100, 100, CV_8UC4, cv::Scalar(0)), "CV_8UC4");
    expect_message(cv::Mat(10, 8, CV_8UC1, cv::Scalar(0)), "at least 24x24 pixels");  // tiny
    expect_message(cv::Mat(10, 8, CV_8UC1, cv::Scalar(0)), "got 8x10");
}

TEST(FaceDetector, MissingOrUnreadableCascadeIsAFileError) {
    CascadeDetectorParams p;
    p.cascade_file = "/nonexistent/cascade.xml";
    EXPECT_THROW(FaceDetector::create(p), FileError);
    p.cascade_file = "no_such_cascade.xml";
    try {
        FaceDetector::create(p);
        FAIL();
    } catch (const FileError& e) {
        EXPECT_NE(std::string(e.what()).find("/usr/share/opencv4"), std::string::npos) << e.what();
    }
    test::TempDir dir;
    std::ofstream(dir / "junk.xml") << "this is not a cascade";
    p.cascade_file = dir / "junk.xml";
    EXPECT_THROW(FaceDetector::create(p), FileError);
}

TEST(FaceDetector, ParamsAreValidated) {
    CascadeDetectorParams p;
    EXPECT_NO_THROW(p.validate());
    p.scale_factor = 1.0;
    EXPECT_THROW(p.validate(), std::invalid_argument);
    p = {};
    p.min_neighbors = 0;
    EXPECT_THROW(FaceDetector::create(p), std::invalid_argument);
    p = {};
    p.max_face_size = 10;
    EXPECT_THROW(p.validate(), std::invalid_argument);
    p = {};
    p.max_working_width = -1;
    EXPECT_THROW(p.validate(), std::invalid_argument);
    EXPECT_NO_THROW(CascadeDetectorParams::fast_frontal().validate());
}

TEST(FaceDetector, FindsCascadesOfOpencvData) {
    EXPECT_TRUE(std::filesystem::exists(find_cascade(default_cascade_file(CascadeKind::Frontal))));
    EXPECT_TRUE(std::filesystem::exists(find_cascade(default_cascade_file(CascadeKind::Profile))));
    EXPECT_THROW(find_cascade(""), std::invalid_argument);
}
