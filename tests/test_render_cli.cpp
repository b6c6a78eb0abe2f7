// tests/test_render_cli.cpp: `wisp render` through the real binary: a PNG with validation clean
// (and synchronization validation), any mesh as a head, its own options' bad input, what --set
// changes in the draw, and a lost device that leaves no picture.
#include "cli_support.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <string>

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

TEST(BadInput, OutputNotPng)
{
    TempDir dir;
    expectUserError(runWisp("render --out '" + (dir / "a.jpg").string() + "'"), ".png");
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
