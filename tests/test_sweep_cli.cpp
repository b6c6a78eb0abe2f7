// tests/test_sweep_cli.cpp: `wisp sweep` through the real binary: a tiny grid's CSV and charts,
// the pass columns of both ways of drawing hair, and --vary values checked before anything is
// written.
#include "app/session/sweep.h"
#include "cli_support.h"
#include "groom_files.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <map>
#include <string>

using namespace wisp::test;

TEST(Sweep, TinyGridWritesAWellFormedCsvAndCharts)
{
    TempDir dir;
    auto r = runWisp(
        "--validation sweep --out '" + (dir / "s").string() +
        "' --vary strands_per_guide=1,3 --vary divisions=2,5 --warmup 1 --frames 2 --width 64 --height 48 --guides 20");
    ASSERT_EQ(r.status, 0) << r.err;
    std::ifstream in(dir / "s" / "results.csv");
    std::string header;
    std::getline(in, header);
    EXPECT_EQ(header.rfind("strands_per_guide,divisions,physics_ms_median,", 0), 0u) << header;
    size_t columns = size_t(std::count(header.begin(), header.end(), ',')) + 1;
    std::vector<std::string> rows;
    for (std::string line; std::getline(in, line);)
        rows.push_back(line);
    ASSERT_EQ(rows.size(), 4u);                // the 2 x 2 grid
    auto fields = [](const std::string& row) { // commas inside quotes ("llvmpipe (LLVM 15, 256 bits)") do not count
        size_t n = 1;
        bool quoted = false;
        for (char c : row) {
            quoted = c == '"' ? !quoted : quoted;
            n += (c == ',' && !quoted) ? 1 : 0;
        }
        return n;
    };
    for (const std::string& row : rows)
        EXPECT_EQ(fields(row), columns) << row;
    EXPECT_EQ(rows[0].rfind("1,2,", 0), 0u);
    EXPECT_EQ(rows[3].rfind("3,5,", 0), 0u);
    EXPECT_NE(rows[3].find(",60,"), std::string::npos) << rows[3]; // 20 guides x 3 strands
    for (const char* chart : {"fps.png", "frame.png", "passes.png"})
        EXPECT_GT(std::filesystem::file_size(dir / "s" / chart), 1000u) << chart;
}

namespace {

// A CSV line's fields (commas inside quotes do not split).
std::vector<std::string> csvFields(const std::string& line)
{
    std::vector<std::string> out(1);
    bool quoted = false;
    for (char c : line) {
        if (c == '"')
            quoted = !quoted;
        else if (c == ',' && !quoted)
            out.emplace_back();
        else
            out.back() += c;
    }
    return out;
}

} // namespace

TEST(Sweep, ColumnsAreThePassesEveryPointRanAndThePathThatDrew)
{
    // The graphics path and the compute path run different passes: the columns are all of them,
    // each point's missing ones 0, the frame last; the compute path's counts beside the OIT's.
    TempDir dir;
    auto r =
        runWisp("--validation sweep --out '" + (dir / "s").string() +
                "' --vary hair_raster=graphics,compute,auto --warmup 1 --frames 2 --width 64 --height 48 --guides 20 "
                "--set strands_per_guide=2 --set divisions=4 --set shadow_size=128");
    ASSERT_EQ(r.status, 0) << r.err;
    std::ifstream in(dir / "s" / "results.csv");
    std::string line;
    std::getline(in, line);
    std::vector<std::string> header = csvFields(line);
    std::vector<std::map<std::string, std::string>> rows;
    while (std::getline(in, line)) {
        std::vector<std::string> fields = csvFields(line);
        ASSERT_EQ(fields.size(), header.size()) << line;
        std::map<std::string, std::string> row;
        for (size_t i = 0; i < header.size(); ++i)
            row[header[i]] = fields[i];
        rows.push_back(row);
    }
    ASSERT_EQ(rows.size(), 3u);
    auto column = [&](const std::string& name) {
        return std::find(header.begin(), header.end(), name) - header.begin();
    };
    for (const char* name :
         {"hair_ms_median", "oit.resolve_ms_median", "strands.count_ms_median", "strands.write_ms_median",
          "strands.resolve_ms_median", "hair.composite_ms_median", "meshes.depth_ms_median", "light.depth_ms_median",
          "raster_segments", "raster_fragments", "raster_overflow", "hair_raster_drawn"})
        EXPECT_LT(size_t(column(name)), header.size()) << name << " in " << line;
    // The frame's columns close the passes', and come after every pass.
    EXPECT_EQ(column("frame_ms_p95") + 1, column("fps"));
    EXPECT_LT(column("strands.resolve_ms_p95"), column("frame_ms_median"));
    EXPECT_EQ(column("raster_segments"), column("oit_overflow") + 1);
    EXPECT_EQ(header.front(), "hair_raster");

    const auto& graphics = rows[0];
    const auto& compute = rows[1];
    const auto& automatic = rows[2];
    EXPECT_EQ(graphics.at("hair_raster_drawn"), "graphics");
    EXPECT_EQ(compute.at("hair_raster_drawn"), "compute");
    EXPECT_EQ(automatic.at("hair_raster_drawn"), "compute") << "auto draws in compute";
    EXPECT_EQ(std::stod(graphics.at("strands.resolve_ms_median")), 0.0) << "not run by the graphics path";
    EXPECT_GT(std::stod(compute.at("strands.resolve_ms_median")), 0.0);
    EXPECT_GT(std::stod(graphics.at("hair_ms_median")), 0.0);
    EXPECT_EQ(std::stod(compute.at("hair_ms_median")), 0.0) << "not run by the compute path";
    EXPECT_GT(std::stoull(graphics.at("oit_fragments")), 0u);
    EXPECT_EQ(std::stoull(compute.at("oit_fragments")), 0u);
    EXPECT_EQ(std::stoull(graphics.at("raster_fragments")), 0u);
    EXPECT_GT(std::stoull(compute.at("raster_segments")), 0u);
    EXPECT_LE(std::stoull(compute.at("raster_segments")), 20u * 2u * 4u) << "the segments on screen, of 160";
    EXPECT_GT(std::stoull(compute.at("raster_fragments")), 0u);
    EXPECT_EQ(compute.at("raster_overflow"), "0");
    for (const char* chart : {"fps.png", "frame.png", "passes.png"})
        EXPECT_GT(std::filesystem::file_size(dir / "s" / chart), 1000u) << chart;
}

TEST(BadInput, SweepVaryValuesAreChecked)
{
    TempDir dir;
    std::string out = " --out '" + (dir / "s").string() + "'";
    expectUserError(runWisp("sweep --vary sparkle=1,2" + out), "unknown setting 'sparkle'");
    auto r = runWisp("sweep --vary divisions=4,0" + out);
    expectUserError(r, "--vary divisions=4,0");
    EXPECT_NE(r.err.find("1 .. 1024"), std::string::npos) << r.err;
    expectUserError(runWisp("sweep --vary divisions" + out), "NAME=V1,V2");
    expectUserError(runWisp("sweep --vary divisions=4,,8" + out), "empty value");
    expectUserError(runWisp("sweep --vary divisions=4,8," + out), "--vary divisions=4,8,: an empty value (a trailing");
    expectUserError(runWisp("sweep --vary oit_k=1,2 --vary oit_k=3,4" + out),
                    "--vary oit_k=3,4: oit_k is varied twice (also by --vary oit_k=1,2)");
    expectUserError(runWisp("sweep --vary divisions=4,8,4" + out), "--vary divisions=4,8,4: 4 is given twice");
    expectUserError(runWisp("sweep --vary light_intensity=2,2.0" + out), "2.0 is given twice"); // one value, two ways
    EXPECT_FALSE(std::filesystem::exists(dir / "s")); // checked before anything is written
}

TEST(BadInput, ASweepGridTooLargeIsRefusedUpFrontWithItsSize)
{
    TempDir dir;
    std::string values;
    for (int v = 1; v <= 65; ++v) // 65 x 65 = 4225 points, past kSweepMostPoints
        values += (values.empty() ? "" : ",") + std::to_string(v);
    static_assert(65 * 65 > wisp::kSweepMostPoints && 65 <= wisp::kSweepMostPoints);
    auto r =
        runWisp("sweep --out '" + (dir / "s").string() + "' --vary seed=" + values + " --vary divisions=" + values);
    expectUserError(r, "--vary: the grid has 4225 points (65 x 65 values); a sweep runs at most " +
                           std::to_string(wisp::kSweepMostPoints));
    EXPECT_EQ(r.err.find("point 1/"), std::string::npos) << r.err; // refused before the first point
    EXPECT_FALSE(std::filesystem::exists(dir / "s"));
}

TEST(BadInput, ASweepFailingAtItsSecondPointLeavesNoFolder)
{
    // The second point's pool (1024 x 1024 x 256 nodes of 12 bytes) is more than the device
    // allows; the first point has run by then (a loaded groom is checked per point, once loaded).
    // The graphics path draws the hair: only it makes the lists (the compute path's frame needs no pool).
    // Nothing half-written: no folder, and a folder that was already there keeps what it held.
    TempDir dir;
    wisp::test::writeTfx4(dir / "groom.tfx", wisp::test::grownStrands(5, 4, [](glm::vec3 p) { return p; }));
    std::string args =
        " --hair '" + (dir / "groom.tfx").string() +
        "' --vary oit_nodes_per_pixel=1,256 --width 1024 --height 1024 --warmup 0 --frames 1 --set shadow_size=64 "
        "--set hair_raster=graphics";
    auto r = runWisp("sweep --out '" + (dir / "s").string() + "'" + args);
    EXPECT_EQ(r.status, 2) << r.err;
    EXPECT_NE(r.err.find("point 2/2"), std::string::npos) << r.err; // the progress lines, then one error line
    EXPECT_NE(r.err.find("\nwisp: the OIT fragment pool"), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(dir / "s"));
    std::filesystem::create_directories(dir / "mine");
    writeFile(dir / "mine" / "notes.txt", "kept");
    EXPECT_EQ(runWisp("sweep --out '" + (dir / "mine").string() + "'" + args).status, 2);
    EXPECT_EQ(readFile(dir / "mine" / "notes.txt"), "kept");
    EXPECT_FALSE(std::filesystem::exists(dir / "mine" / "results.csv"));
}
