#include <fstream>

#include <gtest/gtest.h>

#include "facesocial/error.hpp"
#include "facesocial/image_io.hpp"
#include "support/test_data.hpp"

using namespace facesocial;

TEST(ImageIo, LoadsGreyAndColourFilesInTheAskedForm) {
    const auto pgm = test::data() / "orl" / "s1" / "1.pgm";
    EXPECT_EQ(load_image(pgm, ImageColor::Grey).type(), CV_8UC1);
    EXPECT_EQ(load_image(pgm, ImageColor::Any).type(), CV_8UC1);
    EXPECT_EQ(load_image(pgm, ImageColor::Bgr).type(), CV_8UC3);
    EXPECT_EQ(load_image(pgm).size(), cv::Size(92, 112));
    const auto jpg = test::data() / "caltech_faces1999_partial" / "images" / "image_0001.jpg";
    EXPECT_EQ(load_image(jpg, ImageColor::Any).type(), CV_8UC3);
}

TEST(ImageIo, MissingDirectoryAndNonImageFilesAreFileErrors) {
    test::TempDir dir;
    EXPECT_THROW(load_image(dir / "none.jpg"), FileError);
    EXPECT_THROW(load_image(dir.path()), FileError);
    std::ofstream(dir / "notes.jpg") << "this is text, not a JPEG";
    try {
        load_image(dir / "notes.jpg");
        FAIL();
    } catch (const FileError& e) {
        EXPECT_NE(std::string(e.what()).find("not an image"), std::string::npos) << e.what();
        EXPECT_EQ(e.path(), (dir / "notes.jpg").string());
    }
}

TEST(ImageIo, ListsImagesInNaturalOrder) {
    const auto files = list_images(test::data() / "orl" / "s1");
    ASSERT_EQ(files.size(), 10u);
    EXPECT_EQ(files[0].filename(), "1.pgm");
    EXPECT_EQ(files[1].filename(), "2.pgm");
    EXPECT_EQ(files[9].filename(), "10.pgm");
    EXPECT_THROW(list_images(test::data() / "no_such_folder"), FileError);
}

TEST(ImageIo, SaveRoundTripAndUnwritablePath) {
    test::TempDir dir;
    const cv::Mat img = load_image(test::data() / "orl" / "s2" / "1.pgm", ImageColor::Grey);
    save_image(dir / "copy.png", img);
    EXPECT_EQ(cv::norm(load_image(dir / "copy.png", ImageColor::Grey), img, cv::NORM_INF), 0.0);
    EXPECT_THROW(save_image(dir / "missing_folder" / "x.png", img), FileError);
}
