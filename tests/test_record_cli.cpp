// tests/test_record_cli.cpp: `wisp record` through the real binary: the same command gives the
// same frames (and a video), outputs checked before any work, an earlier run's folder refused (or
// overwritten when asked, never mixed), the contact sheet's every frame numbered, and a lost device
// that keeps the frames written, each complete.
#include "app/session/record.h"
#include "cli_support.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <stb_image.h>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <regex>
#include <string>
#include <vector>

using namespace wisp::test;

TEST(Record, SameCommandGivesTheSameFramesAndAVideo)
{
    TempDir dir;
    std::string common =
        "record --frames 4 --width 96 --height 64 --guides 60 --set strands_per_guide=4 --wind 4,0,0 --out ";
    bool ffmpeg = std::system("command -v ffmpeg >/dev/null 2>&1") == 0;
    auto first = runWisp("--validation " + common + "'" + (dir / "a").string() + "'" +
                         (ffmpeg ? " --video '" + (dir / "a.mp4").string() + "'" : std::string()));
    ASSERT_EQ(first.status, 0) << first.err;
    auto second = runWisp(common + "'" + (dir / "b").string() + "'");
    ASSERT_EQ(second.status, 0) << second.err;
    for (const char* name : {"frame_00000.png", "frame_00003.png", "contact_sheet.png"}) {
        ASSERT_TRUE(std::filesystem::exists(dir / "a" / name)) << name;
        EXPECT_EQ(readFile(dir / "a" / name), readFile(dir / "b" / name)) << name;
    }
    EXPECT_NE(readFile(dir / "a" / "frame_00000.png"), readFile(dir / "a" / "frame_00003.png")); // the hair moved
    EXPECT_FALSE(std::filesystem::exists(dir / "a" / "frame_00004.png"));
    if (!ffmpeg)
        GTEST_SKIP() << "ffmpeg is not installed (Debian package ffmpeg): the video was not tested";
    std::string video = readFile(dir / "a.mp4");
    ASSERT_GT(video.size(), 100u);
    EXPECT_EQ(video.substr(4, 4), "ftyp"); // an MP4 file
}

TEST(BadInput, RecordOutputsAreCheckedFirst)
{
    TempDir dir;
    writeFile(dir / "file", "not a folder");
    expectUserError(runWisp("record --frames 1 --out '" + (dir / "file").string() + "'"), "not a folder");
    expectUserError(runWisp("record --frames 1 --out /nonexistent/deep/frames"), "/nonexistent/deep");
    expectUserError(runWisp("record --frames 1 --out '" + (dir / "f").string() + "' --video /nonexistent/v.mp4"),
                    "/nonexistent");
    EXPECT_FALSE(std::filesystem::exists(dir / "f")); // nothing created
    expectUserError(runWisp("record --frames 0 --out '" + (dir / "g").string() + "'"), "--frames");
}

TEST(Record, DeviceLostKeepsTheFramesWrittenAndMakesNoSheetOrVideo)
{
    static_assert(wisp::kExitDeviceLost != wisp::kExitUserError && wisp::kExitDeviceLost != wisp::kExitInternalError);
    TempDir dir;
    bool ffmpeg = std::system("command -v ffmpeg >/dev/null 2>&1") == 0;
    // About 15 submissions set up the renderer and the solver, then one per frame: the loss comes
    // after a few frames.
    std::string video = ffmpeg ? " --video '" + (dir / "run.mp4").string() + "'" : "";
    auto r = runWisp("--validation record --frames 12 --width 96 --height 64 --guides 60 --set strands_per_guide=4 "
                     "--out '" +
                         (dir / "frames").string() + "'" + video,
                     lostAt(22));
    expectDeviceLost(r, "record");
    std::smatch m;
    ASSERT_TRUE(std::regex_search(r.err, m, std::regex(R"((\d+) of 12 frames (is|are) in )"))) << r.err;
    int written = std::stoi(m[1].str());
    ASSERT_GE(written, 1) << "the loss came before the first frame: raise WISP_INJECT_DEVICE_LOST\n" << r.err;
    ASSERT_LT(written, 12) << r.err;
    EXPECT_NE(r.err.find((dir / "frames").string()), std::string::npos) << r.err;
    for (int f = 0; f < written; ++f) {
        char name[32];
        std::snprintf(name, sizeof(name), "frame_%05d.png", f);
        std::string png = readFile(dir / "frames" / name);
        ASSERT_GT(png.size(), 12u) << name;
        EXPECT_EQ(png.substr(png.size() - 8, 4), "IEND") << name << " ends with its last chunk";
        int w = 0, h = 0, channels = 0;
        unsigned char* pixels = stbi_load_from_memory(reinterpret_cast<const unsigned char*>(png.data()),
                                                      int(png.size()), &w, &h, &channels, 4);
        EXPECT_NE(pixels, nullptr) << name << ": " << stbi_failure_reason();
        stbi_image_free(pixels);
        EXPECT_EQ(w, 96) << name;
        EXPECT_EQ(h, 64) << name;
    }
    char next[32];
    std::snprintf(next, sizeof(next), "frame_%05d.png", written);
    EXPECT_FALSE(std::filesystem::exists(dir / "frames" / next));
    EXPECT_FALSE(std::filesystem::exists(dir / "frames" / "contact_sheet.png"));
    EXPECT_NE(r.err.find("no contact sheet"), std::string::npos) << r.err;
    EXPECT_TRUE(partialFiles(dir.path()).empty()) << partialFiles(dir.path()).front();
    if (!ffmpeg)
        GTEST_SKIP() << "ffmpeg is not installed (Debian package ffmpeg): the video was not tested";
    EXPECT_FALSE(std::filesystem::exists(dir / "run.mp4"));
    EXPECT_NE(r.err.find("no video (" + (dir / "run.mp4").string()), std::string::npos) << r.err;
}

namespace {

struct Rgba {
    int width = 0, height = 0;
    std::vector<unsigned char> pixels;
    const unsigned char* at(int x, int y) const { return &pixels[(size_t(y) * size_t(width) + size_t(x)) * 4]; }
};

Rgba loadPng(const std::filesystem::path& path)
{
    Rgba image;
    int channels = 0;
    unsigned char* p = stbi_load(path.c_str(), &image.width, &image.height, &channels, 4);
    if (p) {
        image.pixels.assign(p, p + size_t(image.width) * size_t(image.height) * 4);
        stbi_image_free(p);
    }
    return image;
}

std::string frameName(int f)
{
    char name[32];
    std::snprintf(name, sizeof(name), "frame_%05d.png", f);
    return name;
}

// The number of video frames ffprobe counts in `video` (-1 when it cannot).
int videoFrames(const std::filesystem::path& video)
{
    std::string command = "ffprobe -v error -count_frames -select_streams v:0 -show_entries stream=nb_read_frames "
                          "-of csv=p=0 '" +
                          video.string() + "'";
    FILE* pipe = popen(command.c_str(), "r");
    if (!pipe)
        return -1;
    char line[64] = {};
    bool read = std::fgets(line, sizeof(line), pipe) != nullptr;
    int status = pclose(pipe);
    return read && status == 0 ? std::atoi(line) : -1;
}

} // namespace

TEST(BadInput, RecordRefusesAFolderHoldingAnEarlierRunUnlessToldToOverwrite)
{
    TempDir dir;
    bool ffmpeg = std::system("command -v ffmpeg >/dev/null 2>&1 && command -v ffprobe >/dev/null 2>&1") == 0;
    std::string common =
        "record --height 32 --guides 30 --set strands_per_guide=2 --out '" + (dir / "run").string() + "'";
    std::string video = ffmpeg ? " --video '" + (dir / "run.mp4").string() + "'" : "";
    auto first = runWisp(common + " --frames 3 --width 48" + video);
    ASSERT_EQ(first.status, 0) << first.err;
    writeFile(dir / "run" / "notes.txt", "mine");
    std::string frame0 = readFile(dir / "run" / "frame_00000.png");

    auto refused = runWisp(common + " --frames 1 --width 48" + video);
    expectUserError(refused, "--out " + (dir / "run").string() +
                                 ": holds 3 frames (frame_00000.png .. frame_00002.png) and a contact sheet of an "
                                 "earlier run; record into an empty folder, or add --overwrite");
    EXPECT_EQ(readFile(dir / "run" / "frame_00000.png"), frame0); // nothing touched
    EXPECT_TRUE(std::filesystem::exists(dir / "run" / "frame_00002.png"));

    auto again = runWisp(common + " --frames 1 --overwrite --width 64" + video);
    ASSERT_EQ(again.status, 0) << again.err;
    EXPECT_TRUE(std::filesystem::exists(dir / "run" / "frame_00000.png"));
    EXPECT_NE(readFile(dir / "run" / "frame_00000.png"), frame0); // the new run's (wider) frame
    EXPECT_FALSE(std::filesystem::exists(dir / "run" / "frame_00001.png"));
    EXPECT_FALSE(std::filesystem::exists(dir / "run" / "frame_00002.png"));
    EXPECT_EQ(loadPng(dir / "run" / "contact_sheet.png").width, 64); // one frame of the new run
    EXPECT_EQ(readFile(dir / "run" / "notes.txt"), "mine");          // only the run's files go
    if (!ffmpeg)
        GTEST_SKIP() << "ffmpeg/ffprobe are not installed (Debian package ffmpeg): the video was not tested";
    EXPECT_EQ(videoFrames(dir / "run.mp4"), 1); // the new run alone
}

TEST(Record, ContactSheetLayoutShowsEveryFrameUpToItsCountThenEvenlyChosen)
{
    wisp::ContactSheetLayout forty = wisp::contactSheetLayout(40, 1280, 720);
    ASSERT_EQ(forty.frames.size(), 40u);
    for (uint32_t f = 0; f < 40; ++f)
        EXPECT_EQ(forty.frames[f], f);
    EXPECT_GE(forty.thumbWidth, wisp::kSheetThumbnailWidth);
    EXPECT_EQ(forty.thumbWidth * forty.shrink, 1280u);
    EXPECT_EQ(forty.columns * forty.rows >= 40 && (forty.columns * (forty.rows - 1)) < 40, true);

    wisp::ContactSheetLayout many = wisp::contactSheetLayout(1000, 1920, 1080);
    ASSERT_EQ(many.frames.size(), size_t(wisp::kSheetMostFrames));
    EXPECT_EQ(many.frames.front(), 0u);
    EXPECT_EQ(many.frames.back(), 999u);
    for (size_t i = 1; i < many.frames.size(); ++i) {
        EXPECT_GT(many.frames[i], many.frames[i - 1]);
        EXPECT_NEAR(double(many.frames[i] - many.frames[i - 1]), 999.0 / (wisp::kSheetMostFrames - 1), 1.0);
    }
    EXPECT_GE(many.thumbWidth, wisp::kSheetThumbnailWidth);

    wisp::ContactSheetLayout small = wisp::contactSheetLayout(3, 100, 60); // narrower than a thumbnail: whole
    EXPECT_EQ(small.shrink, 1u);
    EXPECT_EQ(small.width, 3 * 100 + 2 * wisp::kSheetGutter);
    EXPECT_EQ(small.height, 60u);
}

TEST(Record, TheContactSheetShowsEveryFrameWithItsNumber)
{
    TempDir dir;
    constexpr int kFrames = 14, kWidth = 96, kHeight = 64;
    auto r = runWisp("record --frames " + std::to_string(kFrames) + " --width " + std::to_string(kWidth) +
                     " --height " + std::to_string(kHeight) +
                     " --guides 30 --set strands_per_guide=2 --wind 6,0,0 --out '" + dir.path().string() + "'");
    ASSERT_EQ(r.status, 0) << r.err;
    wisp::ContactSheetLayout layout = wisp::contactSheetLayout(kFrames, kWidth, kHeight);
    ASSERT_EQ(layout.frames.size(), size_t(kFrames));
    Rgba sheet = loadPng(dir / "contact_sheet.png");
    ASSERT_EQ(sheet.width, int(layout.width));
    ASSERT_EQ(sheet.height, int(layout.height));
    std::vector<std::string> labels;
    for (int f = 0; f < kFrames; ++f) {
        Rgba frame = loadPng(dir / frameName(f));
        ASSERT_EQ(frame.width, kWidth);
        int ox = int(layout.cellX(size_t(f))), oy = int(layout.cellY(size_t(f)));
        int lw = int(layout.labelWidth(uint32_t(f))), lh = int(layout.labelHeight());
        size_t same = 0, outside = 0, white = 0;
        std::string label;
        for (int y = 0; y < kHeight; ++y)
            for (int x = 0; x < kWidth; ++x) {
                const unsigned char* s = sheet.at(ox + x, oy + y);
                if (x < lw && y < lh) { // the number: white dots on black
                    bool dot = s[0] == 255 && s[1] == 255 && s[2] == 255;
                    EXPECT_TRUE(dot || (s[0] == 0 && s[1] == 0 && s[2] == 0)) << "frame " << f;
                    white += dot ? 1 : 0;
                    label += dot ? '#' : '.';
                    continue;
                }
                ++outside;
                same += std::equal(s, s + 3, frame.at(x, y)) ? 1 : 0;
            }
        EXPECT_EQ(same, outside) << "frame " << f << " is not whole in its cell";
        EXPECT_GT(white, 0u) << "frame " << f << " has no number";
        labels.push_back(label);
    }
    for (int a = 0; a < 10; ++a) // one glyph per digit
        for (int b = a + 1; b < 10; ++b)
            EXPECT_NE(labels[size_t(a)], labels[size_t(b)]) << a << " and " << b << " are drawn alike";
    EXPECT_NE(loadPng(dir / frameName(0)).pixels, loadPng(dir / frameName(kFrames - 1)).pixels); // the hair moved
}
