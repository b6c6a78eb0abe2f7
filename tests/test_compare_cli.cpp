// tests/test_compare_cli.cpp: `wisp compare` through the real binary (no GPU): identical images
// measure no error, the JSON's numbers are the library's over the frame and the hair's mask, --out
// writes the error image, and every bad input (a missing file, not a PNG, sizes that differ, a mask
// with no hair, an output that cannot be written) ends with one line naming it, exit status 2 and
// no file written.
#include "app/image/image_compare.h"
#include "app/image/image_io.h"
#include "cli_support.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <string>
#include <vector>

using namespace wisp::test;

namespace {

constexpr uint32_t kWidth = 32, kHeight = 24;

// A frame: a gradient with a "head" square; with hair, a band of darker pixels over part of it.
std::vector<uint8_t> frame(bool hair, int brighten = 0)
{
    std::vector<uint8_t> rgba;
    for (uint32_t y = 0; y < kHeight; ++y)
        for (uint32_t x = 0; x < kWidth; ++x) {
            int v = 40 + int(4 * x + 3 * y);
            if (x >= 8 && x < 24 && y >= 4 && y < 20)
                v = 180;
            if (hair && y >= 6 && y < 12 && x >= 6 && x < 26)
                v = 60 + brighten + int(x % 3) * 20;
            rgba.insert(rgba.end(), {uint8_t(v), uint8_t(v * 3 / 4), uint8_t(v / 2), 255});
        }
    return rgba;
}

std::string quoted(const std::filesystem::path& p)
{
    return "'" + p.string() + "'";
}

} // namespace

TEST(CompareCli, IdenticalImagesHaveNoError)
{
    TempDir dir;
    wisp::writePng(dir / "a.png", kWidth, kHeight, frame(true));
    auto r = runWisp("compare " + quoted(dir / "a.png") + " " + quoted(dir / "a.png") + " --json");
    ASSERT_EQ(r.status, 0) << r.err;
    nlohmann::json j = nlohmann::json::parse(r.out);
    EXPECT_EQ(j["frame"]["rmse"].get<double>(), 0.0);
    EXPECT_EQ(j["frame"]["rel_mse"].get<double>(), 0.0);
    EXPECT_NEAR(j["frame"]["ssim"].get<double>(), 1.0, 1e-12);
    EXPECT_EQ(j["frame"]["pixels"].get<size_t>(), size_t(kWidth) * kHeight);
    EXPECT_TRUE(j["hair"].is_null());

    auto text = runWisp("compare " + quoted(dir / "a.png") + " " + quoted(dir / "a.png"));
    ASSERT_EQ(text.status, 0) << text.err;
    EXPECT_NE(text.out.find("RMSE"), std::string::npos) << text.out;
    EXPECT_NE(text.out.find("1.000000"), std::string::npos) << text.out; // SSIM
}

TEST(CompareCli, MeasuresTheFrameAndTheHairAndWritesTheErrorImage)
{
    TempDir dir;
    wisp::writePng(dir / "test.png", kWidth, kHeight, frame(true));
    wisp::writePng(dir / "reference.png", kWidth, kHeight, frame(true, 30));
    wisp::writePng(dir / "bald.png", kWidth, kHeight, frame(false));
    auto r = runWisp("compare " + quoted(dir / "test.png") + " " + quoted(dir / "reference.png") + " --mask " +
                     quoted(dir / "bald.png") + " --out " + quoted(dir / "error.png") + " --error-scale 0.2 --json");
    ASSERT_EQ(r.status, 0) << r.err;
    nlohmann::json j = nlohmann::json::parse(r.out);

    // The same numbers as the library's on the same files.
    wisp::PngImage test = wisp::readPng(dir / "test.png", "test");
    wisp::PngImage reference = wisp::readPng(dir / "reference.png", "reference");
    wisp::LinearImage a = wisp::linearImage(test), b = wisp::linearImage(reference);
    std::vector<uint8_t> mask = wisp::hairMask(test, wisp::readPng(dir / "bald.png", "bald"), 0.0);
    wisp::ImageError frameError = wisp::imageError(a, b), hairError = wisp::imageError(a, b, mask);
    EXPECT_DOUBLE_EQ(j["frame"]["rmse"].get<double>(), frameError.rmse);
    EXPECT_DOUBLE_EQ(j["frame"]["ssim"].get<double>(), frameError.ssim);
    EXPECT_DOUBLE_EQ(j["hair"]["rel_mse"].get<double>(), hairError.relMse);
    EXPECT_DOUBLE_EQ(j["hair"]["ssim"].get<double>(), hairError.ssim);
    // The hair is the band drawn over the frame: 20 x 6 pixels, all of which differ.
    EXPECT_EQ(j["hair"]["pixels"].get<size_t>(), 20u * 6u);
    // Only the hair differs, so the hair's error is larger than the frame's average.
    EXPECT_GT(j["hair"]["rmse"].get<double>(), j["frame"]["rmse"].get<double>());
    EXPECT_LT(j["hair"]["ssim"].get<double>(), 1.0);
    EXPECT_EQ(j["error_image"]["scale"].get<double>(), 0.2);

    wisp::PngImage error = wisp::readPng(dir / "error.png", "error");
    ASSERT_EQ(error.width, kWidth);
    ASSERT_EQ(error.height, kHeight);
    std::vector<uint8_t> expected = wisp::falseColor(wisp::pixelErrors(a, b), 0.2);
    for (size_t i = 0; i < expected.size(); ++i)
        ASSERT_EQ(error.rgba[i], expected[i] * 257) << "byte " << i;
    EXPECT_TRUE(partialFiles(dir.path()).empty());
}

TEST(CompareCli, BadInputNamesTheFileAndWritesNothing)
{
    TempDir dir;
    wisp::writePng(dir / "a.png", kWidth, kHeight, frame(true));
    wisp::writePng(dir / "small.png", 16, 12, std::vector<uint8_t>(16 * 12 * 4, 100));
    wisp::writePng(dir / "tiny.png", 8, 8, std::vector<uint8_t>(8 * 8 * 4, 100));
    writeFile(dir / "notes.png", "these are notes, not a picture\n");
    std::string a = quoted(dir / "a.png"), out = " --out " + quoted(dir / "error.png");

    expectUserError(runWisp("compare " + a + " " + quoted(dir / "missing.png") + out),
                    "the reference " + (dir / "missing.png").string() + ": no such file");
    expectUserError(runWisp("compare " + quoted(dir / "notes.png") + " " + a + out),
                    (dir / "notes.png").string() + ": not a PNG file");
    expectUserError(runWisp("compare " + a + " " + quoted(dir / "small.png") + out), "must be the same size");
    expectUserError(runWisp("compare " + a + " " + a + " --mask " + quoted(dir / "small.png") + out),
                    "--mask " + (dir / "small.png").string() + " is 16 x 12");
    expectUserError(runWisp("compare " + a + " " + a + " --mask " + a + out), "no hair to measure");
    expectUserError(runWisp("compare " + quoted(dir / "tiny.png") + " " + quoted(dir / "tiny.png") + out),
                    "11 x 11 window");
    expectUserError(runWisp("compare " + a + " " + a + " --out " + quoted(dir / "no" / "error.png")), "does not exist");
    expectUserError(runWisp("compare " + a + " " + a + " --out " + quoted(dir / "error.jpg")), ".png");
    expectUserError(runWisp("compare " + a + out + " --error-scale 0"), "--error-scale");
    expectUserError(runWisp("compare " + a), "reference");
    EXPECT_FALSE(std::filesystem::exists(dir / "error.png"));
    EXPECT_TRUE(partialFiles(dir.path()).empty());
}
