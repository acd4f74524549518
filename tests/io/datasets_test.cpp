#include <cstdlib>
#include <fstream>

#include <gtest/gtest.h>

#include "facesocial/datasets.hpp"
#include "facesocial/error.hpp"
#include "support/test_data.hpp"

using namespace facesocial;

TEST(Datasets, DlibFacesHasTheFortyThreeHandDrawnBoxes) {
    const auto all = load_dlib_faces(test::data());
    ASSERT_EQ(all.size(), 9u);
    int faces = 0;
    for (const auto& a : all) {
        EXPECT_TRUE(std::filesystem::exists(a.file)) << a.file;
        faces += int(a.faces.size());
    }
    EXPECT_EQ(faces, 43);
    EXPECT_EQ(all[0].file.filename(), "2007_007763.jpg");
    EXPECT_EQ(all[0].faces[0], cv::Rect(194, 90, 37, 37));
}

TEST(Datasets, MalformedImglabFilesAreFormatErrors) {
    test::TempDir dir;
    std::ofstream(dir / "foreign.xml") << "<opencv_storage></opencv_storage>";
    EXPECT_THROW(load_imglab_xml(dir / "foreign.xml"), ModelFormatError);
    std::ofstream(dir / "bad.xml") << "<images><image file='a.jpg'><box top='x' left='1' width='2' height='3'/></image></images>";
    EXPECT_THROW(load_imglab_xml(dir / "bad.xml"), ModelFormatError);
    EXPECT_THROW(load_imglab_xml(dir / "missing.xml"), FileError);
}

TEST(Datasets, OrlIdentityFoldersInNaturalOrder) {
    const auto people = load_identity_folders(test::data() / "orl");
    ASSERT_EQ(people.size(), 40u);
    EXPECT_EQ(people[0].name, "s1");
    EXPECT_EQ(people[1].name, "s2");
    EXPECT_EQ(people[39].name, "s40");
    for (const auto& p : people) EXPECT_EQ(p.images.size(), 10u);
    test::TempDir empty;
    EXPECT_THROW(load_identity_folders(empty.path()), FileError);
}

TEST(Datasets, NaturalOrder) {
    EXPECT_TRUE(natural_less("s2", "s10"));
    EXPECT_FALSE(natural_less("s10", "s2"));
    EXPECT_TRUE(natural_less("a", "b"));
    EXPECT_TRUE(natural_less("img_002", "img_10"));
    EXPECT_FALSE(natural_less("x", "x"));
}

TEST(Datasets, DataRootComesFromTheEnvironment) {
    const std::string saved = test::data().string();
    ::setenv("FACESOCIAL_DATA", "/no/such/dir", 1);
    EXPECT_THROW(data_root(), FileError);
    ::unsetenv("FACESOCIAL_DATA");
    EXPECT_THROW(data_root(), FileError);
    ::setenv("FACESOCIAL_DATA", saved.c_str(), 1);
    EXPECT_EQ(data_root(), std::filesystem::path(saved));
}
