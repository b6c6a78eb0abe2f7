// tests/test_simulate_cli.cpp: `wisp simulate` through the real binary: the metrics as JSON, the
// per-kernel profile, and a lost device's own exit status.
#include "cli_support.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdio>
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
