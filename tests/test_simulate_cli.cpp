// tests/test_simulate_cli.cpp: `wisp simulate` through the real binary: the metrics as JSON, the
// per-kernel profile, and a lost device's own exit status.
#include "cli_support.h"
#include "test_support.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

using namespace wisp::test;

TEST(Cli, SimulatePrintsTheMetricsAsJson)
{
    auto r = runWisp("--validation simulate --guides 40 --steps 30 --wind 2,0,0 --sphere 0,0.1,0.15,0.04 --json");
    ASSERT_EQ(r.status, 0) << r.err;
    nlohmann::json j = nlohmann::json::parse(r.out);
    for (const char* key : {"steps", "strands", "vertices", "max_stretch", "max_penetration", "root_drift",
                            "nonfinite_resets", "kinetic_energy", "gpu_ms_per_step"})
        EXPECT_TRUE(j.contains(key)) << key;
    EXPECT_EQ(j["steps"], 30);
    EXPECT_EQ(j["strands"], 40);
    EXPECT_EQ(j["vertices"], 40 * 16);
    EXPECT_LT(j["max_stretch"].get<double>(), 1e-4);
    EXPECT_EQ(j["nonfinite_resets"], 0);
    EXPECT_GE(j["kinetic_energy"].size(), 1u);
}

namespace {

std::string quoted(const std::filesystem::path& p)
{
    return "'" + p.string() + "'";
}

// The hair inside the mesh itself, as simulate reports it, checked for sense: shares of strands
// and of vertices (never more vertices than strands: a strand counts when any of its vertices
// does), the deepest as a fraction of the head's diagonal.
void expectInsideMesh(const nlohmann::json& j)
{
    ASSERT_TRUE(j.contains("inside_mesh")) << j;
    EXPECT_EQ(j["inside_mesh"]["depth"], 0.005f);
    EXPECT_EQ(j["inside_mesh"]["skipped_root_vertices"], 2);
    for (const char* when : {"rest", "final"}) {
        const nlohmann::json& m = j["inside_mesh"][when];
        EXPECT_GE(m["strands"].get<double>(), 0.0);
        EXPECT_LE(m["strands"].get<double>(), 1.0);
        EXPECT_LE(m["vertices"].get<double>(), m["strands"].get<double>()) << m;
        EXPECT_GE(m["deepest"].get<double>(), 0.0);
        EXPECT_LT(m["deepest"].get<double>(), 1.0);
    }
}

} // namespace

TEST(Cli, SimulateReportsTheHairInsideTheMeshOnTheDefaultHead)
{
    // Beside the colliders' penetration; on the default head, whose colliders were tuned to it,
    // no strand ends inside the mesh.
    auto r = runWisp("simulate --guides 60 --steps 60 --json");
    ASSERT_EQ(r.status, 0) << r.err;
    nlohmann::json j = nlohmann::json::parse(r.out);
    expectInsideMesh(j);
    EXPECT_LE(j["inside_mesh"]["rest"]["strands"].get<double>(), 0.01) << j["inside_mesh"];
    EXPECT_LE(j["inside_mesh"]["final"]["strands"].get<double>(), 0.02) << j["inside_mesh"];
    // The text says it too.
    r = runWisp("simulate --guides 20 --steps 4");
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_NE(r.out.find("inside the mesh   "), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("% of strands, "), std::string::npos) << r.out;
}

TEST(Cli, SimulateReportsTheHairInsideSintelsBust)
{
    std::string mesh = WISP_SHARED_DATA "/sintel/sintel.obj";
    if (!std::filesystem::exists(mesh))
        GTEST_SKIP() << "Sintel's bust is not in the shared data (" << mesh << ")";
    // The same groom read back by inspect after the same frames (written by groom --out; 20 frames at 30 fps are
    // 80 steps at 120 Hz) gives the
    // figure simulate gives at its end: one measure, whichever command takes it.
    auto r = runWisp("simulate --head '" + mesh + "' --guides 60 --steps 80 --json");
    ASSERT_EQ(r.status, 0) << r.err;
    nlohmann::json j = nlohmann::json::parse(r.out);
    expectInsideMesh(j);
    wisp::test::TempDir dir;
    r = runWisp("groom --head '" + mesh + "' --guides 60 --frames 20 --out " + quoted(dir / "g.tfx"));
    ASSERT_EQ(r.status, 0) << r.err;
    r = runWisp("inspect --head '" + mesh + "' --hair " + quoted(dir / "g.tfx"));
    ASSERT_EQ(r.status, 0) << r.err;
    nlohmann::json inspected = nlohmann::json::parse(r.out)["inside_mesh"];
    EXPECT_NEAR(inspected["strands"].get<double>(), j["inside_mesh"]["final"]["strands"].get<double>(), 0.05)
        << inspected << j["inside_mesh"];
    EXPECT_NEAR(inspected["deepest"].get<double>(), j["inside_mesh"]["final"]["deepest"].get<double>(), 0.01)
        << inspected << j["inside_mesh"];
}

TEST(Cli, SimulateProfileTimesEveryKernel)
{
    auto r = runWisp("simulate --profile --json --guides 20 --warmup 2 --steps 4");
    ASSERT_EQ(r.status, 0) << r.err;
    nlohmann::json j = nlohmann::json::parse(r.out);
    for (const char* kernel : {"integrate", "grid_gather", "step"}) {
        ASSERT_TRUE(j["ms"].contains(kernel)) << kernel;
        EXPECT_GE(j["ms"][kernel]["median"].get<double>(), 0.0);
        EXPECT_GE(j["ms"][kernel]["p95"].get<double>(), j["ms"][kernel]["median"].get<double>());
    }
}

TEST(Cli, DeviceLostDuringSimulateExitsWithItsOwnStatus)
{
    for (int submission : {1, 20}) {
        auto r = runWisp("--validation simulate --guides 60 --steps 200 --sample-every 10 --json", lostAt(submission));
        expectDeviceLost(r, "simulate");
        EXPECT_TRUE(r.out.empty()) << r.out; // no metrics of an unfinished run
    }
}

TEST(Cli, ProgressInALogIsWholeLines)
{
    // stderr is a pipe here, not a terminal: progress comes as lines of their own, not run
    // together by carriage returns.
    auto r = runWisp("simulate --guides 5 --steps 20 --sample-every 2");
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(r.err.find('\r'), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("simulate: 20 / 20 steps\n"), std::string::npos) << r.err;
    EXPECT_LE(std::count(r.err.begin(), r.err.end(), '\n'), 11) << r.err;
}
