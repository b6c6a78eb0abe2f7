// tests/test_cli.cpp: the real wisp binary as a user runs it: help, render, info, inspect, and
// every bad-input path: one line on stderr naming what and where, exit status 2, nothing written.
#include "test_support.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <fstream>

using wisp::test::runWisp;
using wisp::test::TempDir;
using wisp::test::writeFile;

namespace {

size_t lineCount(const std::string& s)
{
    return size_t(std::count(s.begin(), s.end(), '\n'));
}

void expectUserError(const wisp::test::RunResult& r, const std::string& mention)
{
    EXPECT_EQ(r.status, 2) << r.err;
    EXPECT_EQ(lineCount(r.err), 1u) << r.err;
    EXPECT_NE(r.err.find(mention), std::string::npos) << r.err;
    EXPECT_EQ(r.err.find("internal"), std::string::npos) << r.err;
}

}  // namespace

TEST(Cli, HelpDocumentsEveryCommand)
{
    auto r = runWisp("--help");
    EXPECT_EQ(r.status, 0);
    for (const char* cmd : {"render", "view", "info", "inspect", "--validation", "--gpu"})
        EXPECT_NE(r.out.find(cmd), std::string::npos) << cmd;
    auto sub = runWisp("render --help");
    EXPECT_EQ(sub.status, 0);
    for (const char* opt : {"--out", "--width", "--height", "--head", "--samples", "--light-azimuth"})
        EXPECT_NE(sub.out.find(opt), std::string::npos) << opt;
}

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

TEST(Cli, RenderAnyMeshGivenAsHead)
{
    WISP_REQUIRE_DATA(mesh, "sintel/sintel.obj");
    TempDir dir;
    auto r = runWisp("--validation render --width 96 --height 96 --head '" + mesh.string() + "' --out '" +
                     (dir / "s.png").string() + "'");
    EXPECT_EQ(r.status, 0) << r.err;
    EXPECT_TRUE(std::filesystem::exists(dir / "s.png"));
}

TEST(Cli, InfoListsTheDeviceAndFeatures)
{
    auto r = runWisp("info --json");
    ASSERT_EQ(r.status, 0) << r.err;
    nlohmann::json j = nlohmann::json::parse(r.out);
    ASSERT_TRUE(j.is_array());
    ASSERT_GE(j.size(), 1u);
    EXPECT_TRUE(j[0]["usable"].get<bool>());
    EXPECT_TRUE(j[0]["tessellation_shader"].get<bool>());
    EXPECT_TRUE(j[0]["geometry_shader"].get<bool>());
    EXPECT_TRUE(j[0].contains("float_atomic_add"));
    auto text = runWisp("info");
    EXPECT_NE(text.out.find("timestamps"), std::string::npos);
}

TEST(Cli, InspectMeshPrintsOneJsonObject)
{
    WISP_REQUIRE_DATA(mesh, "sintel/sintel.obj");
    auto r = runWisp("inspect '" + mesh.string() + "'");
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(lineCount(r.out), 1u);
    nlohmann::json j = nlohmann::json::parse(r.out);
    EXPECT_EQ(j["kind"], "mesh");
    EXPECT_EQ(j["vertices"], 3046);
    EXPECT_EQ(j["triangles"], 5952);
    ASSERT_EQ(j["bbox"].size(), 2u);
    EXPECT_LT(j["bbox"][0][1].get<double>(), j["bbox"][1][1].get<double>());
}

TEST(BadInput, UnknownOption)
{
    expectUserError(runWisp("render --out x.png --sparkles"), "--sparkles");
}

TEST(BadInput, UnknownCommand)
{
    expectUserError(runWisp("paint"), "paint");
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

TEST(BadInput, MissingMeshNamesThePath)
{
    TempDir dir;
    auto r = runWisp("render --head /nonexistent/bust.obj --out '" + (dir / "a.png").string() + "'");
    expectUserError(r, "/nonexistent/bust.obj");
    EXPECT_TRUE(std::filesystem::is_empty(dir.path()));
}

TEST(BadInput, MalformedMeshNamesFileAndLine)
{
    TempDir dir;
    writeFile(dir / "bad.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n");
    auto r = runWisp("render --head '" + (dir / "bad.obj").string() + "' --out '" + (dir / "a.png").string() + "'");
    expectUserError(r, "bad.obj:4:");
    EXPECT_FALSE(std::filesystem::exists(dir / "a.png"));
    expectUserError(runWisp("inspect '" + (dir / "bad.obj").string() + "'"), "bad.obj:4:");
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

TEST(BadInput, NoVulkanDevice)
{
    TempDir dir;
    auto r = runWisp("render --out '" + (dir / "a.png").string() + "'",
                     "VK_ICD_FILENAMES=/nonexistent/icd.json VK_DRIVER_FILES=/nonexistent/icd.json");
    expectUserError(r, "Vulkan");
    EXPECT_FALSE(std::filesystem::exists(dir / "a.png"));
    expectUserError(runWisp("info", "VK_ICD_FILENAMES=/nonexistent/icd.json VK_DRIVER_FILES=/nonexistent/icd.json"),
                    "no Vulkan device");
}

TEST(BadInput, UnknownGpu)
{
    TempDir dir;
    expectUserError(runWisp("--gpu 42 render --out '" + (dir / "a.png").string() + "'"), "--gpu 42");
    expectUserError(runWisp("render --gpu quantum --out '" + (dir / "a.png").string() + "'"), "quantum");
}

TEST(BadInput, ViewWithoutDisplayPointsToRender)
{
    auto r = runWisp("view", "env -u DISPLAY -u WAYLAND_DISPLAY");
    expectUserError(r, "wisp render");
}

TEST(BadInput, InspectMissingFile)
{
    expectUserError(runWisp("inspect /nonexistent/x.obj"), "/nonexistent/x.obj");
}

TEST(Window, OpensUnderXvfbDrawsAndClosesCleanly)
{
    if (std::system("command -v xvfb-run >/dev/null 2>&1") != 0)
        GTEST_SKIP() << "xvfb-run is not installed (Debian package xvfb): cannot test the window here";
    TempDir dir;
    auto r = runWisp("--validation view --width 320 --height 240 --frames 4 --screenshot '" + (dir / "shot.png").string() + "'",
                     "xvfb-run -a -s '-screen 0 640x480x24'");
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_NE(r.out.find("closed after 4 frames"), std::string::npos) << r.out;
    EXPECT_TRUE(std::filesystem::exists(dir / "shot.png"));
    EXPECT_EQ(r.err.find("validation"), std::string::npos) << r.err;
}
