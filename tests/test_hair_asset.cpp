// tests/test_hair_asset.cpp: hair loaders against the real TressFX files in ../shared/data and
// small TressFX 3 / cyHair / tfx2 files built here per FORMATS.md; every broken-file path with
// its byte offset or line; strand resampling, automatic placement and the inspect JSON.
#include "assets/hair_asset.h"
#include "assets/mesh.h"
#include "core/error.h"
#include "test_support.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <limits>

using namespace wisp;
using wisp::test::TempDir;
using wisp::test::writeFile;

namespace {

// Little-endian bytes for building binary files in memory.
struct Bytes {
    std::string data;

    Bytes& u32(uint32_t v)
    {
        for (int k = 0; k < 4; ++k)
            data.push_back(static_cast<char>((v >> (8 * k)) & 0xffu));
        return *this;
    }
    Bytes& u16(uint16_t v)
    {
        data.push_back(static_cast<char>(v & 0xffu));
        data.push_back(static_cast<char>(v >> 8));
        return *this;
    }
    Bytes& f32(float v) { return u32(std::bit_cast<uint32_t>(v)); }
    Bytes& vec(glm::vec3 p) { return f32(p.x).f32(p.y).f32(p.z); }
    Bytes& zeros(size_t n)
    {
        data.append(n, '\0');
        return *this;
    }
    Bytes& text(const std::string& s)
    {
        data += s;
        return *this;
    }
};

// The point `v` of strand `s` in the small synthetic assets: distinct, exactly representable.
glm::vec3 pointOf(uint32_t s, uint32_t v)
{
    return {0.5f * static_cast<float>(s), 1.0f + 0.25f * static_cast<float>(v), -0.125f * static_cast<float>(s + v)};
}

// TressFX 3: 296-byte header, vertices at 296.
Bytes tfx3File(uint32_t strands, uint32_t perStrand, uint32_t bothEnds = 0)
{
    Bytes b;
    b.f32(3.0f).u32(strands).u32(perStrand).u32(4).u32(bothEnds).zeros(31 * 4);
    b.u32(296).zeros(5 * 4).zeros(32 * 4);
    for (uint32_t s = 0; s < strands; ++s)
        for (uint32_t v = 0; v < perStrand; ++v)
            b.vec(pointOf(s, v));
    return b;
}

// TressFX 4: 160-byte header, xyzw at 160; strand s pins its first `pinned[s]` vertices (w = 0).
Bytes tfx4File(uint32_t strands, uint32_t perStrand, const std::vector<uint32_t>& pinned = {})
{
    Bytes b;
    b.f32(4.0f).u32(strands).u32(perStrand).u32(160).zeros(4 * 4).zeros(32 * 4);
    for (uint32_t s = 0; s < strands; ++s)
        for (uint32_t v = 0; v < perStrand; ++v)
            b.vec(pointOf(s, v)).f32(v < (s < pinned.size() ? pinned[s] : 1u) ? 0.0f : 1.0f);
    return b;
}

// cyHair with strands of `segments[i] + 1` points; with `segmentsArray` false all strands share
// d_segments = segments[0]. `extraArrays` adds thickness (bit 2) and colors (bit 4).
Bytes cyHairFile(const std::vector<uint16_t>& segments, bool segmentsArray, bool extraArrays = false)
{
    uint32_t points = 0;
    for (uint16_t s : segments)
        points += s + 1u;
    uint32_t arrays = (segmentsArray ? 1u : 0u) | 2u | (extraArrays ? (4u | 16u) : 0u);
    Bytes b;
    b.text("HAIR").u32(static_cast<uint32_t>(segments.size())).u32(points).u32(arrays).u32(segments.front());
    b.f32(0.01f).f32(1.0f).f32(0.5f).f32(0.4f).f32(0.3f).zeros(88);
    if (segmentsArray)
        for (uint16_t s : segments)
            b.u16(s);
    for (uint32_t s = 0; s < segments.size(); ++s)
        for (uint32_t v = 0; v <= segments[s]; ++v)
            b.vec(pointOf(s, v));
    if (extraArrays) {
        for (uint32_t k = 0; k < points; ++k)
            b.f32(0.02f);
        for (uint32_t k = 0; k < points; ++k)
            b.vec({0.1f, 0.2f, 0.3f});
    }
    return b;
}

std::string tfx2Text(const std::string& header, uint32_t strands, uint32_t perStrand)
{
    std::string t = header;
    for (uint32_t s = 0; s < strands; ++s) {
        t += "strand " + std::to_string(s) + " numVerts " + std::to_string(perStrand) + " texcoord 0.000000 000000\n";
        for (uint32_t v = 0; v < perStrand; ++v) {
            glm::vec3 p = pointOf(s, v);
            t += std::to_string(p.x) + " " + std::to_string(p.y) + " " + std::to_string(p.z) + "\n";
        }
    }
    return t;
}

void expectExactPoints(const HairAsset& asset, const std::vector<uint32_t>& counts)
{
    ASSERT_EQ(asset.strands.size(), counts.size());
    for (uint32_t s = 0; s < counts.size(); ++s) {
        ASSERT_EQ(asset.strands[s].points.size(), counts[s]) << "strand " << s;
        for (uint32_t v = 0; v < counts[s]; ++v)
            ASSERT_EQ(asset.strands[s].points[v], pointOf(s, v)) << "strand " << s << " point " << v;
    }
}

std::string errorOf(const std::filesystem::path& path)
{
    try {
        loadHairAsset(path);
    } catch (const UserError& e) {
        return e.what();
    }
    return "";
}

// The error names the file and, for binary files, "byte N".
void expectBinaryError(const std::filesystem::path& path, const std::string& offset, const std::string& words = "")
{
    std::string e = errorOf(path);
    EXPECT_NE(e.find(path.string()), std::string::npos) << e;
    EXPECT_NE(e.find("byte " + offset + ":"), std::string::npos) << e;
    if (!words.empty()) {
        EXPECT_NE(e.find(words), std::string::npos) << e;
    }
}

void expectTextError(const std::filesystem::path& path, int line, const std::string& words = "")
{
    std::string e = errorOf(path);
    EXPECT_NE(e.find(path.string() + ":" + std::to_string(line) + ":"), std::string::npos) << e;
    if (!words.empty()) {
        EXPECT_NE(e.find(words), std::string::npos) << e;
    }
}

float median(std::vector<float> v)
{
    std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2), v.end());
    return v[v.size() / 2];
}

// Arc-length position of `p` on the polyline (p must lie on it).
float arcPosition(const std::vector<glm::vec3>& line, glm::vec3 p)
{
    float best = std::numeric_limits<float>::max(), at = 0.0f, walked = 0.0f;
    for (size_t k = 1; k < line.size(); ++k) {
        glm::vec3 d = line[k] - line[k - 1];
        float len = glm::length(d);
        if (len == 0.0f)
            continue;
        float t = std::clamp(glm::dot(p - line[k - 1], d) / (len * len), 0.0f, 1.0f);
        float off = glm::length(line[k - 1] + t * d - p);
        if (off < best) {
            best = off;
            at = walked + t * len;
        }
        walked += len;
    }
    EXPECT_LT(best, 1e-5f) << "the resampled point is off the polyline";
    return at;
}

} // namespace

// ---- real files ---------------------------------------------------------------------------------

TEST(HairAsset, LoadsSintelTfx4)
{
    WISP_REQUIRE_DATA(path, "sintel/sintel_hair_11400x16.tfx");
    HairAsset hair = loadHairAsset(path);
    EXPECT_EQ(hair.format, HairFormat::Tfx4);
    EXPECT_EQ(hair.source, path);
    EXPECT_EQ(hair.strands.size(), 11400u);
    EXPECT_EQ(hair.totalVertices(), 11400u * 16u);
    EXPECT_EQ(hair.minVertices(), 16u);
    EXPECT_EQ(hair.maxVertices(), 16u);
    EXPECT_FALSE(hair.zUp);
    EXPECT_FALSE(hair.mirroredZ);
    for (const HairStrand& s : hair.strands) {
        ASSERT_EQ(s.pinnedRoot, 1u); // this groom pins only vertex 0
        ASSERT_FALSE(s.pinnedTip);
    }
    Bounds b = hair.bounds();
    EXPECT_LT(b.diagonal(), 2.0f); // metres
    EXPECT_GT(b.diagonal(), 0.1f);
    EXPECT_GT(b.min.y, 1.0f); // a standing figure's head, y up
}

TEST(HairAsset, SintelRootsLieOnTheBust)
{
    WISP_REQUIRE_DATA(hairPath, "sintel/sintel_hair_11400x16.tfx");
    WISP_REQUIRE_DATA(meshPath, "sintel/sintel.obj");
    HairAsset hair = loadHairAsset(hairPath);
    Mesh mesh = loadMesh(meshPath);
    std::vector<float> distances;
    distances.reserve(hair.strands.size());
    for (const HairStrand& s : hair.strands) {
        float best = std::numeric_limits<float>::max();
        for (const glm::vec3& p : mesh.positions)
            best = std::min(best, glm::length(p - s.points.front()));
        distances.push_back(best);
    }
    EXPECT_LT(median(distances), 0.01f); // 1 cm: same units, same frame, no placement needed
    HairPlacement placement = autoPlacement(hair, mesh.bounds());
    EXPECT_EQ(placement.scale, 1.0f);
    EXPECT_FALSE(placement.zUpToYUp);
    EXPECT_FALSE(placement.mirrorZ);
}

TEST(HairAsset, LoadsSintelLiteTfx4InBlenderUnits)
{
    WISP_REQUIRE_DATA(path, "sintel-lite/sintel_hair_228x32.tfx");
    WISP_REQUIRE_DATA(meshPath, "sintel-lite/sintel_lite.obj");
    HairAsset hair = loadHairAsset(path);
    EXPECT_EQ(hair.format, HairFormat::Tfx4);
    EXPECT_EQ(hair.strands.size(), 228u);
    EXPECT_EQ(hair.totalVertices(), 228u * 32u);
    EXPECT_EQ(hair.minVertices(), 32u);
    EXPECT_EQ(hair.maxVertices(), 32u);
    for (const HairStrand& s : hair.strands)
        ASSERT_EQ(s.pinnedRoot, 1u);
    float diagonal = hair.bounds().diagonal();
    EXPECT_GT(diagonal, 10.0f); // Blender units: a head about 40 wide
    EXPECT_LT(diagonal, 200.0f);
    EXPECT_EQ(autoPlacement(hair, loadMesh(meshPath).bounds()).scale, 1.0f);
}

TEST(HairAsset, LoadsTressFx2TextInCentimetres)
{
    WISP_REQUIRE_DATA(front, "tressfx-text/hair_front_16_guide.tfx");
    WISP_REQUIRE_DATA(tail, "tressfx-text/hair_tail_16_guide.tfx");
    HairAsset f = loadHairAsset(front);
    HairAsset t = loadHairAsset(tail);
    EXPECT_EQ(f.format, HairFormat::Tfx2);
    EXPECT_EQ(f.strands.size(), 93u);
    EXPECT_EQ(f.totalVertices(), 93u * 16u);
    EXPECT_EQ(t.strands.size(), 474u);
    EXPECT_EQ(t.totalVertices(), 474u * 16u);
    EXPECT_EQ(t.minVertices(), 16u);
    EXPECT_EQ(t.maxVertices(), 16u);
    // The first point of the front file, as written.
    EXPECT_EQ(f.strands[0].points[0], glm::vec3(-2.28788f, 107.007f, 23.5948f));
    EXPECT_FALSE(f.strands[0].pinnedTip); // bothEndsImmovable 0
    for (const HairAsset* h : {&f, &t}) {
        float diagonal = h->bounds().diagonal();
        EXPECT_GT(diagonal, 10.0f); // centimetres
        EXPECT_LT(diagonal, 500.0f);
    }
}

TEST(HairAsset, TressFx2OnTheirHeadAndOnSintel)
{
    WISP_REQUIRE_DATA(tail, "tressfx-text/hair_tail_16_guide.tfx");
    WISP_REQUIRE_DATA(head, "tressfx-text/head_max4.obj");
    WISP_REQUIRE_DATA(sintel, "sintel/sintel.obj");
    HairAsset hair = loadHairAsset(tail);
    EXPECT_EQ(autoPlacement(hair, loadMesh(head).bounds()).scale, 1.0f);          // both centimetres
    EXPECT_FLOAT_EQ(autoPlacement(hair, loadMesh(sintel).bounds()).scale, 0.01f); // centimetres on metres
}

// ---- files built here ---------------------------------------------------------------------------

TEST(HairAsset, LoadsTfx3Exactly)
{
    TempDir dir;
    writeFile(dir / "small.tfx", tfx3File(3, 4, 1).data);
    HairAsset hair = loadHairAsset(dir / "small.tfx");
    EXPECT_EQ(hair.format, HairFormat::Tfx3);
    EXPECT_TRUE(hair.mirroredZ);
    EXPECT_FALSE(hair.zUp);
    expectExactPoints(hair, {4, 4, 4});
    for (const HairStrand& s : hair.strands) {
        EXPECT_EQ(s.pinnedRoot, 1u);
        EXPECT_TRUE(s.pinnedTip); // bothEndsImmovable 1
    }
    HairPlacement p = autoPlacement(hair, hair.bounds());
    EXPECT_TRUE(p.mirrorZ);
    EXPECT_FALSE(p.zUpToYUp);
}

TEST(HairAsset, LoadsTfx4PinnedCounts)
{
    TempDir dir;
    writeFile(dir / "pins.tfx", tfx4File(3, 5, {1, 2, 0}).data);
    HairAsset hair = loadHairAsset(dir / "pins.tfx");
    EXPECT_EQ(hair.format, HairFormat::Tfx4);
    expectExactPoints(hair, {5, 5, 5});
    EXPECT_EQ(hair.strands[0].pinnedRoot, 1u);
    EXPECT_EQ(hair.strands[1].pinnedRoot, 2u); // vertices 0 and 1 have w = 0
    EXPECT_EQ(hair.strands[2].pinnedRoot, 1u); // no w = 0 at all: the root is still pinned
}

TEST(HairAsset, LoadsCyHairWithSegmentsArray)
{
    TempDir dir;
    writeFile(dir / "small.hair", cyHairFile({3, 1, 6}, true, true).data);
    HairAsset hair = loadHairAsset(dir / "small.hair");
    EXPECT_EQ(hair.format, HairFormat::CyHair);
    EXPECT_TRUE(hair.zUp);
    EXPECT_FALSE(hair.mirroredZ);
    expectExactPoints(hair, {4, 2, 7});
    EXPECT_EQ(hair.totalVertices(), 13u);
    EXPECT_EQ(hair.minVertices(), 2u);
    EXPECT_EQ(hair.maxVertices(), 7u);
    HairPlacement p = autoPlacement(hair, hair.bounds());
    EXPECT_TRUE(p.zUpToYUp);
    EXPECT_FALSE(p.mirrorZ);
}

TEST(HairAsset, LoadsCyHairWithDefaultSegments)
{
    TempDir dir;
    writeFile(dir / "even.hair", cyHairFile({5, 5}, false).data);
    HairAsset hair = loadHairAsset(dir / "even.hair");
    expectExactPoints(hair, {6, 6});
}

TEST(HairAsset, TellsFormatsByContentNotName)
{
    TempDir dir;
    writeFile(dir / "a.hair", tfx4File(1, 4).data);
    writeFile(dir / "b.tfx", cyHairFile({2}, true).data);
    writeFile(dir / "c.bin", tfx3File(1, 4).data);
    writeFile(dir / "d.hair", tfx2Text("numStrands 1\n", 1, 3));
    EXPECT_EQ(loadHairAsset(dir / "a.hair").format, HairFormat::Tfx4);
    EXPECT_EQ(loadHairAsset(dir / "b.tfx").format, HairFormat::CyHair);
    EXPECT_EQ(loadHairAsset(dir / "c.bin").format, HairFormat::Tfx3);
    EXPECT_EQ(loadHairAsset(dir / "d.hair").format, HairFormat::Tfx2);
    EXPECT_STREQ(formatName(HairFormat::Tfx2), "tfx2");
    EXPECT_STREQ(formatName(HairFormat::Tfx3), "tfx3");
    EXPECT_STREQ(formatName(HairFormat::Tfx4), "tfx4");
    EXPECT_STREQ(formatName(HairFormat::CyHair), "cyhair");
}

TEST(HairAsset, Tfx2HeaderInAnyOrderWithQuirks)
{
    TempDir dir;
    // numStrands first, keys reordered, an unknown key, CRLF, blank lines, mixed numVerts,
    // the exporter's "texcoord u 000000" and a strand line without texcoords.
    writeFile(dir / "any.tfx", "numStrands 2\r\nis sorted 1\r\nmaxRadiusAroundGuideHair 0.5\r\nversion 2.0\r\n"
                               "exporterNote whatever\r\n\r\nstrand 0 numVerts 3 texcoord 0.25 000000\r\n"
                               "1 2 3\r\n4 5 6\r\n7 8 9\r\n\r\nstrand 1 numVerts 2\r\n-1 -2 -3\r\n1e-3 +2.5 0\r\n");
    HairAsset hair = loadHairAsset(dir / "any.tfx");
    ASSERT_EQ(hair.strands.size(), 2u);
    ASSERT_EQ(hair.strands[0].points.size(), 3u);
    ASSERT_EQ(hair.strands[1].points.size(), 2u);
    EXPECT_EQ(hair.strands[0].points[2], glm::vec3(7, 8, 9));
    EXPECT_EQ(hair.strands[1].points[1], glm::vec3(1e-3f, 2.5f, 0.0f));
    EXPECT_EQ(hair.minVertices(), 2u);
    EXPECT_EQ(hair.maxVertices(), 3u);
}

TEST(HairAsset, Tfx2AppliesScaleRotationTranslation)
{
    TempDir dir;
    std::string body = "numStrands 1\nstrand 0 numVerts 2 texcoord 0 000000\n1 0 0\n0 1 0\n";
    writeFile(dir / "scaled.tfx", "scale 2.0\ntranslation 10 20 30\n" + body);
    HairAsset scaled = loadHairAsset(dir / "scaled.tfx");
    EXPECT_EQ(scaled.strands[0].points[0], glm::vec3(12, 20, 30));
    EXPECT_EQ(scaled.strands[0].points[1], glm::vec3(10, 22, 30));

    // 90 degrees about z: x -> y, y -> -x; then the translation.
    writeFile(dir / "rotated.tfx", "rotation 0 0 90\ntranslation 0 0 1\n" + body);
    HairAsset rotated = loadHairAsset(dir / "rotated.tfx");
    glm::vec3 a = rotated.strands[0].points[0], b = rotated.strands[0].points[1];
    EXPECT_NEAR(a.x, 0.0f, 1e-6f);
    EXPECT_NEAR(a.y, 1.0f, 1e-6f);
    EXPECT_NEAR(a.z, 1.0f, 1e-6f);
    EXPECT_NEAR(b.x, -1.0f, 1e-6f);
    EXPECT_NEAR(b.y, 0.0f, 1e-6f);
}

TEST(HairAsset, Tfx2BothEndsImmovablePinsTheTip)
{
    TempDir dir;
    writeFile(dir / "both.tfx", tfx2Text("bothEndsImmovable 1\nnumStrands 2\n", 2, 4));
    HairAsset hair = loadHairAsset(dir / "both.tfx");
    for (const HairStrand& s : hair.strands) {
        EXPECT_TRUE(s.pinnedTip);
        EXPECT_EQ(s.pinnedRoot, 1u);
    }
}

// ---- broken files -------------------------------------------------------------------------------

TEST(HairErrors, MissingAndEmptyFiles)
{
    std::string e = errorOf("/nonexistent/hair.tfx");
    EXPECT_NE(e.find("/nonexistent/hair.tfx"), std::string::npos) << e;
    EXPECT_NE(e.find("no such"), std::string::npos) << e;
    TempDir dir;
    writeFile(dir / "empty.tfx", "");
    expectBinaryError(dir / "empty.tfx", "0", "empty");
}

TEST(HairErrors, UnrecognisedFiles)
{
    TempDir dir;
    writeFile(dir / "junk.bin", std::string("\x01\x02\x03\x04\x05\x06\x07\x08", 8));
    expectBinaryError(dir / "junk.bin", "0", "unrecognised hair file");
    writeFile(dir / "words.tfx", "\n\nhello world\n");
    expectTextError(dir / "words.tfx", 3, "unrecognised hair file");
}

TEST(HairErrors, Tfx3Broken)
{
    TempDir dir;
    Bytes good = tfx3File(2, 4);
    writeFile(dir / "short-header.tfx", good.data.substr(0, 100));
    expectBinaryError(dir / "short-header.tfx", "0", "header needs 296");
    writeFile(dir / "truncated.tfx", good.data.substr(0, good.data.size() - 5));
    expectBinaryError(dir / "truncated.tfx", "296",
                      "2*4*12 = 96 bytes from byte 296 to byte 392, but the file ends at byte 387");

    Bytes magic = good;
    magic.data.replace(0, 4, Bytes().f32(3.5f).data);
    writeFile(dir / "magic.tfx", magic.data);
    expectBinaryError(dir / "magic.tfx", "0", "unrecognised");

    writeFile(dir / "past-end.tfx", tfx3File(2, 4).data.replace(4, 4, Bytes().u32(200).data));
    expectBinaryError(dir / "past-end.tfx", "296", "200*4*12");

    Bytes nan = good;
    nan.data.replace(296 + 12 * 5 + 4, 4, Bytes().f32(std::numeric_limits<float>::quiet_NaN()).data);
    writeFile(dir / "nan.tfx", nan.data);
    expectBinaryError(dir / "nan.tfx", std::to_string(296 + 12 * 5), "point 1 of strand 1");

    writeFile(dir / "zero.tfx", tfx3File(0, 4).data);
    expectBinaryError(dir / "zero.tfx", "4", "no strands");

    writeFile(dir / "per-strand.tfx", tfx3File(1, 1).data);
    expectBinaryError(dir / "per-strand.tfx", "8", "2..1024");
    writeFile(dir / "huge.tfx", tfx3File(0, 16).data.replace(4, 4, Bytes().u32(50'000'000).data));
    expectBinaryError(dir / "huge.tfx", "4", "more than");
}

TEST(HairErrors, Tfx4Broken)
{
    TempDir dir;
    Bytes good = tfx4File(2, 4);
    writeFile(dir / "short-header.tfx", good.data.substr(0, 20));
    expectBinaryError(dir / "short-header.tfx", "0", "header needs 160");
    writeFile(dir / "truncated.tfx", good.data.substr(0, good.data.size() - 1));
    expectBinaryError(dir / "truncated.tfx", "160",
                      "2*4*16 = 128 bytes from byte 160 to byte 288, but the file ends at byte 287");

    Bytes magic = good;
    magic.data.replace(0, 4, Bytes().f32(2.0f).data);
    writeFile(dir / "magic.tfx", magic.data);
    expectBinaryError(dir / "magic.tfx", "0", "unrecognised");

    writeFile(dir / "past-end.tfx", tfx4File(2, 4).data.replace(8, 4, Bytes().u32(1000).data));
    expectBinaryError(dir / "past-end.tfx", "160", "2*1000*16");
    Bytes offset = good;
    offset.data.replace(12, 4, Bytes().u32(1u << 30).data);
    writeFile(dir / "offset.tfx", offset.data);
    expectBinaryError(dir / "offset.tfx", std::to_string(1u << 30), "but the file ends at byte");

    Bytes nan = good;
    nan.data.replace(160 + 16 * 6 + 8, 4, Bytes().f32(std::numeric_limits<float>::infinity()).data);
    writeFile(dir / "nan.tfx", nan.data);
    expectBinaryError(dir / "nan.tfx", std::to_string(160 + 16 * 6), "point 2 of strand 1");

    writeFile(dir / "zero.tfx", tfx4File(0, 4).data);
    expectBinaryError(dir / "zero.tfx", "4", "no strands");
    writeFile(dir / "per-strand.tfx", tfx4File(0, 4).data.replace(4, 8, Bytes().u32(1).u32(5000).data));
    expectBinaryError(dir / "per-strand.tfx", "8", "5000");
}

TEST(HairErrors, Tfx4HeaderClaimingMoreStrandsThanItsPositionsHold)
{
    // The header says 3 strands but its strand UVs start where the second strand's positions
    // would: the third "strand" was read from the UV block. Its own offsets say where the
    // positions end.
    TempDir dir;
    Bytes file = tfx4File(2, 4);
    uint32_t uvAt = uint32_t(file.data.size());
    for (int k = 0; k < 2 * 2 * 3 * 4; ++k) // 2 strands' UVs, then padding: 4 x 16 bytes more
        file.f32(0.25f);
    file.data.replace(4, 4, Bytes().u32(3).data);
    file.data.replace(16, 4, Bytes().u32(uvAt).data);
    writeFile(dir / "claims.tfx", file.data);
    expectBinaryError(dir / "claims.tfx", "16", "the positions hold 2 of the 3 strands it claims");
    std::string e = errorOf(dir / "claims.tfx");
    EXPECT_NE(e.find("strand texture coordinates start at byte " + std::to_string(uvAt)), std::string::npos) << e;
    // The same header with its true count loads, the UVs ignored.
    file.data.replace(4, 4, Bytes().u32(2).data);
    writeFile(dir / "true.tfx", file.data);
    EXPECT_EQ(loadHairAsset(dir / "true.tfx").strands.size(), 2u);
}

TEST(HairErrors, Tfx3HeaderClaimingMoreStrandsThanItsPositionsHold)
{
    TempDir dir;
    Bytes file = tfx3File(2, 4);
    uint32_t thicknessAt = uint32_t(file.data.size());
    file.zeros(2 * 4 * 12);
    file.data.replace(4, 4, Bytes().u32(4).data);
    file.data.replace(148, 4, Bytes().u32(thicknessAt).data);
    writeFile(dir / "claims.tfx", file.data);
    expectBinaryError(dir / "claims.tfx", "148", "the positions hold 2 of the 4 strands it claims");
}

TEST(HairErrors, CyHairBroken)
{
    TempDir dir;
    Bytes good = cyHairFile({3, 2}, true, true); // 7 points: 128 + 4 + 84 + 28 + 84 bytes
    writeFile(dir / "short-header.hair", good.data.substr(0, 64));
    expectBinaryError(dir / "short-header.hair", "0", "header needs 128");
    writeFile(dir / "truncated.hair", good.data.substr(0, good.data.size() - 2));
    expectBinaryError(dir / "truncated.hair", std::to_string(128 + 4 + 84 + 28), "colors");
    writeFile(dir / "truncated-points.hair", good.data.substr(0, 150));
    expectBinaryError(dir / "truncated-points.hair", "132", "points array");

    Bytes magic = good;
    magic.data.replace(0, 4, "HIAR");
    writeFile(dir / "magic.hair", magic.data);
    EXPECT_NE(errorOf(dir / "magic.hair").find("unrecognised"), std::string::npos) << errorOf(dir / "magic.hair");
    Bytes binaryMagic = good;
    binaryMagic.data.replace(0, 4, std::string("\0AIR", 4));
    writeFile(dir / "magic2.hair", binaryMagic.data);
    expectBinaryError(dir / "magic2.hair", "0", "unrecognised");

    Bytes past = good; // segments say 4 + 3 points, point_count says 9
    past.data.replace(8, 4, Bytes().u32(9).data);
    writeFile(dir / "past-end.hair", past.data);
    expectBinaryError(dir / "past-end.hair", "128", "point_count");
    Bytes many = cyHairFile({3, 2}, false); // 2 strands of d_segments 3 = 8 points, only 7 written
    many.data.replace(8, 4, Bytes().u32(8).data);
    writeFile(dir / "many.hair", many.data);
    expectBinaryError(dir / "many.hair", "128", "but the file ends at byte");

    Bytes nan = good;
    nan.data.replace(132 + 12 * 4 + 8, 4, Bytes().f32(std::numeric_limits<float>::quiet_NaN()).data);
    writeFile(dir / "nan.hair", nan.data);
    expectBinaryError(dir / "nan.hair", std::to_string(132 + 12 * 4), "point 0 of strand 1");

    Bytes zero = good;
    zero.data.replace(4, 4, Bytes().u32(0).data);
    writeFile(dir / "zero.hair", zero.data);
    expectBinaryError(dir / "zero.hair", "4", "no strands");

    Bytes single = cyHairFile({3, 2}, true);
    single.data.replace(130, 2, Bytes().u16(0).data);
    writeFile(dir / "single.hair", single.data);
    expectBinaryError(dir / "single.hair", "130", "strand 1 has 0 segments");

    Bytes noPoints = good;
    noPoints.data.replace(12, 4, Bytes().u32(1).data);
    writeFile(dir / "no-points.hair", noPoints.data);
    expectBinaryError(dir / "no-points.hair", "12", "no points");

    Bytes huge = good;
    huge.data.replace(8, 4, Bytes().u32(200'000'000).data);
    writeFile(dir / "huge.hair", huge.data);
    expectBinaryError(dir / "huge.hair", "8", "more than");
}

TEST(HairErrors, Tfx2Broken)
{
    TempDir dir;
    std::string header = "version 2.0\nscale 1.0\nnumStrands 2\n"; // strands start on line 4
    std::string good = tfx2Text(header, 2, 3);                     // 4 lines per strand

    writeFile(dir / "truncated.tfx", good.substr(0, good.rfind("strand 1")) + "strand 1 numVerts 3\n1 2 3\n");
    expectTextError(dir / "truncated.tfx", 8, "numVerts 3 but only 1 lines follow");
    writeFile(dir / "cut.tfx", good.substr(0, good.size() - 11)); // the last line cut short
    expectTextError(dir / "cut.tfx", 11, "expected 'x y z'");

    writeFile(dir / "magic.tfx", "versoin 2.0\nnumStrands 1\n");
    expectTextError(dir / "magic.tfx", 1, "unrecognised hair file");
    writeFile(dir / "no-count.tfx", "version 2.0\nscale 1.0\nstrand 0 numVerts 2\n0 0 0\n1 1 1\n");
    expectTextError(dir / "no-count.tfx", 3, "no numStrands");

    writeFile(dir / "past-end.tfx", tfx2Text("version 2.0\nnumStrands 50\n", 2, 3));
    expectTextError(dir / "past-end.tfx", 2, "numStrands 50 needs at least 150 lines");
    // (Blank lines inside, not after: trailing ones are padding, and too few lines are refused up front.)
    std::string fewer = tfx2Text("numStrands 3\n", 2, 3);
    writeFile(dir / "fewer.tfx", fewer.insert(fewer.find('\n', fewer.find("strand 0")) + 1, "\n\n\n\n\n\n"));
    expectTextError(dir / "fewer.tfx", 15, "ends after 2 of numStrands 3");
    writeFile(dir / "more.tfx", tfx2Text("numStrands 1\n", 2, 3));
    expectTextError(dir / "more.tfx", 6, "more strands than numStrands 1");

    std::string nan = good;
    nan.replace(nan.find("\n", nan.find("strand 1")) + 1, 8, "nan"); // "0.500000" -> "nan"
    writeFile(dir / "nan.tfx", nan);
    expectTextError(dir / "nan.tfx", 9, "not a finite number");
    writeFile(dir / "word.tfx", "numStrands 1\nstrand 0 numVerts 2\n0 0 banana\n1 1 1\n");
    expectTextError(dir / "word.tfx", 3, "'banana'");

    writeFile(dir / "zero.tfx", "version 2.0\nnumStrands 0\n");
    expectTextError(dir / "zero.tfx", 2, "no strands");
    writeFile(dir / "single.tfx", "numStrands 1\nstrand 0 numVerts 1\n0 0 0\n1 1 1\n");
    expectTextError(dir / "single.tfx", 2, "at least 2");
    writeFile(dir / "order.tfx", "numStrands 1\nstrand 1 numVerts 2\n0 0 0\n1 1 1\n");
    expectTextError(dir / "order.tfx", 2, "out of order");
    writeFile(dir / "bad-key.tfx", "numStrands 1\nscale big\nstrand 0 numVerts 2\n0 0 0\n1 1 1\n");
    expectTextError(dir / "bad-key.tfx", 2, "'big'");
    writeFile(dir / "bad-line.tfx", "numStrands 1\n1.0 2.0\nstrand 0 numVerts 2\n0 0 0\n1 1 1\n");
    expectTextError(dir / "bad-line.tfx", 2, "expected a header key");
}

// ---- resampling, placement, inspect -------------------------------------------------------------

TEST(HairResample, ExactCountAndEndsPreserved)
{
    std::vector<glm::vec3> line = {{0, 0, 0}, {1, 0, 0}, {1, 3, 0}, {1, 3, 2.5f}};
    for (uint32_t count : {2u, 3u, 4u, 7u, 16u, 33u}) {
        std::vector<glm::vec3> r = resampleStrand(line, count);
        ASSERT_EQ(r.size(), count);
        EXPECT_EQ(r.front(), line.front());
        EXPECT_EQ(r.back(), line.back());
    }
    EXPECT_THROW(resampleStrand(line, 1), std::invalid_argument);
    std::vector<glm::vec3> still = resampleStrand({{1, 2, 3}, {1, 2, 3}}, 5);
    ASSERT_EQ(still.size(), 5u);
    for (const glm::vec3& p : still)
        EXPECT_EQ(p, glm::vec3(1, 2, 3));
}

TEST(HairResample, EqualArcLengthSpacingOnABentPolyline)
{
    // Unequal segments, sharp turns and a zero-length segment.
    std::vector<glm::vec3> line = {{0, 0, 0}, {0.3f, 0, 0}, {0.3f, 2, 0}, {0.3f, 2, 0}, {-1, 2.5f, 1}, {-1, 0, 1.2f}};
    float total = 0.0f;
    for (size_t k = 1; k < line.size(); ++k)
        total += glm::length(line[k] - line[k - 1]);
    for (uint32_t count : {5u, 16u, 32u}) {
        std::vector<glm::vec3> r = resampleStrand(line, count);
        float step = total / static_cast<float>(count - 1);
        float previous = 0.0f;
        for (uint32_t k = 1; k < count; ++k) {
            float at = arcPosition(line, r[k]);
            EXPECT_NEAR(at - previous, step, 1e-4f * step) << "count " << count << " point " << k;
            previous = at;
        }
    }
}

TEST(HairResample, StraightLineStaysStraight)
{
    glm::vec3 a(1, -2, 0.5f), b(4, 2, -1.5f);
    std::vector<glm::vec3> line = {a, glm::mix(a, b, 0.1f), glm::mix(a, b, 0.15f), glm::mix(a, b, 0.7f), b};
    std::vector<glm::vec3> r = resampleStrand(line, 11);
    for (uint32_t k = 0; k < r.size(); ++k) {
        glm::vec3 expected = glm::mix(a, b, static_cast<float>(k) / 10.0f);
        EXPECT_NEAR(glm::length(r[k] - expected), 0.0f, 1e-5f) << "point " << k;
    }
}

TEST(HairPlacement, CentimetreAssetOnMetreHeadScalesByAHundredth)
{
    HairAsset hair;
    hair.strands.push_back({{{-15, 150, -10}, {12, 175, 14}}}); // about 40 cm across
    Bounds head{{-0.1f, 1.4f, -0.12f}, {0.1f, 1.75f, 0.12f}};   // about 0.45 m
    HairPlacement p = autoPlacement(hair, head);
    EXPECT_FLOAT_EQ(p.scale, 0.01f);
    EXPECT_EQ(p.offset, glm::vec3(0.0f));
    EXPECT_FALSE(p.zUpToYUp);
    EXPECT_FALSE(p.mirrorZ);

    HairAsset metres; // same units (ratio within [0.2, 5]) keeps scale 1
    metres.strands.push_back({{{-0.1f, 1.5f, -0.1f}, {0.05f, 1.6f, 0.02f}}});
    EXPECT_EQ(autoPlacement(metres, head).scale, 1.0f);
    // Millimetres on metres, and metres on centimetres.
    HairAsset mm;
    mm.strands.push_back({{{-150, 1500, -100}, {120, 1750, 140}}});
    EXPECT_FLOAT_EQ(autoPlacement(mm, head).scale, 0.001f);
    EXPECT_FLOAT_EQ(autoPlacement(metres, Bounds{{-10, 140, -12}, {10, 175, 12}}).scale, 100.0f);
}

TEST(HairPlacement, ScaleThenAxisFixesThenOffset)
{
    glm::vec3 p(1, 2, 3);
    EXPECT_EQ(applyPlacement({}, p), p);
    EXPECT_EQ(applyPlacement({.scale = 2.0f, .offset = {10, 0, 0}}, p), glm::vec3(12, 4, 6));
    EXPECT_EQ(applyPlacement({.mirrorZ = true}, p), glm::vec3(1, 2, -3));
    // z-up to y-up: up (0,0,1) becomes (0,1,0); a proper rotation (x kept, y -> -z).
    EXPECT_EQ(applyPlacement({.zUpToYUp = true}, glm::vec3(0, 0, 1)), glm::vec3(0, 1, 0));
    EXPECT_EQ(applyPlacement({.zUpToYUp = true}, glm::vec3(0, 1, 0)), glm::vec3(0, 0, -1));
    EXPECT_EQ(applyPlacement({.scale = 0.5f, .offset = {0, 1, 0}, .zUpToYUp = true}, p), glm::vec3(0.5f, 2.5f, -1.0f));
}

TEST(HairDescribe, InspectJsonKeys)
{
    TempDir dir;
    writeFile(dir / "small.hair", cyHairFile({3, 1, 6}, true).data);
    nlohmann::json j = describeHairAsset(loadHairAsset(dir / "small.hair"));
    EXPECT_EQ(j["kind"], "hair");
    EXPECT_EQ(j["format"], "cyhair");
    EXPECT_EQ(j["strands"], 3);
    EXPECT_EQ(j["vertices"], 13);
    EXPECT_EQ(j["vertices_per_strand"], nlohmann::json({2, 7}));
    ASSERT_EQ(j["bbox"].size(), 2u);
    EXPECT_EQ(j["bbox"][0], nlohmann::json({0.0f, 1.0f, -1.0f}));
    EXPECT_EQ(j["bbox"][1], nlohmann::json({1.0f, 2.5f, 0.0f}));
    EXPECT_EQ(j.size(), 6u);
}

// ---- Found by fuzzing (fuzz/fuzz_cyhair.cpp, fuzz_tfx.cpp, fuzz_tfx2.cpp) -----------------------

TEST(HairErrors, CyHairHeaderCountsCostNoMemoryTheFileDoesNotBack)
{
    // A 128-byte header claiming 50,000,000 strands (100,000,000 points, within what Wisp reads):
    // the reader allocated 200 MB of per-strand counts before finding the arrays missing, which
    // made the fuzzer crawl. Now every array is checked against the file before any allocation.
    TempDir dir;
    for (uint32_t arrays : {2u, 3u}) { // points only (d_segments 1), and with a segments array
        Bytes b;
        b.text("HAIR").u32(50'000'000).u32(100'000'000).u32(arrays).u32(1).zeros(128 - 20);
        writeFile(dir / "big.hair", b.data);
        test::resetLargestAllocation();
        std::string e = errorOf(dir / "big.hair");
        EXPECT_NE(e.find(arrays == 2u ? "the points array needs" : "the segments array needs"), std::string::npos) << e;
        EXPECT_LT(test::largestAllocation(), size_t(1) << 20) << "arrays " << arrays;
    }
}

TEST(HairErrors, Tfx2HeaderTransformToNonFinitePointsNamesTheLine)
{
    // Finite numbers made infinite by the header's scale (1e30 x 1e9): the points were returned
    // non-finite. The fuzz targets' contract check reports it (fuzz/fuzz_support.h); found while
    // reviewing the reader, not by the fuzzer's own search.
    TempDir dir;
    writeFile(dir / "inf.tfx", "scale 1e30\nnumStrands 1\nstrand 0 numVerts 2 texcoord 0 0\n1e9 0 0\n0 0 0\n");
    std::string e = errorOf(dir / "inf.tfx");
    EXPECT_NE(e.find("inf.tfx:4:"), std::string::npos) << e;
    EXPECT_NE(e.find("not finite once scaled"), std::string::npos) << e;
}

// ---- text as people's tools write it -------------------------------------------------

TEST(HairText, TrailingNulsAndWhiteSpaceArePadding)
{
    // Some exporters pad a file with NULs: it was "more strands than numStrands" (the NUL read as a line).
    TempDir dir;
    std::string good = tfx2Text("version 2.0\nnumStrands 2\n", 2, 3);
    writeFile(dir / "padded.tfx", good + std::string("\0\0\0", 3) + " \r\n\t" + std::string(1, '\0'));
    expectExactPoints(loadHairAsset(dir / "padded.tfx"), {3, 3});
    writeFile(dir / "padded-crlf.tfx", good + "\r\n\r\n" + std::string(64, '\0'));
    expectExactPoints(loadHairAsset(dir / "padded-crlf.tfx"), {3, 3});
}

TEST(HairText, NulInsideTheTextNamesItsLineByteAndWord)
{
    // A NUL inside a number cut the message short at the NUL ("'-2").
    TempDir dir;
    std::string good = tfx2Text("version 2.0\nnumStrands 2\n", 2, 3);
    std::string bad = good;
    size_t at = bad.find('\n', bad.find("strand 1")) + 1; // the first point of strand 1, line 8
    bad.insert(at + 2, 1, '\0');
    writeFile(dir / "nul.tfx", bad);
    std::string e = errorOf(dir / "nul.tfx");
    EXPECT_NE(e.find("nul.tfx:8: byte " + std::to_string(at + 2) + " is a NUL byte inside the text (in '" +
                     good.substr(at, 2) + "\\x00" + good.substr(at + 2, good.find(' ', at) - at - 2) + "')"),
              std::string::npos)
        << e;
    EXPECT_EQ(e.find('\0'), std::string::npos);
    // Early in the file (among the bytes that tell text from binary) it is still the text's error.
    bad = good;
    bad.insert(bad.find("2.0") + 1, 1, '\0');
    writeFile(dir / "nul-header.tfx", bad);
    expectTextError(dir / "nul-header.tfx", 1, "is a NUL byte inside the text (in '2\\x00.0')");
}

TEST(HairText, BareCarriageReturnsEndLinesAsLineFeedsDo)
{
    // Old Mac line endings: the whole file was one line, quoted with its raw CRs in the message.
    TempDir dir;
    std::string good = tfx2Text("version 2.0\nnumStrands 2\n", 2, 3);
    std::string cr = good, crlf;
    std::replace(cr.begin(), cr.end(), '\n', '\r');
    for (char c : good)
        crlf += c == '\n' ? std::string("\r\n") : std::string(1, c);
    writeFile(dir / "cr.tfx", cr);
    expectExactPoints(loadHairAsset(dir / "cr.tfx"), {3, 3});
    writeFile(dir / "crlf.tfx", crlf);
    expectExactPoints(loadHairAsset(dir / "crlf.tfx"), {3, 3});
    // Mixed endings count lines the same way, and an error names its line without a raw CR in it.
    std::string mixed = "version 2.0\rnumStrands 1\r\nstrand 0 numVerts 2\n0 0 0\r1 1 banana\r";
    writeFile(dir / "mixed.tfx", mixed);
    expectTextError(dir / "mixed.tfx", 5, "'banana'");
    EXPECT_EQ(errorOf(dir / "mixed.tfx").find('\r'), std::string::npos);
}

TEST(HairText, NumbersTooSmallForAFloatReadAsZero)
{
    // 1.58480958e-48 is finite; it was "not a finite number". It underflows to 0 in a float.
    TempDir dir;
    writeFile(dir / "tiny.tfx", "numStrands 1\nstrand 0 numVerts 2\n1.58480958e-48 0 -1e-50\n1 1 1e-40\n");
    HairAsset asset = loadHairAsset(dir / "tiny.tfx");
    EXPECT_EQ(asset.strands[0].points[0], glm::vec3(0.0f));
    EXPECT_NEAR(asset.strands[0].points[1].z, 1e-40f, 1e-44f); // a denormal stays one
    // Too large for a float is said as such.
    writeFile(dir / "huge.tfx", "numStrands 1\nstrand 0 numVerts 2\n0 0 0\n1 1 4e38\n");
    expectTextError(dir / "huge.tfx", 4, "'4e38' is beyond the float range");
}

TEST(HairText, CoordinatesPastTheFloatMathsRangeNameTheFileAndWhere)
{
    // A vertex at 1e30 gave "is 3.46e30 long, too short to split into 15 segments" from the scene.
    TempDir dir;
    writeFile(dir / "far.tfx", "numStrands 1\nstrand 0 numVerts 2\n0 0 0\n1e30 1e30 1e30\n");
    expectTextError(dir / "far.tfx", 4, "coordinate 1e+30 is out of the range Wisp's float math handles");
    Bytes tfx4 = tfx4File(2, 4);
    std::string bytes = tfx4.data;
    uint64_t at = 160 + 16 * 5 + 4; // strand 1, point 1, y
    float far = -2e12f;
    std::memcpy(bytes.data() + at, &far, 4);
    writeFile(dir / "far.tfx4", bytes);
    expectBinaryError(dir / "far.tfx4", std::to_string(at),
                      "point 1 of strand 1: coordinate -2e+12 is out of the range");
}
