// tests/test_cli.cpp: the real wisp binary as a user runs it: help, info, inspect, settings, the
// global options, unknown commands and options, no or a wrong device, and the fault injections'
// own checks. Each command's suite is its own file (test_*_cli.cpp); the options every command
// shares are test_shared_options_cli.cpp.
#include "cli_support.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <string>

using namespace wisp::test;

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

TEST(Cli, InspectHairPrintsOneJsonObject)
{
    WISP_REQUIRE_DATA(hair, "sintel/sintel_hair_11400x16.tfx");
    auto r = runWisp("inspect '" + hair.string() + "'");
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(lineCount(r.out), 1u);
    nlohmann::json j = nlohmann::json::parse(r.out);
    EXPECT_EQ(j["kind"], "hair");
    EXPECT_EQ(j["format"], "tfx4");
    EXPECT_EQ(j["strands"], 11400);
    EXPECT_EQ(j["vertices"], 11400 * 16);
    EXPECT_EQ(j["vertices_per_strand"][0], 16);
    EXPECT_EQ(j["vertices_per_strand"][1], 16);
}

TEST(BadInput, UnknownOption)
{
    expectUserError(runWisp("render --out x.png --sparkles"), "--sparkles");
}

TEST(BadInput, UnknownCommand)
{
    expectUserError(runWisp("paint"), "paint");
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

TEST(BadInput, InspectMissingFile)
{
    expectUserError(runWisp("inspect /nonexistent/x.obj"), "/nonexistent/x.obj");
}

TEST(BadInput, CoordinatesPastTheFloatMathsRangeNameTheFileNotTheHair)
{
    // The default head scaled by 1e30 was "hair strand 0 has a zero-length segment" (no file named,
    // the hair blamed); a TressFX vertex at 1e30 was "is 3.46e30 long, too short to split into 15
    // segments". Each names its file and line now, exits 2 and writes nothing.
    TempDir dir;
    std::ifstream in(std::string(WISP_SOURCE_DIR) + "/models/head.obj");
    std::string line, scaled;
    size_t lineNumber = 0, firstVertex = 0;
    while (std::getline(in, line)) {
        ++lineNumber;
        float x = 0, y = 0, z = 0;
        if (std::sscanf(line.c_str(), "v %f %f %f", &x, &y, &z) == 3) {
            char text[128];
            std::snprintf(text, sizeof(text), "v %g %g %g", double(x) * 1e30, double(y) * 1e30, double(z) * 1e30);
            line = text;
            firstVertex = firstVertex == 0 && (x != 0 || y != 0 || z != 0) ? lineNumber : firstVertex;
        }
        scaled += line + "\n";
    }
    ASSERT_GT(firstVertex, 0u);
    std::ofstream(dir / "big.obj") << scaled;
    std::string png = (dir / "a.png").string();
    RunResult r =
        runWisp("render --width 64 --height 64 --head '" + (dir / "big.obj").string() + "' --out '" + png + "'");
    expectUserError(r, (dir / "big.obj").string() + ":" + std::to_string(firstVertex) + ": vertex ");
    EXPECT_NE(r.err.find("is out of the range Wisp's float math handles"), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(png));

    std::ofstream(dir / "far.tfx") << "numStrands 1\nstrand 0 numVerts 3\n0 0 0\n1e30 1e30 1e30\n0 1 0\n";
    r = runWisp("render --width 64 --height 64 --hair '" + (dir / "far.tfx").string() + "' --out '" + png + "'");
    expectUserError(r, (dir / "far.tfx").string() + ":4: coordinate 1e+30 is out of the range");
    EXPECT_FALSE(std::filesystem::exists(png));
}

TEST(Cli, SettingsListsEveryNameWithRangeAndDefault)
{
    auto r = runWisp("settings");
    ASSERT_EQ(r.status, 0) << r.err;
    for (const char* name : {"guides", "vertices_per_strand", "strands_per_guide", "divisions", "interpolation",
                             "deviation", "lod", "width"})
        EXPECT_NE(r.out.find(std::string("\n") + name + " "), std::string::npos) << name;
    EXPECT_NE(r.out.find("single | multi | mixed"), std::string::npos);
}

TEST(BadInput, DeviceLossInjectionTakesASubmissionNumber)
{
    TempDir dir;
    expectUserError(runWisp("render --out '" + (dir / "a.png").string() + "'", "WISP_INJECT_DEVICE_LOST=0"),
                    "WISP_INJECT_DEVICE_LOST=0: must be a queue submission number");
    EXPECT_FALSE(std::filesystem::exists(dir / "a.png"));
}

// A device lacking a feature Wisp needs, through the test-only WISP_HIDE_FEATURE=NAME (renderer/
// vk/context.h: every device reports NAME absent): one line naming the device and the feature.
TEST(BadInput, DeviceLackingAFeatureIsNamedWithTheFeature)
{
    TempDir dir;
    auto info = runWisp("info --json");
    ASSERT_EQ(info.status, 0) << info.err;
    std::string device0 = nlohmann::json::parse(info.out)[0]["name"].get<std::string>();
    const std::string hide = "WISP_HIDE_FEATURE=geometryShader";
    auto r = runWisp("render --out '" + (dir / "a.png").string() + "'", hide);
    expectUserError(r, "lacks what Wisp needs: geometryShader");
    EXPECT_NE(r.err.find("Vulkan device "), std::string::npos) << r.err;
    auto chosen = runWisp("--gpu 0 record --frames 1 --out '" + (dir / "f").string() + "'", hide);
    expectUserError(chosen, "Vulkan device 0 '" + device0 + "' lacks what Wisp needs: geometryShader");
    auto two = runWisp("simulate --steps 1", "WISP_HIDE_FEATURE=tessellationShader,VK_KHR_push_descriptor");
    expectUserError(two, "lacks what Wisp needs: tessellationShader, VK_KHR_push_descriptor");
    EXPECT_FALSE(std::filesystem::exists(dir / "a.png"));
    EXPECT_FALSE(std::filesystem::exists(dir / "f")); // refused before the folder is made
    auto listed = runWisp("info --json", hide);
    ASSERT_EQ(listed.status, 0) << listed.err;
    nlohmann::json d = nlohmann::json::parse(listed.out)[0];
    EXPECT_FALSE(d["usable"].get<bool>());
    EXPECT_EQ(d["missing"], nlohmann::json::array({"geometryShader"}));
    expectUserError(runWisp("info", "WISP_HIDE_FEATURE=warpDrive"),
                    "WISP_HIDE_FEATURE: 'warpDrive' is not a feature it can hide (known: dynamicRendering");
}
