// tests/test_record_cli.cpp: `wisp record` through the real binary: the same command gives the
// same frames (and a video), outputs checked before any work, and a lost device that keeps the
// frames written, each complete.
#include "cli_support.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <stb_image.h>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <regex>
#include <string>

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
