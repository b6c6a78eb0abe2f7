// tests/test_hostile_cli.cpp: what a hostile but realistic user tried, through the real binary: a
// full disk under every writer (a real one, a filled tmpfs, where the machine lets a test mount
// it; an injected write failure, WISP_INJECT_WRITE_FAILURE, everywhere), /dev/full as standard
// output, a style given every way under explicit options, short grown hair that is rigid, parts
// of mixed formats, what each export format keeps, a sweep's contradictions, and the messages of
// the options the argument parser checks. Each test names the command it runs.
#include "cli_support.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <string>
#include <sys/wait.h>
#include <vector>

using namespace wisp::test;

namespace {

std::string quoted(const std::filesystem::path& p)
{
    return "'" + p.string() + "'";
}

// A bad run's checks for a write that failed: exit 2, one line naming `file` and the full disk,
// and no temporary file under `dir`.
void expectWriteFailure(const RunResult& r, const std::filesystem::path& file, const std::filesystem::path& dir)
{
    expectUserError(r, "cannot write " + file.string() + ": No space left on device");
    EXPECT_TRUE(partialFiles(dir).empty()) << r.err;
}

const std::string kInject = "WISP_INJECT_WRITE_FAILURE=";

} // namespace

// ---- the full disk ---------------------------------------------------------------------------

// wisp render --no-hair --width 160 --height 120 --out FULL/r.png, on a real full disk (a 64 KiB
// tmpfs, filled), over a good r.png: it exited 0 and left r.png at 0 bytes.
TEST(HostileDisk, RenderOnAFullDiskFailsNamingThePictureAndKeepsTheEarlierOne)
{
    WISP_REQUIRE_SMALL_DISK(disk, 64 * 1024);
    TempDir dir;
    std::string args = "render --no-hair --width 160 --height 120 --out ";
    ASSERT_EQ(runWisp(args + quoted(dir / "r.png")).status, 0);
    std::string good = readFile(dir / "r.png");
    ASSERT_GT(good.size(), 1000u);
    std::filesystem::copy_file(dir / "r.png", disk / "r.png");
    ASSERT_GT(disk.fill(), 0u);
    auto r = runWisp(args + quoted(disk / "r.png"));
    expectWriteFailure(r, disk / "r.png", disk.path());
    EXPECT_EQ(readFile(disk / "r.png"), good); // the earlier picture, whole
    // A new file on the full disk: nothing is left behind at all.
    r = runWisp(args + quoted(disk / "big.png"));
    expectWriteFailure(r, disk / "big.png", disk.path());
    EXPECT_FALSE(std::filesystem::exists(disk / "big.png"));
}

// wisp record --no-hair --frames 3 --out FULL/rec on a full disk: it exited 0 with truncated and
// empty frames and contact sheet.
TEST(HostileDisk, RecordOnAFullDiskFailsNamingTheFrame)
{
    WISP_REQUIRE_SMALL_DISK(disk, 64 * 1024);
    std::filesystem::create_directories(disk / "rec");
    ASSERT_GT(disk.fill(), 0u);
    auto r = runWisp("record --no-hair --frames 3 --width 96 --height 64 --out " + quoted(disk / "rec"));
    EXPECT_EQ(r.status, 2) << r.err;
    EXPECT_NE(
        r.err.find("wisp: cannot write " + (disk / "rec" / "frame_00000.png").string() + ": No space left on device"),
        std::string::npos)
        << r.err;
    EXPECT_FALSE(std::filesystem::exists(disk / "rec" / "frame_00000.png"));
    EXPECT_TRUE(partialFiles(disk.path()).empty());
}

// WISP_INJECT_WRITE_FAILURE=1 wisp render --no-hair --width 96 --height 64 --out r.png over a good
// r.png: the picture fails half-written, as on a full disk, and r.png keeps what it held.
TEST(HostileDisk, RenderWithAFailedWriteKeepsTheEarlierPicture)
{
    TempDir dir;
    std::string args = "render --no-hair --width 96 --height 64 --out " + quoted(dir / "r.png");
    ASSERT_EQ(runWisp(args).status, 0);
    std::string good = readFile(dir / "r.png");
    auto r = runWisp(args, kInject + "1");
    expectWriteFailure(r, dir / "r.png", dir.path());
    EXPECT_TRUE(r.out.empty()) << r.out; // the picture's name is printed only once it is written
    EXPECT_EQ(readFile(dir / "r.png"), good);
}

// WISP_INJECT_WRITE_FAILURE=2 (the second frame) and =4 (the contact sheet, after 3 frames)
// wisp record --no-hair --frames 3 --width 96 --height 64 --out rec: exit 2 naming the file.
TEST(HostileDisk, RecordWithAFailedWriteNamesTheFrameOrTheSheet)
{
    TempDir dir;
    std::string args = "record --no-hair --frames 3 --width 96 --height 64 --overwrite --out " + quoted(dir / "rec");
    // The progress lines, then the one error line.
    auto expectLastLine = [&](const RunResult& r, const std::filesystem::path& file) {
        EXPECT_EQ(r.status, 2) << r.err;
        std::string line = "wisp: cannot write " + file.string() + ": No space left on device\n";
        EXPECT_TRUE(r.err.size() >= line.size() && r.err.compare(r.err.size() - line.size(), line.size(), line) == 0)
            << r.err;
        EXPECT_EQ(r.err.find("wisp: "), r.err.rfind("wisp: ")) << r.err; // one line of wisp's own
        EXPECT_TRUE(partialFiles(dir.path()).empty());
    };
    expectLastLine(runWisp(args, kInject + "2"), dir / "rec" / "frame_00001.png");
    EXPECT_TRUE(std::filesystem::exists(dir / "rec" / "frame_00000.png"));
    EXPECT_FALSE(std::filesystem::exists(dir / "rec" / "frame_00001.png"));
    expectLastLine(runWisp(args, kInject + "4"), dir / "rec" / "contact_sheet.png");
    EXPECT_FALSE(std::filesystem::exists(dir / "rec" / "contact_sheet.png"));
}

// WISP_INJECT_WRITE_FAILURE=5 wisp record --no-hair --frames 3 ... --video v.mp4: the three frames
// and the sheet are written, then the video (ffmpeg's, into the temporary file) fails: exit 2
// naming it, no video and no temporary left.
TEST(HostileDisk, RecordWithAFailedVideoWriteNamesTheVideo)
{
    TempDir dir;
    auto r = runWisp("record --no-hair --frames 3 --width 96 --height 64 --out " + quoted(dir / "rec") + " --video " +
                         quoted(dir / "v.mp4"),
                     kInject + "5");
    EXPECT_EQ(r.status, 2) << r.err;
    EXPECT_NE(r.err.find("wisp: cannot write " + (dir / "v.mp4").string() + ": No space left on device"),
              std::string::npos)
        << r.err;
    EXPECT_TRUE(std::filesystem::exists(dir / "rec" / "contact_sheet.png"));
    EXPECT_FALSE(std::filesystem::exists(dir / "v.mp4"));
    EXPECT_TRUE(partialFiles(dir.path()).empty());
}

// WISP_INJECT_WRITE_FAILURE=1 wisp sweep --vary divisions=2 ... --out s: results.csv fails, and the
// sweep leaves nothing (its folder was made for it).
TEST(HostileDisk, SweepWithAFailedCsvWriteLeavesNothing)
{
    TempDir dir;
    auto r = runWisp("sweep --out " + quoted(dir / "s") +
                         " --vary divisions=2 --warmup 0 --frames 1 --width 64 --height 48 --guides 8",
                     kInject + "1");
    // The points' progress lines, then the one error line.
    EXPECT_EQ(r.status, 2) << r.err;
    EXPECT_NE(
        r.err.find("\nwisp: cannot write " + (dir / "s" / "results.csv").string() + ": No space left on device\n"),
        std::string::npos)
        << r.err;
    EXPECT_FALSE(std::filesystem::exists(dir / "s"));
}

// WISP_INJECT_WRITE_FAILURE=1 wisp groom --guides 20 --out g.tfx, and compare --out diff.png.
TEST(HostileDisk, GroomAndCompareWithAFailedWriteKeepTheEarlierFiles)
{
    TempDir dir;
    std::string groom = "groom --guides 20 --out " + quoted(dir / "g.tfx");
    ASSERT_EQ(runWisp(groom).status, 0);
    std::string good = readFile(dir / "g.tfx");
    expectWriteFailure(runWisp(groom, kInject + "1"), dir / "g.tfx", dir.path());
    EXPECT_EQ(readFile(dir / "g.tfx"), good);

    ASSERT_EQ(runWisp("render --no-hair --width 32 --height 32 --out " + quoted(dir / "a.png")).status, 0);
    std::string compare =
        "compare " + quoted(dir / "a.png") + " " + quoted(dir / "a.png") + " --out " + quoted(dir / "diff.png");
    ASSERT_EQ(runWisp(compare).status, 0) << runWisp(compare).err;
    std::string diff = readFile(dir / "diff.png");
    expectWriteFailure(runWisp(compare, kInject + "1"), dir / "diff.png", dir.path());
    EXPECT_EQ(readFile(dir / "diff.png"), diff);
}

// wisp settings >/dev/full and wisp simulate --json --steps 2 --guides 8 >/dev/full: what a
// command prints is lost, and it said nothing and exited 0.
TEST(HostileDisk, AFullStandardOutputFailsTheRun)
{
    TempDir dir;
    for (const char* args : {"settings", "simulate --json --steps 2 --guides 8"}) {
        std::string command = "'" WISP_BINARY "' " + std::string(args) + " >/dev/full 2>" + quoted(dir / "err");
        int raw = std::system(command.c_str());
        ASSERT_TRUE(WIFEXITED(raw));
        RunResult r{WEXITSTATUS(raw), "", readFile(dir / "err")};
        expectUserError(r, "wisp: cannot write the standard output: No space left on device");
    }
}

// ---- a style given any way, under explicit options ---------------------------------------------

// wisp simulate --json --steps 2 --set hair_style=afro --guides 60: it simulated the afro's 2,400
// guides (--style afro --guides 60 kept 60).
TEST(HostileStyle, AStyleBySetKeepsAnExplicitGuideCount)
{
    for (const char* style : {"--set hair_style=afro", "--style afro"})
        for (const char* order : {"first", "last"}) {
            std::string args = std::string(order) == "first" ? std::string(style) + " --guides 60 --set curl_turns=3"
                                                             : std::string("--set curl_turns=3 --guides 60 ") + style;
            auto r = runWisp("simulate --json --steps 2 " + args);
            ASSERT_EQ(r.status, 0) << args << "\n" << r.err;
            auto j = nlohmann::json::parse(r.out);
            EXPECT_EQ(j["strands"], 60) << args;
            EXPECT_EQ(j["settings"]["hair_style"], "custom") << args; // the afro, refined
            EXPECT_EQ(j["settings"]["curl_turns"], 3) << args;
            EXPECT_GT(j["settings"]["curl"].get<double>(), 0.0) << args; // the afro's own curl stays
        }
}

// wisp sweep --guides 60 --vary hair_style=bob,afro: it drew 101,200 and 76,800 strands, and
// results.csv had no column that showed the guides.
TEST(HostileStyle, ASweepOfStylesKeepsAnExplicitGuideCountAndRecordsIt)
{
    TempDir dir;
    auto r = runWisp("sweep --out " + quoted(dir / "s") +
                     " --guides 60 --vary hair_style=bob,afro --warmup 0 --frames 1 --width 64 --height 48");
    ASSERT_TRUE(std::filesystem::exists(dir / "s" / "results.csv")) << r.err;
    std::ifstream in(dir / "s" / "results.csv");
    std::string header, line;
    std::getline(in, header);
    std::vector<std::string> names;
    for (size_t at = 0; at <= header.size();) {
        size_t comma = header.find(',', at);
        names.push_back(header.substr(at, comma == std::string::npos ? std::string::npos : comma - at));
        at = comma == std::string::npos ? header.size() + 1 : comma + 1;
    }
    auto column = [&](const std::string& name) {
        return size_t(std::find(names.begin(), names.end(), name) - names.begin());
    };
    ASSERT_LT(column("guides"), names.size()) << header;
    ASSERT_LT(column("strands"), names.size()) << header;
    std::vector<uint64_t> strands;
    while (std::getline(in, line)) {
        std::vector<std::string> fields;
        for (size_t at = 0; at <= line.size();) {
            size_t comma = line.find(',', at);
            fields.push_back(line.substr(at, comma == std::string::npos ? std::string::npos : comma - at));
            at = comma == std::string::npos ? line.size() + 1 : comma + 1;
        }
        EXPECT_EQ(fields[column("guides")], "60") << line;
        strands.push_back(std::stoull(fields[column("strands")]));
    }
    ASSERT_EQ(strands.size(), 2u);
    for (uint64_t s : strands) { // 60 guides times the style's strands a guide, whatever it is
        EXPECT_EQ(s % 60, 0u) << s;
        EXPECT_LE(s, 60u * 64u) << s;
    }
}

// ---- short grown hair --------------------------------------------------------------------------

// wisp simulate --json --steps 20 --guides 60 --hair-length 0.035: every strand was rigid
// (kinetic energy 0) and nothing said so; --set hair_length=0.01, the documented minimum, too.
TEST(HostileShortHair, ShortGrownHairMovesAndItsRigidStrandsAreReported)
{
    // wisp simulate --guides 60 --hair-length 0.035 reported kinetic energy 0 and nothing else:
    // 3.5 cm is below the rigid length (4 cm), and now says so. 8 cm moves.
    auto r = runWisp("simulate --json --steps 20 --guides 60 --hair-length 0.035");
    ASSERT_EQ(r.status, 0) << r.err;
    auto j = nlohmann::json::parse(r.out);
    ASSERT_TRUE(j.contains("rigid_strands")) << r.out;
    EXPECT_EQ(j["rigid_strands"]["of"], 60);
    EXPECT_GE(j["rigid_strands"]["count"].get<int>(), 30) << r.out;
    r = runWisp("simulate --json --steps 20 --guides 60 --hair-length 0.08");
    ASSERT_EQ(r.status, 0) << r.err;
    j = nlohmann::json::parse(r.out);
    EXPECT_LT(j["rigid_strands"]["count"].get<int>(), 30) << r.out;
    EXPECT_GT(j["worst"]["kinetic_energy"].get<double>(), 0.0) << r.out;
    // 1 cm is rigid throughout, and says so: in the JSON and in one line of the text report.
    r = runWisp("simulate --json --steps 2 --guides 60 --set hair_length=0.01");
    ASSERT_EQ(r.status, 0) << r.err;
    j = nlohmann::json::parse(r.out);
    EXPECT_GE(j["rigid_strands"]["count"].get<int>(), 55) << r.out; // a stray lifted past 4 cm may move
    EXPECT_GT(j["rigid_strands"]["shorter_than"].get<double>(), 0.0);
    r = runWisp("simulate --steps 2 --guides 60 --set hair_length=0.01");
    ASSERT_EQ(r.status, 0) << r.err;
    std::regex line(R"(hair strands: (\d+) of 60 grown guides rigid \(shorter than 4 cm: they follow the head)");
    std::smatch m;
    ASSERT_TRUE(std::regex_search(r.out, m, line)) << r.out;
    EXPECT_EQ(m[1].str(), std::to_string(j["rigid_strands"]["count"].get<int>()));
    // render's summary says it too.
    TempDir dir;
    r = runWisp("render --guides 20 --set hair_length=0.01 --width 48 --height 32 --out " + quoted(dir / "r.png"));
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_TRUE(std::regex_search(r.out, std::regex(R"(hair strands: \d+ of 20 grown guides rigid)"))) << r.out;
    // Long hair has none, and says nothing (the bob has a few: those its trim line cuts short).
    r = runWisp("simulate --json --steps 2 --guides 60 --style long");
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(nlohmann::json::parse(r.out)["rigid_strands"]["count"], 0);
    r = runWisp("simulate --steps 2 --guides 60 --style long");
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(r.out.find("grown guides rigid"), std::string::npos) << r.out;
}

// ---- parts of mixed formats --------------------------------------------------------------------

// wisp groom --out g.tfx; wisp groom --out g.hair; wisp groom --hair g.tfx --hair g.hair --out
// both.tfx: the two exports of one groom, each loading alone, were refused together ("roots are
// not on the head ... y-up"): the cyHair part's z-up turn was applied to the whole groom.
TEST(HostileParts, PartsOfMixedFormatsArePlacedEachByItsOwnFormat)
{
    TempDir dir;
    ASSERT_EQ(runWisp("groom --guides 40 --out " + quoted(dir / "g.tfx")).status, 0);
    ASSERT_EQ(runWisp("groom --guides 40 --out " + quoted(dir / "g.hair")).status, 0);
    for (const char* order : {"tfx first", "hair first"}) {
        std::string hair = std::string(order) == "tfx first"
                               ? "--hair " + quoted(dir / "g.tfx") + " --hair " + quoted(dir / "g.hair")
                               : "--hair " + quoted(dir / "g.hair") + " --hair " + quoted(dir / "g.tfx");
        auto r = runWisp("groom " + hair + " --out " + quoted(dir / "both.tfx"));
        EXPECT_EQ(r.status, 0) << order << "\n" << r.err;
        EXPECT_EQ(r.err.find("warning"), std::string::npos) << order << "\n" << r.err;
    }
}

// ---- what each export keeps --------------------------------------------------------------------

// wisp groom --guides 40 --out g.tfx, then wisp groom --hair g.tfx --out again.tfx: the points
// moved by up to 0.84 mm (resampled); they stay where they were.
TEST(HostileExport, ATfxRoundTripKeepsThePoints)
{
    TempDir dir;
    ASSERT_EQ(runWisp("groom --guides 40 --out " + quoted(dir / "g.tfx")).status, 0);
    auto r = runWisp("groom --hair " + quoted(dir / "g.tfx") + " --out " + quoted(dir / "again.tfx"));
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(readFile(dir / "again.tfx"), readFile(dir / "g.tfx")); // the same bytes: points and pinning
}

// wisp groom --guides 40 --out g.hair: cyHair carries no pinning; one line says what is lost.
TEST(HostileExport, ACyHairExportSaysWhatItsFormatCannotCarry)
{
    TempDir dir;
    auto r = runWisp("groom --guides 40 --out " + quoted(dir / "g.hair"));
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(lineCount(r.err), 1u) << r.err;
    EXPECT_NE(r.err.find("cyHair carries no pinning"), std::string::npos) << r.err;
    // Every one of the 40 guides loses its pinning: pinned at its first segment, or rigid (the few
    // the bob's trim cuts shorter than the rigid length).
    std::smatch m;
    ASSERT_TRUE(std::regex_search(
        r.err, m, std::regex(R"(lost (\d+) strands pinned at their first segment(, (\d+) rigid strands)?)")))
        << r.err;
    EXPECT_EQ(std::stoi(m[1].str()) + (m[3].matched ? std::stoi(m[3].str()) : 0), 40) << r.err;
    r = runWisp("groom --guides 40 --out " + quoted(dir / "g.tfx"));
    EXPECT_TRUE(r.err.empty()) << r.err; // TressFX keeps it
}

// ---- a sweep's contradictions, before the first point ------------------------------------------

// wisp sweep --vary curl_turns=1,15 --vary curl=0.05 --set vertices_per_strand=16: it failed only
// after point 1 had run.
TEST(HostileSweep, EveryPointIsCheckedBeforeTheFirstRuns)
{
    TempDir dir;
    auto r = runWisp("sweep --out " + quoted(dir / "s") +
                     " --vary curl_turns=1,15 --vary curl=0.05 --set vertices_per_strand=16 --warmup 0 --frames 1 "
                     "--width 64 --height 48 --guides 8");
    expectUserError(r, "sweep: point 2/2 (curl_turns=15, curl=0.05), before any point ran: curl_turns 15");
    EXPECT_FALSE(std::filesystem::exists(dir / "s"));
}

// ---- messages ----------------------------------------------------------------------------------

// wisp groom --out DIR: it said "unknown groom format ''".
TEST(HostileMessages, GroomIntoAFolderSaysItIsAFolder)
{
    TempDir dir;
    expectUserError(runWisp("groom --out " + quoted(dir.path())), "is a folder; name the groom file in it");
}

// wisp simulate --set curl_turns=20 ...: its range said 0 .. 20, but 16 and more could never be
// used with curl, and the advice was to raise vertices_per_strand to 64 when it already was.
TEST(HostileMessages, CurlTurnsRangeIsTrueAndItsAdviceRight)
{
    expectUserError(runWisp("simulate --steps 1 --set curl=0.05 --set curl_turns=20"),
                    "--set curl_turns: 20 is out of range: allowed 0 .. 15");
    auto r = runWisp("simulate --steps 1 --guides 8 --set curl=0.05 --set curl_turns=15 --set curl_randomness=1 "
                     "--set vertices_per_strand=64");
    expectUserError(r, "at most 64 vertices a strand hold 10.5 such turns (lower curl_turns or curl_randomness)");
    EXPECT_EQ(r.err.find("raise vertices_per_strand"), std::string::npos) << r.err;
    expectUserError(runWisp("simulate --steps 1 --guides 8 --set curl=0.05 --set curl_turns=15 "
                            "--set curl_randomness=0 --set vertices_per_strand=32"),
                    "raise vertices_per_strand to 61 or lower curl_turns");
    // The largest in range fits the most vertices.
    EXPECT_EQ(runWisp("simulate --steps 1 --guides 8 --set curl=0.05 --set curl_turns=15 "
                      "--set curl_randomness=0 --set vertices_per_strand=64")
                  .status,
              0);
}

// wisp render --reference --sample-seed 4294967296 (and -1): "Could not convert"; --spp 0,
// --bounces 0, --width 100000, compare --error-scale nan: "Value 0 not in range 1 to 1000000"; two
// --style: "At Most 1 required but received 2". Every option speaks the project's one form.
TEST(HostileMessages, OptionsTheParserChecksSpeakTheProjectsForm)
{
    TempDir dir;
    std::string out = " --out " + quoted(dir / "r.png");
    struct Case {
        std::string args, line;
    };
    for (const Case& c : std::vector<Case>{
             {"render --reference --sample-seed 4294967296" + out,
              "wisp: --sample-seed: 4294967296 is out of range: allowed 0 .. 4294967295\n"},
             {"render --reference --sample-seed -1" + out, "wisp: --sample-seed: -1 is out of range: allowed 0 .. "
                                                           "4294967295\n"},
             {"render --reference --spp 0" + out, "wisp: --spp: 0 is out of range: allowed 1 .. 1000000\n"},
             {"render --reference --bounces 0" + out, "wisp: --bounces: 0 is out of range: allowed 1 .. 1000\n"},
             {"render --width 100000" + out, "wisp: --width: 100000 is out of range: allowed 16 .. 8192\n"},
             {"render --frames 2.5" + out, "wisp: --frames: 2.5 is not a whole number\n"},
             {"render --fps nan" + out, "wisp: --fps: 'nan' is not a finite number\n"},
             {"compare " + quoted(dir / "a.png") + " " + quoted(dir / "a.png") + " --error-scale nan",
              "wisp: --error-scale: 'nan' is not a finite number\n"},
             {"render --style afro --style bob" + out,
              "wisp: --style: given 2 times; it takes one value (give it once)\n"},
             {"bsdf --melanin 1,2,3 --compare", "wisp: --melanin: 3 values given; it takes at most 2\n"},
         }) {
        auto r = runWisp(c.args);
        EXPECT_EQ(r.status, 2) << c.args << "\n" << r.err;
        EXPECT_EQ(r.err, c.line) << c.args;
    }
    EXPECT_FALSE(std::filesystem::exists(dir / "r.png"));
}

// wisp simulate --set global_stiffness=: "is not a number", with no word of the part syntax.
TEST(HostileMessages, APartSettingsBadValueNamesThePartSyntax)
{
    expectUserError(runWisp("simulate --steps 1 --set global_stiffness="),
                    "--set global_stiffness: '' is not a number (a number, or 'part', one part's value by --part "
                    "PART:global=VALUE)");
    expectUserError(runWisp("simulate --steps 1 --set drag=fast"), "by --part PART:drag=VALUE");
}

// wisp render --guides 1 --width 96 --height 64 --set hair_raster=compute: "0 behind the meshes"
// read as if no hair were hidden; the count is of segments skipped whole by the coarse depth.
TEST(HostileMessages, TheRasterLineSaysWhatItsHiddenCountCounts)
{
    TempDir dir;
    auto r =
        runWisp("render --guides 1 --width 96 --height 64 --set hair_raster=compute --out " + quoted(dir / "r.png"));
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_NE(r.out.find(" skipped whole: behind the meshes in every 8 x 8 tile they cross)"), std::string::npos)
        << r.out;
}

// wisp render --reference --spp 2 --width 48 --height 32 --guides 8: the progress bar said 2.4 s
// where the summary said 0.09 s (the bar counted the simulation and the scene's building too).
TEST(HostileMessages, TheReferencesProgressAndSummaryAgreeOnTheTime)
{
    TempDir dir;
    auto r = runWisp("render --reference --spp 2 --width 48 --height 32 --guides 8 --frames 3 --out " +
                     quoted(dir / "r.png"));
    ASSERT_EQ(r.status, 0) << r.err;
    std::smatch bar, summary;
    ASSERT_TRUE(std::regex_search(r.err, bar, std::regex(R"(2/2 samples, ([0-9.]+) s)"))) << r.err;
    ASSERT_TRUE(std::regex_search(r.out, summary, std::regex(R"(at 48x32 in ([0-9.]+) s)"))) << r.out;
    EXPECT_NEAR(std::stod(bar[1].str()), std::stod(summary[1].str()), 0.1) << r.err << r.out;
}

// ---- fitted colliders on meshes that are not heads ---------------------------------------------

namespace {

// OBJ text of a closed UV sphere (radius r, centre (0, cy, 0)), its triangles counter-clockwise seen
// from outside, or clockwise (`insideOut`); or an open cylinder (the side alone).
std::string sphereObj(float r, float cy, bool insideOut)
{
    constexpr int kRings = 12, kSegments = 16;
    std::string obj;
    char line[96];
    for (int i = 0; i <= kRings; ++i)
        for (int j = 0; j < kSegments; ++j) {
            double theta = 3.14159265358979 * i / kRings, phi = 2.0 * 3.14159265358979 * j / kSegments;
            std::snprintf(line, sizeof line, "v %.6f %.6f %.6f\n", r * std::sin(theta) * std::cos(phi),
                          cy + r * std::cos(theta), r * std::sin(theta) * std::sin(phi));
            obj += line;
        }
    auto at = [](int i, int j) { return i * kSegments + (j % kSegments) + 1; };
    for (int i = 0; i < kRings; ++i)
        for (int j = 0; j < kSegments; ++j) {
            int a = at(i, j), b = at(i, j + 1), c = at(i + 1, j + 1), d = at(i + 1, j);
            // (a, b, c): theta grows downward, phi from +x toward +z; (b - a) x (c - a) points out.
            if (insideOut)
                std::snprintf(line, sizeof line, "f %d %d %d\nf %d %d %d\n", a, c, b, a, d, c);
            else
                std::snprintf(line, sizeof line, "f %d %d %d\nf %d %d %d\n", a, b, c, a, c, d);
            obj += line;
        }
    return obj;
}

// A cube of 8 corners (side 0.2, its base at y = 0), each face two triangles counter-clockwise seen
// from outside.
const char* const kCubeObj = "v -0.1 0 -0.1\nv 0.1 0 -0.1\nv 0.1 0 0.1\nv -0.1 0 0.1\n"
                             "v -0.1 0.2 -0.1\nv 0.1 0.2 -0.1\nv 0.1 0.2 0.1\nv -0.1 0.2 0.1\n"
                             "f 1 2 3\nf 1 3 4\nf 5 8 7\nf 5 7 6\nf 1 5 6\nf 1 6 2\n"
                             "f 2 6 7\nf 2 7 3\nf 3 7 8\nf 3 8 4\nf 4 8 5\nf 4 5 1\n";

std::string cylinderObj(float r, float height)
{
    constexpr int kSegments = 24, kRows = 8;
    std::string obj;
    char line[96];
    for (int i = 0; i <= kRows; ++i)
        for (int j = 0; j < kSegments; ++j) {
            double phi = 2.0 * 3.14159265358979 * j / kSegments;
            std::snprintf(line, sizeof line, "v %.6f %.6f %.6f\n", r * std::cos(phi),
                          height * (1.0 - double(i) / kRows), r * std::sin(phi));
            obj += line;
        }
    auto at = [](int i, int j) { return i * kSegments + (j % kSegments) + 1; };
    for (int i = 0; i < kRows; ++i)
        for (int j = 0; j < kSegments; ++j) {
            std::snprintf(line, sizeof line, "f %d %d %d\nf %d %d %d\n", at(i, j), at(i, j + 1), at(i + 1, j + 1),
                          at(i, j), at(i + 1, j + 1), at(i + 1, j));
            obj += line;
        }
    return obj;
}

} // namespace

// wisp simulate --steps 1 --guides 20 --head cylinder.obj (open), --head inside-out.obj and
// --head cube.obj: colliders fitted to them were accepted silently. Each now gets one warning line
// naming the mesh and what is wrong (the cube's fitted cranium, pulled under its top face, leaves
// most of its scalp far outside it, where hair sinks into the cube); the project's head as a bare
// mesh (its colliders fitted too) and a closed sphere get none.
TEST(HostileHeads, MeshesThatAreNotHeadsAreSaidToBe)
{
    TempDir dir;
    writeFile(dir / "cylinder.obj", cylinderObj(0.08f, 0.25f));
    writeFile(dir / "inside-out.obj", sphereObj(0.1f, 0.1f, true));
    writeFile(dir / "sphere.obj", sphereObj(0.1f, 0.1f, false));
    writeFile(dir / "cube.obj", kCubeObj);
    struct Case {
        std::string mesh, says;
    };
    for (const Case& c : std::vector<Case>{
             {"cylinder.obj", "the mesh is open on the upper half of its head"},
             {"inside-out.obj", "the mesh is inside-out (its signed volume is"},
             {"cube.obj", "the colliders fitted to it hold its scalp badly, as they do a mesh that is no head: "}}) {
        for (const std::string& command :
             {"groom --guides 20 --out " + quoted(dir / "g.tfx"), std::string("simulate --steps 1 --guides 20")}) {
            auto r = runWisp(command + " --head " + quoted(dir / c.mesh));
            std::string warning = "wisp: warning: " + (dir / c.mesh).string() + ": ";
            EXPECT_EQ(r.status, 0) << c.mesh << "\n" << r.err;
            EXPECT_NE(r.err.find(warning), std::string::npos) << c.mesh << "\n" << r.err;
            EXPECT_NE(r.err.find(c.says), std::string::npos) << c.mesh << "\n" << r.err;
            // One line for the mesh, whatever is wrong with it.
            size_t first = r.err.find(warning);
            EXPECT_EQ(r.err.find(warning, first + 1), std::string::npos) << c.mesh << "\n" << r.err;
        }
    }
    for (const std::filesystem::path& head :
         {dir / "sphere.obj", std::filesystem::path(WISP_SOURCE_DIR) / "models" / "head.obj"}) {
        auto r = runWisp("groom --guides 20 --head " + quoted(head) + " --out " + quoted(dir / "g.tfx"));
        EXPECT_EQ(r.status, 0) << head << "\n" << r.err;
        EXPECT_EQ(r.err.find("warning"), std::string::npos) << head << "\n" << r.err;
    }
}

// What the cube's warning says happens: wisp simulate --json --steps 60 --guides 200 --head cube.obj
// leaves hair far inside the cube (deepest 12% of its diagonal on lavapipe: its scalp lies far
// outside the fitted colliders), where the project's head as a bare mesh keeps it near its surface
// (1.2%).
TEST(HostileHeads, HairSinksIntoTheCubeItsWarningNames)
{
    TempDir dir;
    writeFile(dir / "cube.obj", kCubeObj);
    auto deepest = [](const std::filesystem::path& head) {
        auto r = runWisp("simulate --json --steps 60 --guides 200 --head " + quoted(head));
        EXPECT_EQ(r.status, 0) << head << "\n" << r.err;
        return nlohmann::json::parse(r.out)["inside_mesh"]["final"]["deepest"].get<double>();
    };
    EXPECT_GT(deepest(dir / "cube.obj"), 0.06);
    EXPECT_LT(deepest(std::filesystem::path(WISP_SOURCE_DIR) / "models" / "head.obj"), 0.03);
}

// Real heads given as bare meshes, their colliders fitted (Sintel's and Sintel Lite's busts, open at
// the neck with a few stray edges; the TressFX sample's), are said nothing of.
TEST(HostileHeads, RealHeadsWithFittedCollidersAreNotWarnedAbout)
{
    WISP_REQUIRE_DATA(sintel, "sintel/sintel.obj");
    WISP_REQUIRE_DATA(lite, "sintel-lite/sintel_lite.obj");
    WISP_REQUIRE_DATA(tressfx, "tressfx-text/head_max4.obj");
    TempDir dir;
    for (const std::filesystem::path& head : {sintel, lite, tressfx}) {
        auto r = runWisp("groom --guides 20 --head " + quoted(head) + " --out " + quoted(dir / "g.tfx"));
        EXPECT_EQ(r.status, 0) << head << "\n" << r.err;
        EXPECT_EQ(r.err.find("warning"), std::string::npos) << head << "\n" << r.err;
    }
}
