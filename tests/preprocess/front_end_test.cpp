#include <gtest/gtest.h>

#include "facesocial/front_end.hpp"
#include "facesocial/image_io.hpp"
#include "support/test_data.hpp"

using namespace facesocial;

TEST(FrontEnd, OnePersonPhotoGivesOneNormalisedFace) {
    const FrontEnd fe;
    const cv::Mat image = load_image(test::data() / "caltech_faces1999_partial" / "images" / "image_0001.jpg");
    const FrontEndResult r = fe.process(image);
    ASSERT_EQ(r.faces.size(), 1u);
    EXPECT_FALSE(r.skin_filter_skipped);
    EXPECT_GE(r.faces[0].skin_fraction, 0.2);
    EXPECT_EQ(r.faces[0].face.pixels.size(), fe.params().normalizer.output_size);
}

TEST(FrontEnd, MostCaltechPhotosGiveExactlyOneFace) {
    const FrontEnd fe;
    const auto files = list_images(test::data() / "caltech_faces1999_partial" / "images");
    ASSERT_GE(files.size(), 160u);
    int one = 0, n = 0;
    for (std::size_t i = 0; i < files.size(); i += 8, ++n) one += fe.process(load_image(files[i])).faces.size() == 1;
    EXPECT_GE(double(one) / n, 0.9) << one << " of " << n;
}

TEST(FrontEnd, GreyPhotoSkipsSkinFilter) {
    const FrontEnd fe;
    const cv::Mat grey = load_image(test::data() / "caltech_faces1999_partial" / "images" / "image_0001.jpg",
                                    ImageColor::Grey);
    const FrontEndResult r = fe.process(grey);
    EXPECT_TRUE(r.skin_filter_skipped);
    EXPECT_EQ(r.faces.size(), 1u);
}

TEST(FrontEnd, ParamsAreValidated) {
    FrontEndParams p;
    p.frontal.kind = CascadeKind::Profile;
    EXPECT_THROW(FrontEnd{p}, std::invalid_argument);
    p = {};
    p.skin.min_skin_fraction = -1;
    EXPECT_THROW(FrontEnd{p}, std::invalid_argument);
}
