// tests/test_render_cli.cpp: `wisp render` through the real binary: a PNG with validation clean
// (and synchronization validation), any mesh as a head, its own options' bad input, what --set
// changes in the draw, samples a device lacks said and recorded as drawn, and a lost device that
// leaves no picture.
#include "cli_support.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

using namespace wisp::test;

TEST(Cli, RenderWritesAPngWithValidationClean)
{
    TempDir dir;
    auto r = runWisp("--validation render --width 200 --height 150 --out '" + (dir / "head.png").string() + "'");
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_TRUE(r.err.empty()) << r.err;
    ASSERT_TRUE(std::filesystem::exists(dir / "head.png"));
    // PNG signature and the IHDR's width and height.
    std::ifstream in(dir / "head.png", std::ios::binary);
    unsigned char header[24];
    in.read(reinterpret_cast<char*>(header), 24);
    EXPECT_EQ(header[1], 'P');
    EXPECT_EQ(header[2], 'N');
    EXPECT_EQ((header[18] << 8) | header[19], 200);
    EXPECT_EQ((header[22] << 8) | header[23], 150);
}

TEST(Cli, EveryPassIsCleanUnderSynchronizationValidation)
{
    // Shadows, deep opacity, both ways of drawing the strands (the compute path's meshes in compute,
    // and by graphics under the guides), both transparency modes and every shading model, one
    // sample and four, the head alone: the barriers the frame derives from the passes'
    // declarations satisfy the synchronization checks.
    TempDir dir;
    for (const char* sets : {"--set hair_raster=graphics --set transparency=oit --set shading=karis",
                             "--set hair_raster=graphics --set transparency=msaa --set shading=lut",
                             "--set hair_raster=graphics --set dom_layers=0 --set shading=kajiya",
                             "--set hair_raster=compute --set shading=lut", "--set hair_raster=compute --set samples=1",
                             "--set hair_raster=compute --set dom_layers=0 --set shading=kajiya --set shadows=off",
                             "--set hair_raster=compute --set dom_layers=0",
                             "--set hair_raster=compute --set show_guides=on", "--no-hair --set hair_raster=compute"}) {
        auto r = runWisp("--sync-validation render --width 96 --height 72 --guides 60 --set strands_per_guide=4 " +
                         std::string(sets) + " --set shadow_size=256 --out '" + (dir / "s.png").string() + "'");
        EXPECT_EQ(r.status, 0) << sets << "\n" << r.err;
        EXPECT_TRUE(r.err.empty()) << sets << "\n" << r.err;
    }
}

TEST(Cli, RenderAnyMeshGivenAsHead)
{
    WISP_REQUIRE_DATA(mesh, "sintel/sintel.obj");
    TempDir dir;
    auto r = runWisp("--validation render --width 96 --height 96 --head '" + mesh.string() + "' --out '" +
                     (dir / "s.png").string() + "'");
    EXPECT_EQ(r.status, 0) << r.err;
    EXPECT_TRUE(std::filesystem::exists(dir / "s.png"));
}

TEST(BadInput, OutOfRangeSizeNamesTheRange)
{
    TempDir dir;
    auto r = runWisp("render --width 5 --out '" + (dir / "a.png").string() + "'");
    expectUserError(r, "--width");
    EXPECT_NE(r.err.find("16"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("8192"), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(dir / "a.png"));
}

TEST(BadInput, NonNumericValue)
{
    expectUserError(runWisp("render --out a.png --height tall"), "--height");
}

TEST(BadInput, OutputFolderMissing)
{
    auto r = runWisp("render --out /nonexistent/dir/a.png");
    expectUserError(r, "/nonexistent/dir");
}

TEST(BadInput, OutputUnderAFileSaysTheFileIsNoFolder)
{
    TempDir dir;
    writeFile(dir / "notes", "a file");
    expectUserError(runWisp("render --out '" + (dir / "notes" / "a.png").string() + "'"),
                    "'" + (dir / "notes").string() + "' is a file, not a folder");
    expectUserError(runWisp("render --out '" + (dir / "notes" / "deeper" / "a.png").string() + "'"),
                    "'" + (dir / "notes").string() + "' is a file, not a folder");
    expectUserError(runWisp("record --frames 1 --out '" + (dir / "notes" / "frames").string() + "'"),
                    "'" + (dir / "notes").string() + "' is a file, not a folder");
}

TEST(BadInput, OutputNotPng)
{
    TempDir dir;
    expectUserError(runWisp("render --out '" + (dir / "a.jpg").string() + "'"), ".png");
}

TEST(BadInput, StillWithoutProfileIsRefused)
{
    TempDir dir;
    expectUserError(runWisp("render --still --out '" + (dir / "a.png").string() + "'"),
                    "--still is an option of --profile");
    EXPECT_FALSE(std::filesystem::exists(dir / "a.png"));
}

// --still: the timed frames take no steps, said in the profile's JSON (what the physics costs a
// frame is the difference from a profile without it; HairSession.AStillProfileStepsOnlyInItsWarmUp
// counts the steps).
TEST(Cli, AStillProfileSaysItsTimedFramesTookNoSteps)
{
    for (bool still : {false, true}) {
        auto r = runWisp(std::string("render --profile 2 --warmup 1 --width 64 --height 48 --guides 20 "
                                     "--set strands_per_guide=2") +
                         (still ? " --still" : ""));
        ASSERT_EQ(r.status, 0) << r.err;
        nlohmann::json j = nlohmann::json::parse(r.out);
        EXPECT_EQ(j["timed_steps"].get<bool>(), !still);
        EXPECT_TRUE(j["ms"].contains("frame"));
    }
}

namespace {

// The MSAA sample counts of the device wisp picks (`info --json`; empty when several are usable,
// since then which one is picked is not this test's business).
std::vector<uint32_t> pickedDeviceSamples()
{
    auto info = runWisp("info --json");
    std::vector<uint32_t> counts;
    if (info.status != 0)
        return counts;
    size_t usable = 0;
    for (const auto& d : nlohmann::json::parse(info.out))
        if (d["usable"].get<bool>()) {
            ++usable;
            counts = d["msaa_samples"].get<std::vector<uint32_t>>();
        }
    return usable == 1 ? counts : std::vector<uint32_t>{};
}

} // namespace

TEST(Cli, SamplesTheDeviceLacksAreSaidAndWhatWasDrawnRecorded)
{
    std::vector<uint32_t> has = pickedDeviceSamples();
    if (has.empty())
        GTEST_SKIP() << "not one usable device: cannot tell which device's samples apply";
    auto drawn = [&](uint32_t asked) { // the most of asked, asked / 2, ... the device has
        for (uint32_t s = asked; s > 1; s >>= 1)
            if (std::find(has.begin(), has.end(), s) != has.end())
                return s;
        return 1u;
    };
    TempDir dir;
    std::string small = " --width 32 --height 32 --guides 10 --set strands_per_guide=1";
    for (uint32_t asked : {2u, 8u}) {
        auto r = runWisp("render --profile 1 --warmup 0 --samples " + std::to_string(asked) + small);
        ASSERT_EQ(r.status, 0) << r.err;
        nlohmann::json j = nlohmann::json::parse(r.out);
        EXPECT_EQ(j["samples"], drawn(asked)) << "the JSON records what was drawn";
        EXPECT_EQ(j["settings"]["samples"], drawn(asked));
        // the compute raster's counts, the one walk's included (a first frame has no room: it spills)
        ASSERT_TRUE(j["raster"]["one_walk"].is_boolean()) << r.out;
        EXPECT_LE(j["raster"]["spilled"].get<uint64_t>(), j["raster"]["fragments"].get<uint64_t>()) << r.out;
        std::string line = "wisp: samples " + std::to_string(asked) + ": '";
        if (drawn(asked) < asked) {
            EXPECT_NE(r.err.find(line), std::string::npos) << r.err;
            EXPECT_NE(r.err.find("; drawing with " + std::to_string(drawn(asked)) + "\n"), std::string::npos) << r.err;
            EXPECT_EQ(lineCount(r.err), 1u) << r.err;
        } else {
            EXPECT_EQ(r.err.find(line), std::string::npos) << r.err;
        }
    }
    auto sweep =
        runWisp("sweep --out '" + (dir / "s").string() + "' --vary samples=1,2,4,8 --warmup 0 --frames 1" + small);
    ASSERT_EQ(sweep.status, 0) << sweep.err;
    std::ifstream in(dir / "s" / "results.csv");
    std::string header;
    std::getline(in, header);
    std::vector<std::string> names;
    std::stringstream hs(header);
    for (std::string n; std::getline(hs, n, ',');)
        names.push_back(n);
    auto column = std::find(names.begin(), names.end(), "samples_drawn");
    ASSERT_NE(column, names.end()) << header;
    for (uint32_t asked : {1u, 2u, 4u, 8u}) {
        std::string row;
        ASSERT_TRUE(std::getline(in, row));
        std::vector<std::string> fields;
        std::stringstream rs(row);
        for (std::string f; std::getline(rs, f, ',');)
            fields.push_back(f);
        ASSERT_GT(fields.size(), size_t(column - names.begin())) << row;
        EXPECT_EQ(fields[0], std::to_string(asked)) << row;
        EXPECT_EQ(fields[size_t(column - names.begin())], std::to_string(drawn(asked))) << row;
    }
}

TEST(Cli, SetChangesWhatIsDrawn)
{
    TempDir dir;
    auto r = runWisp("render --width 64 --height 64 --guides 10 --set strands_per_guide=100 --set divisions=100 "
                     "--set hair_raster=graphics --out '" +
                     (dir / "a.png").string() + "'");
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_NE(r.out.find("10 guides x 100 strands x 100 divisions = 100000 segments"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("50 instances"), std::string::npos) << r.out; // past the tessellation limits, not capped
    // In compute: every segment on screen is drawn, each fragment counted.
    r = runWisp("render --width 64 --height 64 --guides 10 --set strands_per_guide=100 --set divisions=100 "
                "--set hair_raster=compute --out '" +
                (dir / "b.png").string() + "'");
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_NE(r.out.find("drawn in compute"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("compute raster: 100000 segments on screen"), std::string::npos) << r.out;
}

TEST(Cli, DeviceLostDuringRenderWritesNoPicture)
{
    TempDir dir;
    // The first submission uploads the head; a later one simulates or draws a frame.
    for (int submission : {1, 16}) {
        auto r = runWisp("--validation render --frames 3 --width 96 --height 64 --guides 60 --set strands_per_guide=4 "
                         "--out '" +
                             (dir / "a.png").string() + "'",
                         lostAt(submission));
        expectDeviceLost(r, "render");
        EXPECT_NE(r.err.find((dir / "a.png").string() + " was not written"), std::string::npos) << r.err;
        EXPECT_TRUE(r.out.empty()) << r.out;
        EXPECT_FALSE(std::filesystem::exists(dir / "a.png"));
        EXPECT_TRUE(partialFiles(dir.path()).empty()) << partialFiles(dir.path()).front();
    }
}
