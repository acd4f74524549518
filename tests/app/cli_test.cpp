// Runs the facesocial command-line tool as a user would.
#include <array>
#include <cstdio>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "support/test_data.hpp"

namespace {

struct CliRun {
    int code;
    std::string out;
};

CliRun run(const std::string& args) {
    const std::string cmd = std::string(FACESOCIAL_CLI_PATH) + " " + args + " 2>&1";
    FILE* pipe = popen(cmd.c_str(), "r");
    if (!pipe) return {-1, ""};
    std::string out;
    std::array<char, 4096> buf;
    while (std::size_t n = fread(buf.data(), 1, buf.size(), pipe)) out.append(buf.data(), n);
    const int status = pclose(pipe);
    return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, out};
}

}  // namespace

TEST(Cli, DetectPrintsJsonLinesAndWritesCropsAndAnnotations) {
    facesocial::test::TempDir out;
    const auto image = facesocial::test::data() / "caltech_faces1999_partial" / "images" / "image_0001.jpg";
    const CliRun r = run("detect " + image.string() + " --profile --json --out " + out.path().string());
    ASSERT_EQ(r.code, 0) << r.out;
    EXPECT_NE(r.out.find("\"faces\":[{\"box\""), std::string::npos) << r.out;
    EXPECT_TRUE(std::filesystem::exists(out / "image_0001_annotated.jpg"));
    EXPECT_TRUE(std::filesystem::exists(out / "image_0001_face0.png"));
}

TEST(Cli, NonImageFileIsAClearErrorNotACrash) {
    facesocial::test::TempDir dir;
    std::ofstream(dir / "readme.jpg") << "plain text";
    const CliRun r = run("detect " + (dir / "readme.jpg").string());
    EXPECT_EQ(r.code, 1) << r.out;
    EXPECT_NE(r.out.find("not an image"), std::string::npos) << r.out;
    const CliRun missing = run("detect " + (dir / "absent.jpg").string());
    EXPECT_EQ(missing.code, 1);
    EXPECT_NE(missing.out.find("no such file"), std::string::npos) << missing.out;
}

TEST(Cli, UsageErrorsExitWithTwo) {
    EXPECT_EQ(run("").code, 2);
    EXPECT_EQ(run("frobnicate").code, 2);
    EXPECT_EQ(run("detect").code, 2);
    EXPECT_EQ(run("detect x.jpg --bogus").code, 2);
    EXPECT_EQ(run("eval nothing").code, 2);
}
