// tests/test_shared_options_cli.cpp: the head, hair, physics and settings options render,
// record, view, simulate and sweep share (app/scene/session_options.h), through the real binary: values
// out of range or not finite, --set, broken and missing files, per-part parameters, and workloads
// refused before anything is built.
#include "cli_support.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <string>

using namespace wisp::test;

TEST(BadInput, NonFiniteAndAbsurdNumbersAreRangeErrors)
{
    // CLI11's own ranges let "nan" through (comparisons with NaN are false): every floating-point
    // option refuses it, and the infinities, naming itself.
    for (const char* option : {"--friction nan", "--repulsion nan", "--hair-length inf", "--length-variation -inf",
                               "--curl nan", "--step-hz -1", "--global-stiffness nan", "--local-stiffness inf",
                               "--damping nan", "--drag nan", "--hair-scale nan"}) {
        std::string name = std::string(option).substr(0, std::string(option).find(' '));
        expectUserError(runWisp(std::string("simulate --steps 1 ") + option), name);
    }
    TempDir dir;
    std::string out = " --out '" + (dir / "a.png").string() + "'";
    for (const char* option : {"--fps nan", "--light-azimuth nan", "--light-elevation inf", "--light-intensity nan",
                               "--width 0", "--height 100000", "--frames -1"}) {
        std::string name = std::string(option).substr(0, std::string(option).find(' '));
        expectUserError(runWisp(std::string("render ") + option + out), name);
    }
    expectUserError(runWisp("simulate --guides 10000000"), "--guides");
    expectUserError(runWisp("simulate --guides -1"), "--guides");
    expectUserError(runWisp("simulate --vertices 0"), "--vertices");
    expectUserError(runWisp("simulate --seed -1"), "--seed");
    // A device index past what std::stoul reads was an internal error (exit 1).
    expectUserError(runWisp("--gpu 99999999999999999999 simulate --steps 1"), "--gpu");
    expectUserError(runWisp("simulate --steps 1 --set friction=nan"), "friction");
    expectUserError(runWisp("render --set width=inf" + out), "width");
    EXPECT_FALSE(std::filesystem::exists(dir / "a.png"));
}

TEST(BadInput, SetNamesTheSettingAndItsRange)
{
    TempDir dir;
    std::string out = " --out '" + (dir / "a.png").string() + "'";
    expectUserError(runWisp("render --set sparkle=3" + out), "unknown setting 'sparkle'");
    auto r = runWisp("render --set strands_per_guide=0" + out);
    expectUserError(r, "strands_per_guide");
    EXPECT_NE(r.err.find("1 .. 4096"), std::string::npos) << r.err;
    expectUserError(runWisp("render --set interpolation=bilinear" + out), "single | multi | mixed");
    expectUserError(runWisp("render --set width=wide" + out), "not a number");
    expectUserError(runWisp("render --set lod" + out), "NAME=VALUE");
    expectUserError(runWisp("simulate --set width=0.001 --steps 1"), "does not use it");
    EXPECT_FALSE(std::filesystem::exists(dir / "a.png"));
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

TEST(BadInput, BrokenHairFileNamesFileAndOffset)
{
    TempDir dir;
    writeFile(dir / "broken.tfx", std::string("\x00\x00\x80\x40", 4) + std::string(40, '\x01')); // 4.0, then garbage
    auto r = runWisp("simulate --hair '" + (dir / "broken.tfx").string() + "' --steps 1");
    expectUserError(r, "broken.tfx");
    EXPECT_NE(r.err.find("byte"), std::string::npos) << r.err;
    expectUserError(runWisp("inspect '" + (dir / "broken.tfx").string() + "'"), "broken.tfx");
}

TEST(BadInput, MissingHairFile)
{
    expectUserError(runWisp("simulate --hair /nonexistent/groom.tfx"), "/nonexistent/groom.tfx");
}

TEST(BadInput, SphereNeedsAPositiveRadius)
{
    expectUserError(runWisp("simulate --sphere 0,0,0,-1 --steps 1"), "--sphere");
    expectUserError(runWisp("simulate --sphere 0,0,0 --steps 1"), "--sphere");
}

TEST(BadInput, OutOfRangePhysicsValues)
{
    auto r = runWisp("simulate --vertices 3");
    expectUserError(r, "--vertices");
    EXPECT_NE(r.err.find("64"), std::string::npos) << r.err;
    expectUserError(runWisp("simulate --friction 1.5"), "--friction");
    expectUserError(runWisp("simulate --guides 0"), "--guides");
}

TEST(BadInput, SphereWindAndOffsetMustBeFinite)
{
    expectUserError(runWisp("simulate --steps 1 --sphere nan,0,0,1"),
                    "--sphere: the first value (nan) is not a finite number");
    expectUserError(runWisp("simulate --steps 1 --sphere 0,0,0,inf"),
                    "--sphere: the fourth value (inf) is not a finite number");
    expectUserError(runWisp("simulate --steps 1 --wind nan,0,0"),
                    "--wind: the first value (nan) is not a finite number");
    expectUserError(runWisp("simulate --steps 1 --wind 1e9,0,0"), "--wind");
    expectUserError(runWisp("simulate --steps 1 --hair-offset 0,nan,0"),
                    "--hair-offset: the second value (nan) is not a finite number");
}

TEST(BadInput, DrawnStrandsPast32BitsAreRefusedBeforeGrowing)
{
    // 2,000,000 guides x 4096 strands: more strands than 32-bit numbers, refused before any guide
    // is grown (growing them would take minutes) and before the device is touched.
    TempDir dir;
    auto r = runWisp("render --guides 2000000 --set strands_per_guide=4096 --out '" + (dir / "a.png").string() + "'");
    expectUserError(r, "8192000000 drawn strands");
    EXPECT_FALSE(std::filesystem::exists(dir / "a.png"));
}

TEST(BadInput, WorkloadLargerThanTheGpuIsRefusedUpFront)
{
    // The device's memory from `wisp info`; a GPU with more than these workloads need is skipped.
    auto info = runWisp("info --json");
    ASSERT_EQ(info.status, 0) << info.err;
    uint64_t most = 0;
    for (const auto& d : nlohmann::json::parse(info.out))
        most = std::max(most, d["device_local_bytes"].get<uint64_t>());
    if (most > (uint64_t(6) << 30))
        GTEST_SKIP() << "the device has " << (most >> 20) << " MiB: these workloads fit";
    // About 8.6 GB of solver state: refused with both sizes before 2,000,000 guides are grown.
    auto r = runWisp("simulate --guides 2000000 --vertices 64 --grid 256 --steps 1");
    expectUserError(r, "MiB of GPU memory");
    EXPECT_NE(r.err.find("needs"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("' has " + std::to_string((most + (1u << 20) - 1) >> 20) + " MiB"), std::string::npos)
        << r.err;
    // A picture of 8192 x 8192 x 4 samples with 8192^2 light maps: about 5 GB of images (the
    // samples estimated are those the device draws: a refusal is still one line).
    TempDir dir;
    r = runWisp("render --width 8192 --height 8192 --samples 4 --set shadow_size=8192 --out '" +
                (dir / "a.png").string() + "'");
    expectUserError(r, "MiB of GPU memory");
    EXPECT_NE(r.err.find("8192 x 8192 x 4 samples"), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(dir / "a.png"));
    r = runWisp("render --no-hair --width 8192 --height 8192 --samples 8 --set shadow_size=8192 --out '" +
                (dir / "a.png").string() + "'");
    expectUserError(r, "MiB of GPU memory");
    EXPECT_FALSE(std::filesystem::exists(dir / "a.png"));
}

TEST(BadInput, ComputeRasterLargerThanTheGpuIsRefusedUpFront)
{
    // 1000 guides x 4096 strands x 1024 divisions drawn in compute: about 105 GB of strand
    // vertices, fragments and light buffers; the simulation and the images are small. Refused,
    // naming the compute raster, before the hair is grown or the device touched.
    auto info = runWisp("info --json");
    ASSERT_EQ(info.status, 0) << info.err;
    uint64_t most = 0;
    for (const auto& d : nlohmann::json::parse(info.out))
        most = std::max(most, d["device_local_bytes"].get<uint64_t>());
    if (most > (uint64_t(96) << 30))
        GTEST_SKIP() << "the device has " << (most >> 20) << " MiB: this workload fits";
    TempDir dir;
    for (const char* path : {"compute", "auto"}) {
        auto r =
            runWisp("render --width 64 --height 64 --guides 1000 --set strands_per_guide=4096 --set divisions=1024 "
                    "--set shadow_size=64 --set hair_raster=" +
                    std::string(path) + " --out '" + (dir / "a.png").string() + "'");
        expectUserError(r, "MiB of GPU memory");
        EXPECT_NE(r.err.find(", compute raster "), std::string::npos) << r.err;
        EXPECT_NE(r.err.find("(4096000 strands x 1024 divisions)"), std::string::npos) << r.err;
        EXPECT_NE(r.err.find("strands_per_guide, divisions"), std::string::npos) << r.err;
        EXPECT_FALSE(std::filesystem::exists(dir / "a.png"));
    }
}

TEST(BadInput, BadPartSettings)
{
    expectUserError(runWisp("simulate --steps 1 --part 3:global=0.1"), "no part '3'");
    expectUserError(runWisp("simulate --steps 1 --part 0:global=2"), "global: 2 is out of range: allowed 0 .. 1");
    expectUserError(runWisp("simulate --steps 1 --part 0:stiff=0.1"), "unknown key 'stiff'");
    expectUserError(runWisp("simulate --steps 1 --part 0:global=abc"), "not a number");
    expectUserError(runWisp("simulate --steps 1 --part global=0.1"), "PART:key=value");
    expectUserError(runWisp("simulate --steps 1 --part 0:"), "--part 0:: no key=value after '0:'");
    expectUserError(runWisp("simulate --steps 1 --part 0:global=0.1,global=0.2"),
                    "--part 0:global=0.1,global=0.2: global is given twice");
    expectUserError(runWisp("simulate --steps 1 --part 0:global=0.1,"), "an empty key=value");
}

TEST(BadInput, APartNameTwoFilesShareIsRefused)
{
    WISP_REQUIRE_DATA(front, "tressfx-text/hair_front_16_guide.tfx");
    WISP_REQUIRE_DATA(head, "tressfx-text/head_max4.obj");
    TempDir dir;
    std::filesystem::create_directories(dir / "a");
    std::filesystem::create_directories(dir / "b");
    std::filesystem::copy_file(front, dir / "a" / "fringe.tfx");
    std::filesystem::copy_file(front, dir / "b" / "fringe.tfx");
    std::string hair =
        " --hair '" + (dir / "a" / "fringe.tfx").string() + "' --hair '" + (dir / "b" / "fringe.tfx").string() + "'";
    expectUserError(
        runWisp("simulate --steps 1 --head '" + head.string() + "'" + hair + " --part fringe.tfx:global=0.5"),
        "--part fringe.tfx:global=0.5: 'fringe.tfx' names parts 0 and 1: give the index");
}

TEST(Cli, EachPartTakesItsOwnParameters)
{
    WISP_REQUIRE_DATA(front, "tressfx-text/hair_front_16_guide.tfx");
    WISP_REQUIRE_DATA(tail, "tressfx-text/hair_tail_16_guide.tfx");
    WISP_REQUIRE_DATA(head, "tressfx-text/head_max4.obj");
    auto r =
        runWisp("simulate --json --steps 2 --head '" + head.string() + "' --hair '" + front.string() + "' --hair '" +
                tail.string() + "' --part 1:global=0.5,drag=3 --part hair_front_16_guide:local=0.05");
    ASSERT_EQ(r.status, 0) << r.err;
    nlohmann::json j = nlohmann::json::parse(r.out);
    EXPECT_FLOAT_EQ(j["parts"][1]["global_stiffness"].get<float>(), 0.5f);
    EXPECT_FLOAT_EQ(j["parts"][1]["drag"].get<float>(), 3.0f);
    EXPECT_FLOAT_EQ(j["parts"][0]["local_stiffness"].get<float>(), 0.05f);
    EXPECT_NE(j["parts"][0]["global_stiffness"], j["parts"][1]["global_stiffness"]);
    // A part by its file's name (as the README says), or by the path given to --hair.
    auto named = runWisp("simulate --json --steps 1 --head '" + head.string() + "' --hair '" + front.string() +
                         "' --hair '" + tail.string() + "' --part hair_tail_16_guide.tfx:global=0.5 --part '" +
                         front.string() + ":local=0.05'");
    ASSERT_EQ(named.status, 0) << named.err;
    nlohmann::json k = nlohmann::json::parse(named.out);
    EXPECT_FLOAT_EQ(k["parts"][1]["global_stiffness"].get<float>(), 0.5f);
    EXPECT_FLOAT_EQ(k["parts"][0]["local_stiffness"].get<float>(), 0.05f);
}

TEST(Cli, RenderLoadedHairInParts)
{
    WISP_REQUIRE_DATA(front, "tressfx-text/hair_front_16_guide.tfx");
    WISP_REQUIRE_DATA(tail, "tressfx-text/hair_tail_16_guide.tfx");
    WISP_REQUIRE_DATA(head, "tressfx-text/head_max4.obj");
    auto r = runWisp("--validation simulate --json --steps 20 --head '" + head.string() + "' --hair '" +
                     front.string() + "' --hair '" + tail.string() + "'");
    ASSERT_EQ(r.status, 0) << r.err;
    nlohmann::json j = nlohmann::json::parse(r.out);
    EXPECT_EQ(j["strands"], 93 + 474);
    ASSERT_EQ(j["parts"].size(), 2u);
    EXPECT_EQ(j["parts"][0]["name"], "hair_front_16_guide");
    EXPECT_EQ(j["parts"][1]["name"], "hair_tail_16_guide");
    EXPECT_EQ(j["nonfinite_resets"], 0);
}

TEST(BadInput, ADegenerateHeadIsRefusedByEveryCommand)
{
    TempDir dir;
    writeFile(dir / "point.obj", "v 1 2 3\nv 1 2 3\nv 1 2 3\nf 1 2 3\n");
    std::string head = " --head '" + (dir / "point.obj").string() + "'";
    std::vector<std::string> commands = {
        "simulate --steps 2 --guides 5",
        "render --guides 5 --width 64 --height 48 --out '" + (dir / "a.png").string() + "'",
        "render --no-hair --width 64 --height 48 --out '" + (dir / "b.png").string() + "'"};
    for (const std::string& command : commands)
        expectUserError(runWisp(command + head), "the mesh is degenerate: all its 3 vertices lie at one point");
    EXPECT_FALSE(std::filesystem::exists(dir / "a.png"));
    EXPECT_FALSE(std::filesystem::exists(dir / "b.png"));
    expectUserError(runWisp("inspect '" + (dir / "point.obj").string() + "'"), "degenerate");
}
