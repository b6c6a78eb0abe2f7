// tests/test_hair_writer.cpp: the groom writers (assets/hair_writer.h) against Wisp's own readers:
// a small groom written as cyHair and TressFX 4 comes back the same strands (counts, positions,
// pinned vertices, the right way up); a grown groom written and loaded on its head is placed as in
// the file, strand for strand; every refused input names what is wrong and leaves no file behind.
#include "assets/hair_asset.h"
#include "assets/hair_writer.h"
#include "core/error.h"
#include "physics/groomed_head.h"
#include "test_support.h"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstring>
#include <limits>

using namespace wisp;
using wisp::test::readFile;
using wisp::test::TempDir;

namespace {

// Three strands of 5 points in head space (y up), not symmetric in any axis, so a wrong turn or
// mirror shows; strand 1 has 2 pinned root vertices, strand 2 a pinned tip.
GroomToWrite smallGroom()
{
    GroomToWrite g;
    for (uint32_t s = 0; s < 3; ++s) {
        HairStrand strand;
        for (uint32_t v = 0; v < 5; ++v)
            strand.points.push_back({0.01f * float(s) + 0.002f * float(v), 0.2f - 0.03f * float(v),
                                     -0.05f - 0.011f * float(v) + 0.004f * float(s)});
        strand.pinnedRoot = s == 1 ? 2 : 1;
        strand.pinnedTip = s == 2;
        g.strands.push_back(strand);
    }
    g.thickness = 7e-5f;
    g.info = "test groom";
    return g;
}

// The loaded asset's points as Wisp places them by default (cyHair's z-up turned y-up).
std::vector<glm::vec3> placedPoints(const HairAsset& asset, size_t s)
{
    HairPlacement placement;
    placement.zUpToYUp = asset.zUp;
    placement.mirrorZ = asset.mirroredZ;
    std::vector<glm::vec3> out;
    for (const glm::vec3& p : asset.strands[s].points)
        out.push_back(applyPlacement(placement, p));
    return out;
}

void expectSameStrands(const GroomToWrite& written, const HairAsset& read, float tolerance)
{
    ASSERT_EQ(read.strands.size(), written.strands.size());
    for (size_t s = 0; s < written.strands.size(); ++s) {
        std::vector<glm::vec3> got = placedPoints(read, s);
        ASSERT_EQ(got.size(), written.strands[s].points.size()) << "strand " << s;
        for (size_t v = 0; v < got.size(); ++v)
            for (int c = 0; c < 3; ++c)
                EXPECT_NEAR(got[v][c], written.strands[s].points[v][c], tolerance)
                    << "strand " << s << " point " << v << " axis " << c;
    }
}

float f32At(const std::string& bytes, size_t at)
{
    uint32_t u = 0;
    std::memcpy(&u, bytes.data() + at, 4);
    return std::bit_cast<float>(u);
}

} // namespace

TEST(HairWriter, FormatComesFromTheExtension)
{
    EXPECT_EQ(hairFormatForOutput("a/b.hair"), HairFormat::CyHair);
    EXPECT_EQ(hairFormatForOutput("b.HAIR"), HairFormat::CyHair);
    EXPECT_EQ(hairFormatForOutput("b.tfx"), HairFormat::Tfx4);
    for (const char* bad : {"b.obj", "b", "b.hair.png"}) {
        try {
            hairFormatForOutput(bad);
            ADD_FAILURE() << bad << " was accepted";
        } catch (const UserError& e) {
            EXPECT_NE(std::string(e.what()).find(bad), std::string::npos) << e.what();
            EXPECT_NE(std::string(e.what()).find(".hair (cyHair) or .tfx (TressFX 4)"), std::string::npos) << e.what();
        }
    }
}

TEST(HairWriter, CyHairRoundTripsTheRightWayUp)
{
    TempDir dir;
    GroomToWrite g = smallGroom();
    writeHairFile(dir / "g.hair", g);
    HairAsset read = loadHairAsset(dir / "g.hair");
    EXPECT_EQ(read.format, HairFormat::CyHair);
    EXPECT_TRUE(read.zUp);
    expectSameStrands(g, read, 1e-7f);
    // Stored z-up: the file's z is Wisp's y (the root is the highest point of each strand).
    EXPECT_FLOAT_EQ(read.strands[0].points[0].z, g.strands[0].points[0].y);
    EXPECT_FLOAT_EQ(read.strands[0].points[0].y, -g.strands[0].points[0].z);
    // Every strand has 5 points: no segments array, d_segments 4; the thickness and info kept.
    std::string bytes = readFile(dir / "g.hair");
    ASSERT_EQ(bytes.size(), 128u + 12u * 15u);
    EXPECT_EQ(bytes[12], char(2)); // arrays: points only
    EXPECT_EQ(bytes[16], char(4)); // d_segments
    EXPECT_FLOAT_EQ(f32At(bytes, 20), 7e-5f);
    EXPECT_EQ(std::string(bytes.data() + 40), "test groom");
}

TEST(HairWriter, CyHairWritesASegmentsArrayForStrandsOfDifferentLengths)
{
    TempDir dir;
    GroomToWrite g = smallGroom();
    g.strands[1].points.resize(3);
    writeHairFile(dir / "g.hair", g);
    std::string bytes = readFile(dir / "g.hair");
    EXPECT_EQ(bytes[12], char(3)); // segments and points
    ASSERT_EQ(bytes.size(), 128u + 2u * 3u + 12u * 13u);
    expectSameStrands(g, loadHairAsset(dir / "g.hair"), 1e-7f);
}

TEST(HairWriter, TressFx4RoundTripsPositionsAndPinnedRoots)
{
    TempDir dir;
    GroomToWrite g = smallGroom();
    writeHairFile(dir / "g.tfx", g);
    HairAsset read = loadHairAsset(dir / "g.tfx");
    EXPECT_EQ(read.format, HairFormat::Tfx4);
    EXPECT_FALSE(read.zUp);
    EXPECT_FALSE(read.mirroredZ);
    expectSameStrands(g, read, 0.0f); // y-up floats, stored as they are
    EXPECT_EQ(read.strands[0].pinnedRoot, 1u);
    EXPECT_EQ(read.strands[1].pinnedRoot, 2u);
    EXPECT_EQ(read.strands[2].pinnedRoot, 1u);
    // The pinned tip is an inverse mass of 0 on the last vertex (TressFX reads it; Wisp's reader
    // takes only the leading run as pinned roots).
    std::string bytes = readFile(dir / "g.tfx");
    ASSERT_EQ(bytes.size(), 160u + 16u * 15u);
    auto w = [&](size_t s, size_t v) { return f32At(bytes, 160 + 16 * (5 * s + v) + 12); };
    EXPECT_EQ(w(0, 0), 0.0f);
    EXPECT_EQ(w(0, 1), 1.0f);
    EXPECT_EQ(w(1, 1), 0.0f);
    EXPECT_EQ(w(2, 4), 0.0f);
    EXPECT_EQ(w(0, 4), 1.0f);
}

TEST(HairWriter, AGrownGroomLoadsBackOnItsHeadAsInTheFile)
{
    GrowthSettings growth;
    growth.guides = 24;
    growth.verticesPerStrand = 8;
    GroomedHead grown = buildGrownHead(defaultHeadPath(), growth);
    GroomToWrite g;
    for (size_t s = 0; s < grown.strands.strandCount(); ++s) {
        HairStrand strand;
        strand.points.assign(grown.strands.rest.begin() + std::ptrdiff_t(8 * s),
                             grown.strands.rest.begin() + std::ptrdiff_t(8 * s + 8));
        strand.pinnedRoot = grown.strands.strands[s].pinnedRoot;
        g.strands.push_back(strand);
    }
    TempDir dir;
    for (const char* name : {"grown.hair", "grown.tfx"}) {
        writeHairFile(dir / name, g);
        GroomedHead loaded = buildLoadedHead(defaultHeadPath(), {{.file = dir / name}}, 8);
        ASSERT_TRUE(loaded.placement.has_value());
        EXPECT_EQ(loaded.placement->method, GroomPlacement::Method::File) << name;
        EXPECT_FLOAT_EQ(loaded.placement->placement.scale, 1.0f) << name;
        ASSERT_EQ(loaded.strands.strandCount(), grown.strands.strandCount()) << name;
        ASSERT_EQ(loaded.strands.rest.size(), grown.strands.rest.size()) << name;
        // Strands of the vertex count asked for keep their points (a resample by arc length moved
        // them by up to 2 mm here): the written points, within float rounding (metres).
        float worst = 0.0f;
        for (size_t s = 0; s < g.strands.size(); ++s) {
            const std::vector<glm::vec3>& expected = g.strands[s].points;
            for (size_t v = 0; v < 8; ++v)
                worst = std::max(worst, glm::length(loaded.strands.rest[8 * s + v] - expected[v]));
        }
        EXPECT_LT(worst, 1e-6f) << name;
        // TressFX keeps the pinned vertices (w = 0); cyHair has no field for them, so its strands load
        // with the root alone pinned (or rigid when too short to simulate, as the loader decides).
        bool tfx = std::string(name).ends_with(".tfx");
        for (size_t s = 0; s < grown.strands.strandCount(); ++s)
            if (tfx)
                EXPECT_EQ(loaded.strands.strands[s].pinnedRoot, grown.strands.strands[s].pinnedRoot) << name;
            else
                EXPECT_LE(loaded.strands.strands[s].pinnedRoot, grown.strands.strands[s].pinnedRoot) << name;
    }
}

TEST(HairWriter, RefusesWhatItCannotWriteAndLeavesNothingBehind)
{
    TempDir dir;
    struct Case {
        const char* name;
        std::function<void(GroomToWrite&)> spoil;
        const char* file;
        const char* mention;
    };
    float nan = std::numeric_limits<float>::quiet_NaN();
    std::vector<Case> cases = {
        {"no strands", [](GroomToWrite& g) { g.strands.clear(); }, "g.hair", "the groom has no strands"},
        {"one point", [](GroomToWrite& g) { g.strands[2].points.resize(1); }, "g.tfx", "strand 2 has 1 point(s)"},
        {"not finite", [&](GroomToWrite& g) { g.strands[1].points[3].y = nan; }, "g.hair",
         "point 3 of strand 1 is not finite"},
        {"uneven tfx4", [](GroomToWrite& g) { g.strands[1].points.resize(4); }, "g.tfx",
         "strand 1 has 4 points but strand 0 has 5"},
        {"unknown extension", [](GroomToWrite&) {}, "g.obj", "unknown groom format '.obj'"},
        {"no folder", [](GroomToWrite&) {}, "missing/g.hair", "cannot write"},
    };
    for (const Case& c : cases) {
        GroomToWrite g = smallGroom();
        c.spoil(g);
        try {
            writeHairFile(dir / c.file, g);
            ADD_FAILURE() << c.name << ": written";
        } catch (const UserError& e) {
            EXPECT_NE(std::string(e.what()).find(c.mention), std::string::npos) << c.name << ": " << e.what();
        }
        EXPECT_TRUE(std::filesystem::is_empty(dir.path())) << c.name;
    }
}
