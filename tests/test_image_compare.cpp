// tests/test_image_compare.cpp: app/image/image_compare.h and PNG reading (app/image/image_io.h) on the CPU: the
// metrics against cases computed by hand (identical images, a constant offset, constant images'
// SSIM), SSIM falling for shifted and noised copies, a mask restricting every metric, the hair's
// mask from a frame without hair, the error image's colour map ordered by lightness, and PNG input's
// bad files.
#include "app/image/image_compare.h"
#include "app/image/image_io.h"
#include "core/error.h"
#include "tests/test_support.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

using namespace wisp;
using wisp::test::TempDir;

namespace {

constexpr uint32_t kWidth = 48, kHeight = 40;

// A grey image of value f(x, y) (linear).
template <typename F> LinearImage image(F f, uint32_t width = kWidth, uint32_t height = kHeight)
{
    LinearImage out{.width = width, .height = height, .rgb = {}};
    for (uint32_t y = 0; y < height; ++y)
        for (uint32_t x = 0; x < width; ++x)
            out.rgb.push_back(glm::vec3(f(int(x), int(y))));
    return out;
}

// Structure at several scales, values in [0.05, 0.75]: something for SSIM's windows to compare.
float texture(int x, int y)
{
    return 0.4f + 0.2f * std::sin(0.7f * float(x)) * std::cos(0.45f * float(y)) +
           0.15f * std::sin(0.13f * float(x * y));
}

// Deterministic noise in [-1, 1] (a hash of the pixel).
float noise(int x, int y)
{
    uint32_t h = uint32_t(x) * 73856093u ^ uint32_t(y) * 19349663u;
    h ^= h >> 13;
    h *= 0x5bd1e995u;
    h ^= h >> 15;
    return float(h & 0xffffu) / 32767.5f - 1.0f;
}

double luminance(glm::vec3 c)
{
    return 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b;
}

} // namespace

TEST(ImageCompare, SrgbTransferIsTheStandards)
{
    EXPECT_EQ(decodeSrgb(0.0), 0.0);
    EXPECT_NEAR(decodeSrgb(1.0), 1.0, 1e-12);
    EXPECT_NEAR(decodeSrgb(0.04), 0.04 / 12.92, 1e-15);                // the linear toe
    EXPECT_NEAR(decodeSrgb(0.5), std::pow(0.555 / 1.055, 2.4), 1e-15); // the power segment
    EXPECT_NEAR(decodeSrgb(0.04045), 0.04045 / 12.92, 1e-7);           // the two meet
    for (double v : {0.001, 0.02, 0.2, 0.7})
        EXPECT_NEAR(decodeSrgb(encodeSrgb(v)), v, 1e-12);
}

TEST(ImageCompare, IdenticalImagesHaveNoError)
{
    LinearImage a = image(texture);
    ImageError e = imageError(a, a);
    EXPECT_EQ(e.pixels, size_t(kWidth) * kHeight);
    EXPECT_EQ(e.rmse, 0.0);
    EXPECT_EQ(e.relMse, 0.0);
    EXPECT_NEAR(e.ssim, 1.0, 1e-12);
    EXPECT_EQ(e.ssimPixels, size_t(kWidth - 10) * (kHeight - 10)); // the 'valid' window centres
}

TEST(ImageCompare, AConstantOffsetIsTheRmse)
{
    // Every pixel and channel 0.1 brighter: RMSE 0.1, whatever the picture.
    LinearImage a = image(texture);
    LinearImage b = image([](int x, int y) { return texture(x, y) + 0.1f; });
    EXPECT_NEAR(imageError(a, b).rmse, 0.1, 1e-6);
    EXPECT_NEAR(imageError(b, a).rmse, 0.1, 1e-6);

    // Constant images: relMSE is one term, and SSIM its luminance term alone (no variance: the
    // contrast and structure term is C2 / C2), on the encoded luma.
    LinearImage grey = image([](int, int) { return 0.25f; });
    LinearImage lighter = image([](int, int) { return 0.35f; });
    ImageError e = imageError(grey, lighter);
    EXPECT_NEAR(e.relMse, 0.01 / (0.35 * 0.35 + kRelMseEpsilon), 1e-6);
    double ya = encodeSrgb(0.25), yb = encodeSrgb(0.35), c1 = kSsimK1 * kSsimK1;
    EXPECT_NEAR(e.ssim, (2.0 * ya * yb + c1) / (ya * ya + yb * yb + c1), 1e-6);
    EXPECT_LT(e.ssim, 1.0);
}

TEST(ImageCompare, SsimFallsForShiftedAndNoisedCopies)
{
    LinearImage a = image(texture);
    LinearImage shifted = image([](int x, int y) { return texture(x + 1, y); });
    double ssimShifted = imageError(shifted, a).ssim;
    EXPECT_LT(ssimShifted, 0.99);
    EXPECT_GT(ssimShifted, -1.0);

    double previousSsim = 1.0, previousRmse = 0.0;
    for (float amplitude : {0.01f, 0.05f, 0.2f}) {
        LinearImage noised = image([&](int x, int y) { return texture(x, y) + amplitude * noise(x, y); });
        ImageError e = imageError(noised, a);
        EXPECT_LT(e.ssim, previousSsim) << "noise " << amplitude;
        EXPECT_GT(e.rmse, previousRmse) << "noise " << amplitude;
        previousSsim = e.ssim;
        previousRmse = e.rmse;
    }
}

TEST(ImageCompare, TheMaskRestrictsEveryMetric)
{
    // The images differ by 0.2 in columns 40.. (outside the mask) and by 0.1 in a 4 x 4 block at
    // (2, 2) inside it; the mask is columns 0..19.
    LinearImage a = image(texture);
    LinearImage b = image([](int x, int y) {
        float d = x >= 40 ? 0.2f : (x >= 2 && x < 6 && y >= 2 && y < 6) ? 0.1f : 0.0f;
        return texture(x, y) + d;
    });
    std::vector<uint8_t> mask(size_t(kWidth) * kHeight, 0);
    for (uint32_t y = 0; y < kHeight; ++y)
        for (uint32_t x = 0; x < 20; ++x)
            mask[y * kWidth + x] = 1;
    ImageError inMask = imageError(a, b, mask);
    ImageError frame = imageError(a, b);
    size_t n = 20 * kHeight;
    EXPECT_EQ(inMask.pixels, n);
    EXPECT_NEAR(inMask.rmse, 0.1 * std::sqrt(16.0 / double(n)), 1e-6);
    EXPECT_GT(frame.rmse, inMask.rmse);
    EXPECT_GT(frame.relMse, inMask.relMse);
    // Window centres in columns 5..19: the ones past column 9 see no difference at all.
    EXPECT_EQ(inMask.ssimPixels, size_t(15) * (kHeight - 10));
    EXPECT_LT(inMask.ssim, 1.0);
    EXPECT_GT(inMask.ssim, frame.ssim);

    // Outside the block the masked metrics see no difference: the mask is all they read.
    std::vector<uint8_t> away(mask.size(), 0);
    for (uint32_t y = 20; y < kHeight; ++y)
        for (uint32_t x = 12; x < 28; ++x)
            away[y * kWidth + x] = 1;
    ImageError untouched = imageError(a, b, away);
    EXPECT_EQ(untouched.rmse, 0.0);
    EXPECT_NEAR(untouched.ssim, 1.0, 1e-12);
}

TEST(ImageCompare, HairIsWhereTheFrameDiffersFromTheFrameWithoutHair)
{
    PngImage without{.width = 4, .height = 2, .rgba = std::vector<uint16_t>(4 * 2 * 4, 100 * 257)};
    PngImage with = without;
    with.rgba[4 * 1 + 0] = 103 * 257; // pixel 1: red 3 levels brighter
    with.rgba[4 * 6 + 2] = 98 * 257;  // pixel 6: blue 2 levels darker
    with.rgba[4 * 7 + 3] = 0;         // pixel 7: alpha only (not colour)
    EXPECT_EQ(hairMask(with, without, 0.0), (std::vector<uint8_t>{0, 1, 0, 0, 0, 0, 1, 0}));
    EXPECT_EQ(hairMask(with, without, 2.0), (std::vector<uint8_t>{0, 1, 0, 0, 0, 0, 0, 0}));
}

TEST(ImageCompare, TheErrorColoursRiseInLightness)
{
    double previous = -1.0;
    for (int i = 0; i <= 255; ++i) {
        glm::vec3 c = errorColor(double(i) / 255.0);
        for (int k = 0; k < 3; ++k) {
            EXPECT_GE(c[k], 0.0f);
            EXPECT_LE(c[k], 1.0f);
        }
        EXPECT_GT(luminance(c), previous) << "step " << i;
        previous = luminance(c);
    }
    EXPECT_LT(luminance(errorColor(0.0)), 0.02); // no error: dark
    EXPECT_GT(luminance(errorColor(1.0)), 0.7);  // the scale: light
    glm::vec3 top = errorColor(1.0);
    EXPECT_GT(top.r, top.b); // pale yellow, not white or blue
}

TEST(ImageCompare, TheErrorImageMapsErrorOverScale)
{
    std::vector<float> errors = {0.0f, 0.05f, 0.1f, 0.4f};
    std::vector<uint8_t> rgba = falseColor(errors, 0.1);
    ASSERT_EQ(rgba.size(), 16u);
    auto encoded = [](double t) {
        glm::vec3 c = errorColor(t);
        return std::vector<uint8_t>{uint8_t(std::lround(encodeSrgb(c.r) * 255.0)),
                                    uint8_t(std::lround(encodeSrgb(c.g) * 255.0)),
                                    uint8_t(std::lround(encodeSrgb(c.b) * 255.0)), 255};
    };
    EXPECT_EQ(std::vector<uint8_t>(rgba.begin(), rgba.begin() + 4), encoded(0.0));
    EXPECT_EQ(std::vector<uint8_t>(rgba.begin() + 4, rgba.begin() + 8), encoded(128.0 / 255.0)); // half the scale
    EXPECT_EQ(std::vector<uint8_t>(rgba.begin() + 8, rgba.begin() + 12), encoded(1.0));
    EXPECT_EQ(std::vector<uint8_t>(rgba.begin() + 12, rgba.end()), encoded(1.0)); // beyond it: clamped
}

TEST(ImageCompare, PixelErrorIsTheRmsOverChannels)
{
    LinearImage a{.width = 1, .height = 1, .rgb = {glm::vec3(0.5f, 0.5f, 0.5f)}};
    LinearImage b{.width = 1, .height = 1, .rgb = {glm::vec3(0.5f, 0.8f, 0.9f)}};
    EXPECT_NEAR(pixelErrors(a, b)[0], std::sqrt((0.09 + 0.16) / 3.0), 1e-6);
}

TEST(PngInput, ReadsWhatWasWrittenAt16Bits)
{
    TempDir dir;
    std::vector<uint8_t> rgba = {0, 1, 128, 255, 255, 254, 10, 200};
    writePng(dir / "two.png", 2, 1, rgba);
    PngImage png = readPng(dir / "two.png", "test");
    ASSERT_EQ(png.width, 2u);
    ASSERT_EQ(png.height, 1u);
    ASSERT_EQ(png.rgba.size(), rgba.size());
    for (size_t i = 0; i < rgba.size(); ++i)
        EXPECT_EQ(png.rgba[i], rgba[i] * 257) << i;
    LinearImage linear = linearImage(png);
    EXPECT_NEAR(linear.rgb[0].b, decodeSrgb(128.0 / 255.0), 1e-6);
    EXPECT_EQ(linear.rgb[1].r, 1.0f);
}

TEST(PngInput, BadFilesNameTheFileAndWhy)
{
    TempDir dir;
    auto message = [](const std::filesystem::path& path) {
        try {
            readPng(path, "the test image");
        } catch (const UserError& e) {
            return std::string(e.what());
        }
        return std::string("no error");
    };
    std::string missing = message(dir / "missing.png");
    EXPECT_NE(missing.find("the test image " + (dir / "missing.png").string() + ": no such file"), std::string::npos)
        << missing;
    wisp::test::writeFile(dir / "text.png", "not a picture\n");
    EXPECT_NE(message(dir / "text.png").find("not a PNG file"), std::string::npos) << message(dir / "text.png");
    std::filesystem::create_directory(dir / "folder.png");
    EXPECT_NE(message(dir / "folder.png").find("is a folder"), std::string::npos);
    // A real PNG cut short: the signature is right, the data is not.
    writePng(dir / "whole.png", 16, 16, std::vector<uint8_t>(16 * 16 * 4, 90));
    std::string bytes = wisp::test::readFile(dir / "whole.png");
    wisp::test::writeFile(dir / "cut.png", bytes.substr(0, 40));
    std::string cut = message(dir / "cut.png");
    EXPECT_NE(cut.find("cut.png: cannot decode the PNG"), std::string::npos) << cut;
}

// The linear output is an OpenEXR file an independent decoder reads: ffmpeg's (libavcodec's own
// EXR decoder) gives back every channel's float exactly, the rows in order, alpha apart.
TEST(ExrOutput, FfmpegReadsBackEveryFloat)
{
    TempDir dir;
    constexpr uint32_t kW = 5, kH = 3;
    std::vector<float> rgba(kW * kH * 4);
    for (size_t i = 0; i < rgba.size(); ++i)
        rgba[i] = float(i % 4 == 3 ? double(i) / double(rgba.size()) : 0.37 * double(i) + 1e-3 * double(i * i));
    rgba[0] = 123456.5f; // beyond 8 and 16 bits' range: floats
    rgba[5] = 2.5e-6f;
    writeExr(dir / "frame.exr", kW, kH, rgba);
    std::filesystem::path raw = dir / "frame.raw";
    std::string command = "ffmpeg -v error -y -i '" + (dir / "frame.exr").string() +
                          "' -f rawvideo -pix_fmt gbrapf32le '" + raw.string() + "' 2>&1";
    ASSERT_EQ(std::system(command.c_str()), 0) << command;
    std::string bytes = wisp::test::readFile(raw);
    ASSERT_EQ(bytes.size(), rgba.size() * 4); // planes G, B, R, A, each kW x kH
    auto plane = [&](int p, size_t pixel) {
        float f = 0.0f;
        std::memcpy(&f, bytes.data() + (size_t(p) * kW * kH + pixel) * 4, 4);
        return f;
    };
    for (size_t i = 0; i < size_t(kW) * kH; ++i) {
        EXPECT_EQ(plane(2, i), rgba[i * 4 + 0]) << i;
        EXPECT_EQ(plane(0, i), rgba[i * 4 + 1]) << i;
        EXPECT_EQ(plane(1, i), rgba[i * 4 + 2]) << i;
        EXPECT_EQ(plane(3, i), rgba[i * 4 + 3]) << i;
    }
}

TEST(ExrOutput, BadPathsAreRefusedAndNothingIsLeft)
{
    TempDir dir;
    auto message = [](const std::filesystem::path& path) {
        try {
            writeExr(path, 1, 1, {1.0f, 2.0f, 3.0f, 1.0f});
        } catch (const UserError& e) {
            return std::string(e.what());
        }
        return std::string("no error");
    };
    EXPECT_NE(message(dir / "missing" / "a.exr").find("does not exist"), std::string::npos);
    EXPECT_NE(message(dir / "a.tiff").find("must be a .png or an .exr"), std::string::npos);
    std::filesystem::create_directory(dir / "folder.exr");
    EXPECT_NE(message(dir / "folder.exr").find("is a directory"), std::string::npos);
    size_t entries = 0;
    for ([[maybe_unused]] const auto& e : std::filesystem::directory_iterator(dir.path()))
        ++entries;
    EXPECT_EQ(entries, 1u); // the folder made above: no temporary, no file
}
