// tests/test_groom_cli.cpp: `wisp groom` through the real binary (the grown guides written
// as cyHair and TressFX 4, at rest and after simulated frames, read back by `wisp inspect` with the
// same strands; every bad input refused with one line, exit 2 and no file), and the groom's figures
// in `wisp simulate --json`: the side standoff, and the tips' lag behind a head turn (above 0 for
// soft hair, about 0 for hair the shape constraints hold rigid).
#include "cli_support.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <string>

using namespace wisp::test;

namespace {

std::string quoted(const std::filesystem::path& p)
{
    return "'" + p.string() + "'";
}

nlohmann::json inspect(const std::string& args)
{
    RunResult r = runWisp("inspect " + args);
    EXPECT_EQ(r.status, 0) << r.err;
    return r.status == 0 ? nlohmann::json::parse(r.out) : nlohmann::json();
}

} // namespace

TEST(Cli, GroomWritesTheGrownGuidesThatInspectReadsBack)
{
    TempDir dir;
    for (const char* name : {"g.hair", "g.tfx"}) {
        std::filesystem::path out = dir / name;
        RunResult r = runWisp("groom --guides 30 --vertices 8 --out " + quoted(out));
        ASSERT_EQ(r.status, 0) << r.err;
        EXPECT_NE(r.out.find("30 guides x 8 vertices at rest"), std::string::npos) << r.out;
        nlohmann::json file = inspect(quoted(out));
        EXPECT_EQ(file["strands"], 30) << name;
        EXPECT_EQ(file["vertices"], 30 * 8) << name;
        EXPECT_EQ(file["format"], std::string(name) == "g.hair" ? "cyhair" : "tfx4");
        EXPECT_EQ(file["up_axis"], std::string(name) == "g.hair" ? "z" : "y");
        // On the default head it was grown on, the roots land where the file has them.
        nlohmann::json onHead = inspect("--hair " + quoted(out) + " --vertices 8");
        EXPECT_EQ(onHead["strands"], 30) << name;
        EXPECT_EQ(onHead["placement"]["method"], "file") << onHead["placement"].dump();
        EXPECT_GT(onHead["side_standoff"].get<double>(), 0.0);
    }
    EXPECT_TRUE(partialFiles(dir.path()).empty());
}

TEST(Cli, GroomAfterFramesWritesWhereTheGuidesHang)
{
    TempDir dir;
    RunResult rest = runWisp("groom --guides 12 --vertices 8 --out " + quoted(dir / "rest.tfx"));
    ASSERT_EQ(rest.status, 0) << rest.err;
    RunResult moved =
        runWisp("--validation groom --guides 12 --vertices 8 --frames 6 --out " + quoted(dir / "moved.tfx"));
    ASSERT_EQ(moved.status, 0) << moved.err;
    EXPECT_NE(moved.out.find("after 6 frames"), std::string::npos) << moved.out;
    EXPECT_EQ(inspect(quoted(dir / "moved.tfx"))["strands"], 12);
    // The hair has fallen a little under gravity: the files differ, their roots do not.
    std::string a = readFile(dir / "rest.tfx"), b = readFile(dir / "moved.tfx");
    ASSERT_EQ(a.size(), b.size());
    EXPECT_NE(a, b);
    for (size_t s = 0; s < 12; ++s) {
        size_t root = 160 + 16 * 8 * s;
        EXPECT_EQ(a.substr(root, 16), b.substr(root, 16)) << "strand " << s;
    }
}

TEST(Cli, GroomRefusesBadOutputsAndWritesNothing)
{
    TempDir dir;
    struct Case {
        std::string args, mention;
    };
    for (const Case& c : std::vector<Case>{
             {"--out " + quoted(dir / "g.obj"), "unknown groom format '.obj'"},
             {"--out " + quoted(dir / "missing" / "g.hair"), "does not exist"},
             {"--out " + quoted(dir.path()), "is a folder"},
             {"--out " + quoted(dir / "g.hair") + " --frames 100001", "--frames"},
             {"--out " + quoted(dir / "g.hair") + " --frames -1", "--frames"},
             {"--guides 10", "--out"},
             {"--out " + quoted(dir / "g.tfx") + " --hair " + quoted(dir / "none.tfx"), "none.tfx"},
         }) {
        RunResult r = runWisp("groom " + c.args);
        expectUserError(r, c.mention);
        EXPECT_TRUE(std::filesystem::is_empty(dir.path())) << c.args;
    }
}

TEST(Cli, SimulateReportsTheSideStandoffAtRestAndAtTheEnd)
{
    RunResult r = runWisp("simulate --guides 30 --steps 20 --json");
    ASSERT_EQ(r.status, 0) << r.err;
    nlohmann::json j = nlohmann::json::parse(r.out);
    double rest = j["side_standoff"]["rest"].get<double>(), last = j["side_standoff"]["final"].get<double>();
    EXPECT_GT(rest, 0.0);
    EXPECT_LT(rest, 2.0);
    EXPECT_GT(last, 0.0);
    EXPECT_TRUE(j["tip_lag_deg"].is_null()) << j["tip_lag_deg"]; // the head does not turn
}

TEST(Cli, SimulateReportsTheTipsLagBehindAHeadTurn)
{
    TempDir dir;
    writeFile(dir / "turn.json", R"({"version": 1, "interpolation": "smooth", "duration": 1.5,
        "keys": [{"time": 0.0, "head_yaw": 0}, {"time": 0.6, "head_yaw": 60}, {"time": 1.5, "head_yaw": 60}]})");
    auto lag = [&](const std::string& extra) {
        RunResult r = runWisp("simulate --guides 24 --vertices 8 --steps 120 --json --scene " +
                              quoted(dir / "turn.json") + extra);
        EXPECT_EQ(r.status, 0) << r.err;
        nlohmann::json j = r.status == 0 ? nlohmann::json::parse(r.out) : nlohmann::json();
        EXPECT_TRUE(j["tip_lag_deg"].is_object()) << r.out;
        EXPECT_NEAR(j["tip_lag_deg"]["head_yaw_max"].get<double>(), 60.0, 2.0);
        return j["tip_lag_deg"];
    };
    nlohmann::json soft = lag("");
    nlohmann::json rigid = lag(" --set global_stiffness=1 --set local_stiffness=1");
    EXPECT_GT(soft["peak"].get<double>(), 2.0) << soft;
    EXPECT_GE(soft["peak"].get<double>(), soft["final"].get<double>());
    EXPECT_LT(rigid["peak"].get<double>(), 0.5) << rigid;
}

TEST(GroomCommandCli, ALoadedGroomsDensityIsChosenAndSaidUnlessGiven)
{
    // A groom of 4,000 strands, written by `wisp groom`, drawn on the default head: 25 strands
    // each (about 100,000), said in one line; strands_per_guide given on the command line wins.
    TempDir dir;
    std::filesystem::path groom = dir / "groom.tfx";
    ASSERT_EQ(runWisp("groom --guides 4000 --vertices 8 --out " + quoted(groom)).status, 0);
    std::string render = "render --width 48 --height 36 --hair " + quoted(groom) + " --out " + quoted(dir / "a.png");
    RunResult chosen = runWisp(render);
    ASSERT_EQ(chosen.status, 0) << chosen.err;
    EXPECT_NE(chosen.out.find("hair density: 4000 strands in the file, each drawn as 25 (strands_per_guide"),
              std::string::npos)
        << chosen.out;
    EXPECT_NE(chosen.out.find("4000 guides x 25 strands"), std::string::npos) << chosen.out;
    RunResult given = runWisp(render + " --set strands_per_guide=3");
    ASSERT_EQ(given.status, 0) << given.err;
    EXPECT_EQ(given.out.find("hair density"), std::string::npos) << given.out;
    EXPECT_NE(given.out.find("4000 guides x 3 strands"), std::string::npos) << given.out;

    // A loaded groom's drawn strands keep their guides' lengths (strand_length_jitter 0) unless
    // it is given: the same fragments as with 0 given, fewer with strands cut.
    auto fragments = [](const std::string& out) {
        size_t at = out.find(" hair fragments");
        size_t from = out.rfind(", ", at);
        return at == std::string::npos || from == std::string::npos ? std::string() : out.substr(from, at - from);
    };
    RunResult whole = runWisp(render + " --set strand_length_jitter=0");
    RunResult cut = runWisp(render + " --set strand_length_jitter=0.6");
    ASSERT_EQ(whole.status, 0) << whole.err;
    ASSERT_EQ(cut.status, 0) << cut.err;
    ASSERT_NE(fragments(chosen.out), "") << chosen.out;
    EXPECT_EQ(fragments(chosen.out), fragments(whole.out)) << chosen.out << whole.out;
    EXPECT_NE(fragments(cut.out), fragments(whole.out)) << cut.out;
}
