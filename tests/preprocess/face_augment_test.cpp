// augment_faces on real ORL faces: originals first, realistic variations, determinism, errors.
#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include "facesocial/face_augment.hpp"
#include "facesocial/image_io.hpp"
#include "support/test_data.hpp"

using namespace facesocial;

namespace {

std::vector<cv::Mat> orl_person(int n) {
    std::vector<cv::Mat> out;
    for (int i = 1; i <= n; ++i)
        out.push_back(load_image(test::data() / "orl" / "s5" / (std::to_string(i) + ".pgm"), ImageColor::Grey));
    return out;
}

}  // namespace

TEST(FaceAugment, KeepsOriginalsFirstAndMakesCloseButDifferentVariations) {
    const auto faces = orl_person(3);
    const auto grown = augment_faces(faces, 12, {}, 42);
    ASSERT_EQ(grown.size(), 12u);
    for (int i = 0; i < 3; ++i) EXPECT_EQ(cv::norm(grown[i], faces[i], cv::NORM_INF), 0.0);
    for (std::size_t i = 3; i < grown.size(); ++i) {
        EXPECT_EQ(grown[i].type(), CV_8UC1);
        EXPECT_EQ(grown[i].size(), faces[0].size());
        const cv::Mat& src = faces[i % 3];
        cv::Mat mirrored;
        cv::flip(src, mirrored, 1);
        const double diff = std::min(cv::norm(grown[i], src, cv::NORM_L1), cv::norm(grown[i], mirrored, cv::NORM_L1)) / double(src.total());
        EXPECT_GT(diff, 0.5) << i;    // not a copy
        EXPECT_LT(diff, 40.0) << i;   // still the same face, mean change well under 40 grey levels
    }
    // Deterministic for a seed, different for another.
    const auto again = augment_faces(faces, 12, {}, 42);
    const auto other = augment_faces(faces, 12, {}, 43);
    EXPECT_EQ(cv::norm(again[7], grown[7], cv::NORM_INF), 0.0);
    EXPECT_GT(cv::norm(other[7], grown[7], cv::NORM_INF), 0.0);
    EXPECT_EQ(augment_faces(faces, 2).size(), 2u);
}

TEST(FaceAugment, WorksOnFloatFacesAndRejectsBadInput) {
    auto faces = orl_person(2);
    std::vector<cv::Mat> floats;
    for (const auto& f : faces) floats.push_back(cv::Mat_<float>(f) / 255.0f);
    const auto grown = augment_faces(floats, 5);
    EXPECT_EQ(grown[4].type(), CV_32FC1);
    EXPECT_TRUE(cv::checkRange(grown[4]));
    EXPECT_THROW(augment_faces({}, 5), std::invalid_argument);
    EXPECT_THROW(augment_faces({faces[0], floats[1]}, 5), std::invalid_argument);
    EXPECT_THROW(augment_faces({cv::Mat(10, 10, CV_8UC3)}, 5), std::invalid_argument);
    AugmentParams p;
    p.max_rotation_deg = -1;
    EXPECT_THROW(augment_faces(faces, 5, p), std::invalid_argument);
}
