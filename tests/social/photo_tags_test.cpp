// Tags to faces on real group photos (dlib_faces): nearest-face choice, profile refusal, one tag
// per face, bad tags.
#include <gtest/gtest.h>

#include "facesocial/datasets.hpp"
#include "facesocial/front_end.hpp"
#include "facesocial/image_io.hpp"
#include "facesocial/photo_tags.hpp"
#include "support/test_data.hpp"

using namespace facesocial;

namespace {

cv::Point2f centre(const cv::Rect& r) { return {r.x + r.width / 2.f, r.y + r.height / 2.f}; }

/// A dlib_faces photo with at least `n` annotated faces, and its frontal detections.
struct GroupPhoto {
    cv::Mat image;
    std::vector<cv::Rect> truth;
    std::vector<Detection> faces;
};

GroupPhoto group_photo(std::size_t n) {
    FrontEndParams p;
    p.normalize = false;
    const FrontEnd front_end(p);
    for (const AnnotatedImage& a : load_dlib_faces(test::data())) {
        if (a.faces.size() < n) continue;
        GroupPhoto g{load_image(a.file), a.faces, {}};
        for (const FrontEndFace& f : front_end.process(g.image).faces) g.faces.push_back(f.detection);
        if (g.faces.size() >= n) return g;
    }
    ADD_FAILURE() << "no dlib_faces photo with " << n << " detected faces";
    return {};
}

}  // namespace

TEST(PhotoTags, EachTagResolvesToTheNearestDetectedFace) {
    const GroupPhoto g = group_photo(3);
    ASSERT_GE(g.faces.size(), 3u);
    std::vector<PhotoTag> tags;
    for (std::size_t k = 0; k < 3; ++k) {
        const cv::Rect b = g.faces[k].box;
        tags.push_back({"p" + std::to_string(k), centre(b) + cv::Point2f(0.2f * b.width, -0.15f * b.height)});
    }
    const auto r = resolve_tags(g.faces, tags, g.image.size());
    for (std::size_t k = 0; k < 3; ++k) {
        EXPECT_EQ(r[k].outcome, TagOutcome::Resolved) << r[k].reason;
        EXPECT_EQ(r[k].face, int(k));
        EXPECT_LT(r[k].distance, 0.3);
    }
    // A tag far from every face resolves to nothing.
    const auto far = resolve_tags({g.faces[0]}, {{"x", centre(g.faces[0].box) + cv::Point2f(2.f * g.faces[0].box.width, 0)}},
                                  g.image.size());
    if (far[0].tag.point.x < g.image.cols) EXPECT_EQ(far[0].outcome, TagOutcome::NoFaceNearby);
}

TEST(PhotoTags, AProfileNearestFaceIsRefusedEvenWithAFrontalFaceNearby) {
    GroupPhoto g = group_photo(2);
    ASSERT_GE(g.faces.size(), 2u);
    // Make the first face a profile (as the profile detector would report it) and tag next to
    // it: the tag must yield nothing, never the frontal neighbour.
    g.faces[0].pose = FacePose::ProfileLeft;
    const auto r = resolve_tags(g.faces, {{"ann", centre(g.faces[0].box)}}, g.image.size());
    EXPECT_EQ(r[0].outcome, TagOutcome::NearestIsProfile);
    EXPECT_EQ(r[0].face, 0);
    EXPECT_NE(r[0].reason.find("profile"), std::string::npos);
}

TEST(PhotoTags, OneTagPerFaceTheNearerTagWins) {
    const GroupPhoto g = group_photo(1);
    const cv::Rect b = g.faces[0].box;
    const auto r = resolve_tags({g.faces[0]}, {{"ann", centre(b) + cv::Point2f(0.3f * b.width, 0)}, {"bob", centre(b)}},
                                g.image.size());
    EXPECT_EQ(r[1].outcome, TagOutcome::Resolved);
    EXPECT_EQ(r[0].outcome, TagOutcome::FaceTaken);
    EXPECT_NE(r[0].reason.find("bob"), std::string::npos);
}

TEST(PhotoTags, BadTagsGiveClearErrors) {
    const GroupPhoto g = group_photo(1);
    const cv::Size size = g.image.size();
    EXPECT_THROW(resolve_tags(g.faces, {{"ann", {-1.f, 5.f}}}, size), std::invalid_argument);
    EXPECT_THROW(resolve_tags(g.faces, {{"ann", {float(size.width), 5.f}}}, size), std::invalid_argument);
    EXPECT_THROW(resolve_tags(g.faces, {{"", {5.f, 5.f}}}, size), std::invalid_argument);
    EXPECT_THROW(resolve_tags(g.faces, {{"ann", {5.f, 5.f}}, {"ann", {50.f, 5.f}}}, size), std::invalid_argument);
    EXPECT_THROW(resolve_tags(g.faces, {{"zed", {5.f, 5.f}}}, size, {}, {"ann", "bob"}), std::invalid_argument);
    try {
        resolve_tags(g.faces, {{"ann", {5.f, 5000.f}}}, size);
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("inside the"), std::string::npos);
    }
    TagResolverParams p;
    p.max_distance = 0;
    EXPECT_THROW(resolve_tags(g.faces, {}, size, p), std::invalid_argument);
}
