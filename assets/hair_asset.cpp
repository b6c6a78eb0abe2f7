// assets/hair_asset.cpp: the hair file readers (TressFX 2 text, TressFX 3/4 binary, cyHair),
// each checking every size and count against the file length before it reads, plus strand
// resampling, automatic placement and the inspect summary. Binary errors name the byte offset,
// text errors the line.
#include "assets/hair_asset.h"

#include "assets/text.h"
#include "core/error.h"
#include "core/rotation.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <bit>
#include <charconv>
#include <cmath>
#include <fstream>
#include <stdexcept>
#include <string>
#include <string_view>

namespace wisp {

namespace {

constexpr uint64_t kMaxPoints = 100'000'000;          // more than any groom Wisp can simulate
constexpr uint64_t kMaxFileBytes = uint64_t(4) << 30; // 4 GiB: 100M tfx4 points are 1.6 GB
constexpr uint32_t kMinFileVerticesPerStrand = 2;     // tfx3 / tfx4 numVerticesPerStrand range
constexpr uint32_t kMaxFileVerticesPerStrand = 1024;

constexpr uint64_t kTfx3HeaderBytes = 296;
constexpr uint64_t kTfx3VertexOffsetAt = 144;
constexpr uint64_t kTfx3Stride = 12; // float x, y, z
constexpr uint64_t kTfx4HeaderBytes = 160;
constexpr uint64_t kTfx4Stride = 16; // float x, y, z, w (inverse mass)

constexpr uint64_t kCyHairHeaderBytes = 128;
constexpr uint32_t kCySegments = 1u << 0;
constexpr uint32_t kCyPoints = 1u << 1;
constexpr uint32_t kCyThickness = 1u << 2;
constexpr uint32_t kCyTransparency = 1u << 3;
constexpr uint32_t kCyColors = 1u << 4;

constexpr std::string_view kTfx2Keys[] = {"version",
                                          "scale",
                                          "rotation",
                                          "translation",
                                          "bothEndsImmovable",
                                          "maxNumVerticesInStrand",
                                          "numFollowHairsPerGuideHair",
                                          "maxRadiusAroundGuideHair",
                                          "numStrands",
                                          "is",
                                          "strand"};

std::string str(uint64_t n)
{
    return std::to_string(n);
}

bool isTfx2Key(std::string_view word)
{
    return std::find(std::begin(kTfx2Keys), std::end(kTfx2Keys), word) != std::end(kTfx2Keys);
}

// ---- binary files -------------------------------------------------------------------------------

class BinaryFile {
public:
    BinaryFile(const std::filesystem::path& path, const std::string& data) : path_(path), data_(data) {}

    uint64_t size() const { return data_.size(); }

    [[noreturn]] void fail(uint64_t offset, const std::string& what) const
    {
        throw UserError(path_.string() + ": byte " + str(offset) + ": " + what);
    }

    // `what` needs `bytes` (spelt out as `formula`) starting at `offset`: fail unless they are there.
    // The message names where they start and end and where the file ends, so the numbers cannot
    // read as contradictory ("needs 96 bytes but the file has 391").
    void need(uint64_t offset, uint64_t bytes, const std::string& what, const std::string& formula = "") const
    {
        if (offset <= size() && bytes <= size() - offset)
            return;
        std::string amount = formula.empty() ? str(bytes) : formula + " = " + str(bytes);
        fail(offset, what + " needs " + amount + " bytes from byte " + str(offset) + " to byte " + str(offset + bytes) +
                         ", but the file ends at byte " + str(size()));
    }

    // The header's other sections (offset, name, where the header holds that offset): the block of
    // `bytes` at `offset` must end before the first of them that starts after it, or the header
    // claims more than the block holds (a count too large reads the next section as points).
    struct Section {
        uint32_t offset;
        const char* name;
        uint64_t at;
    };
    void fitsBefore(uint64_t offset, uint64_t bytes, uint64_t strideBytes, uint64_t count, const std::string& counted,
                    std::initializer_list<Section> sections) const
    {
        for (const Section& next : sections) {
            if (next.offset <= offset || offset + bytes <= next.offset)
                continue;
            fail(next.at, "the header's " + counted + " need positions from byte " + str(offset) + " to byte " +
                              str(offset + bytes) + ", but its " + next.name + " start at byte " + str(next.offset) +
                              " (the offset at byte " + str(next.at) + "): the positions hold " +
                              str((next.offset - offset) / strideBytes) + " of the " + str(count) +
                              " strands it claims");
        }
    }

    uint32_t u32(uint64_t at) const { return byte(at) | byte(at + 1) << 8 | byte(at + 2) << 16 | byte(at + 3) << 24; }
    uint16_t u16(uint64_t at) const { return static_cast<uint16_t>(byte(at) | byte(at + 1) << 8); }
    float f32(uint64_t at) const { return std::bit_cast<float>(u32(at)); }

    // A point of three floats at `at`; fails on a non-finite coordinate or one past kMaxCoordinate.
    glm::vec3 point(uint64_t at, uint64_t strand, uint64_t vertex) const
    {
        glm::vec3 p(f32(at), f32(at + 4), f32(at + 8));
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
            fail(at, "point " + str(vertex) + " of strand " + str(strand) + " has a non-finite coordinate");
        for (int axis = 0; axis < 3; ++axis)
            if (std::string error = coordinateRangeError(p[axis]); !error.empty())
                fail(at + 4 * uint64_t(axis), "point " + str(vertex) + " of strand " + str(strand) + ": " + error);
        return p;
    }

private:
    uint32_t byte(uint64_t at) const { return static_cast<unsigned char>(data_[at]); }

    const std::filesystem::path& path_;
    const std::string& data_;
};

// Shared by TressFX 3 and 4: the strand count at byte 4 and the vertices per strand at byte 8.
void checkTfxCounts(const BinaryFile& file, uint32_t strands, uint32_t perStrand)
{
    if (strands == 0)
        file.fail(4, "the file holds no strands (strand count 0)");
    if (perStrand < kMinFileVerticesPerStrand || perStrand > kMaxFileVerticesPerStrand)
        file.fail(8, "vertices per strand is " + str(perStrand) + ", outside " + str(kMinFileVerticesPerStrand) + ".." +
                         str(kMaxFileVerticesPerStrand));
    if (uint64_t(strands) * perStrand > kMaxPoints)
        file.fail(4, str(strands) + " strands of " + str(perStrand) + " vertices are more than the " + str(kMaxPoints) +
                         " points Wisp reads");
}

HairAsset loadTfx3(const BinaryFile& file)
{
    file.need(0, kTfx3HeaderBytes, "the TressFX 3 header");
    uint32_t strands = file.u32(4);
    uint32_t perStrand = file.u32(8);
    bool bothEnds = file.u32(16) != 0;
    uint32_t offset = file.u32(kTfx3VertexOffsetAt);
    checkTfxCounts(file, strands, perStrand);
    if (offset < kTfx3HeaderBytes)
        file.fail(kTfx3VertexOffsetAt,
                  "vertex offset " + str(offset) + " lies inside the " + str(kTfx3HeaderBytes) + "-byte header");
    file.need(offset, uint64_t(strands) * perStrand * kTfx3Stride, "vertex data",
              str(strands) + "*" + str(perStrand) + "*" + str(kTfx3Stride));
    file.fitsBefore(offset, uint64_t(strands) * perStrand * kTfx3Stride, uint64_t(perStrand) * kTfx3Stride, strands,
                    str(strands) + " strands of " + str(perStrand) + " vertices",
                    {{file.u32(148), "per-strand thicknesses", 148},
                     {file.u32(152), "per-strand texture coordinates", 152},
                     {file.u32(156), "per-vertex colours", 156},
                     {file.u32(160), "guide hair indices", 160},
                     {file.u32(164), "per-vertex texture coordinates", 164}});

    HairAsset asset;
    asset.format = HairFormat::Tfx3;
    asset.mirroredZ = true;
    asset.strands.resize(strands);
    uint64_t at = offset;
    for (uint32_t s = 0; s < strands; ++s) {
        HairStrand& strand = asset.strands[s];
        strand.pinnedTip = bothEnds;
        strand.points.reserve(perStrand);
        for (uint32_t v = 0; v < perStrand; ++v, at += kTfx3Stride)
            strand.points.push_back(file.point(at, s, v));
    }
    return asset;
}

HairAsset loadTfx4(const BinaryFile& file)
{
    file.need(0, kTfx4HeaderBytes, "the TressFX 4 header");
    uint32_t strands = file.u32(4);
    uint32_t perStrand = file.u32(8);
    uint32_t offset = file.u32(12);
    checkTfxCounts(file, strands, perStrand);
    if (offset < kTfx4HeaderBytes)
        file.fail(12, "vertex offset " + str(offset) + " lies inside the " + str(kTfx4HeaderBytes) + "-byte header");
    file.need(offset, uint64_t(strands) * perStrand * kTfx4Stride, "vertex data",
              str(strands) + "*" + str(perStrand) + "*" + str(kTfx4Stride));
    file.fitsBefore(offset, uint64_t(strands) * perStrand * kTfx4Stride, uint64_t(perStrand) * kTfx4Stride, strands,
                    str(strands) + " strands of " + str(perStrand) + " vertices",
                    {{file.u32(16), "strand texture coordinates", 16},
                     {file.u32(20), "vertex texture coordinates", 20},
                     {file.u32(24), "strand thicknesses", 24},
                     {file.u32(28), "vertex colours", 28}});

    HairAsset asset;
    asset.format = HairFormat::Tfx4;
    asset.strands.resize(strands);
    uint64_t at = offset;
    for (uint32_t s = 0; s < strands; ++s) {
        HairStrand& strand = asset.strands[s];
        strand.points.reserve(perStrand);
        uint32_t pinned = 0;
        bool leading = true;
        for (uint32_t v = 0; v < perStrand; ++v, at += kTfx4Stride) {
            strand.points.push_back(file.point(at, s, v));
            float w = file.f32(at + 12);
            if (!std::isfinite(w))
                file.fail(at + 12, "point " + str(v) + " of strand " + str(s) + " has a non-finite inverse mass");
            leading = leading && w == 0.0f;
            pinned += leading ? 1 : 0;
        }
        strand.pinnedRoot = std::max(pinned, 1u);
    }
    return asset;
}

HairAsset loadCyHair(const BinaryFile& file)
{
    file.need(0, kCyHairHeaderBytes, "the cyHair header");
    uint32_t hairCount = file.u32(4);
    uint32_t pointCount = file.u32(8);
    uint32_t arrays = file.u32(12);
    uint32_t defaultSegments = file.u32(16);
    if (hairCount == 0)
        file.fail(4, "the file holds no strands (hair_count 0)");
    if (pointCount > kMaxPoints)
        file.fail(8, "point_count " + str(pointCount) + " is more than the " + str(kMaxPoints) + " points Wisp reads");
    if (!(arrays & kCyPoints))
        file.fail(12, "the file has no points array (bit 1 of arrays is clear)");
    if (uint64_t(pointCount) < 2 * uint64_t(hairCount))
        file.fail(8, "point_count " + str(pointCount) + " is too few for " + str(hairCount) +
                         " strands of at least 2 points");

    // Nothing is allocated until every array is known to be in the file: the counts in a header
    // of a few bytes must not cost memory the file does not back.
    uint64_t at = kCyHairHeaderBytes;
    uint64_t segmentsAt = at;
    bool segmentsArray = (arrays & kCySegments) != 0;
    if (segmentsArray) {
        file.need(at, 2 * uint64_t(hairCount), "the segments array", str(hairCount) + "*2");
        uint64_t sum = 0;
        for (uint32_t i = 0; i < hairCount; ++i) {
            uint16_t segments = file.u16(segmentsAt + 2 * uint64_t(i));
            if (segments == 0)
                file.fail(segmentsAt + 2 * uint64_t(i),
                          "strand " + str(i) + " has 0 segments: a strand needs at least 2 points");
            sum += segments + 1u;
        }
        if (sum != pointCount)
            file.fail(segmentsAt, "the segments array adds up to " + str(sum) + " points but point_count (byte 8) is " +
                                      str(pointCount));
        at += 2 * uint64_t(hairCount);
    } else {
        if (defaultSegments == 0)
            file.fail(16, "d_segments is 0 and there is no segments array: a strand needs at least 2 points");
        if (uint64_t(hairCount) * (uint64_t(defaultSegments) + 1) != pointCount)
            file.fail(16, str(hairCount) + " strands of d_segments " + str(defaultSegments) + " + 1 points make " +
                              str(uint64_t(hairCount) * (uint64_t(defaultSegments) + 1)) +
                              " points but point_count (byte 8) is " + str(pointCount));
    }
    uint64_t pointsAt = at;
    file.need(at, 12 * uint64_t(pointCount), "the points array", str(pointCount) + "*3*4");
    at += 12 * uint64_t(pointCount);
    struct Trailing {
        uint32_t bit;
        uint64_t bytesPerPoint;
        const char* name;
    };
    for (Trailing t :
         {Trailing{kCyThickness, 4, "the thickness array"}, Trailing{kCyTransparency, 4, "the transparency array"},
          Trailing{kCyColors, 12, "the colors array"}}) {
        if (arrays & t.bit) {
            file.need(at, t.bytesPerPoint * pointCount, t.name, str(pointCount) + "*" + str(t.bytesPerPoint));
            at += t.bytesPerPoint * pointCount;
        }
    }

    HairAsset asset;
    asset.format = HairFormat::CyHair;
    asset.zUp = true;
    asset.strands.resize(hairCount);
    at = pointsAt;
    for (uint32_t s = 0; s < hairCount; ++s) {
        HairStrand& strand = asset.strands[s];
        uint32_t points = segmentsArray ? file.u16(segmentsAt + 2 * uint64_t(s)) + 1u : defaultSegments + 1u;
        strand.points.reserve(points);
        for (uint32_t v = 0; v < points; ++v, at += 12)
            strand.points.push_back(file.point(at, s, v));
    }
    return asset;
}

// ---- TressFX 2 text -----------------------------------------------------------------------------

class TextFile {
public:
    // The file's lines (ended by LF, CRLF or CR) without its padding; a NUL inside them fails.
    TextFile(const std::filesystem::path& path, const std::string& data) : path_(path)
    {
        std::string_view text = textOf(data);
        checkNoNulBytes(text, bomBytes(data), path, "TressFX 2 text");
        lines_ = splitLines(text);
    }

    size_t lineCount() const { return lines_.size(); }

    [[noreturn]] void fail(size_t line, const std::string& what) const
    {
        throw UserError(path_.string() + ":" + str(line) + ": " + what);
    }

    // The words of line `index` (0-based); empty for blank and '#' comment lines.
    std::vector<std::string_view> words(size_t index) const
    {
        std::vector<std::string_view> out;
        std::string_view rest = lines_[index];
        while (true) {
            size_t start = rest.find_first_not_of(" \t");
            if (start == std::string_view::npos)
                break;
            rest.remove_prefix(start);
            size_t end = rest.find_first_of(" \t");
            out.push_back(rest.substr(0, end));
            rest.remove_prefix(end == std::string_view::npos ? rest.size() : end);
        }
        if (!out.empty() && out.front().starts_with('#'))
            out.clear();
        return out;
    }

    float number(size_t line, std::string_view word) const
    {
        float value = 0.0f;
        if (std::string error = parseFloatWord(word, value); !error.empty())
            fail(line, error);
        return value;
    }

    // A point's coordinate: a number within kMaxCoordinate.
    float coordinate(size_t line, std::string_view word) const
    {
        float value = number(line, word);
        if (std::string error = coordinateRangeError(value); !error.empty())
            fail(line, error);
        return value;
    }

    uint64_t count(size_t line, std::string_view word) const
    {
        uint64_t value = 0;
        auto [end, ec] = std::from_chars(word.data(), word.data() + word.size(), value);
        if (ec != std::errc() || end != word.data() + word.size())
            fail(line, "'" + quoteText(word, 40) + "' is not a whole number");
        return value;
    }

    std::string text(size_t index) const { return quoteText(lines_[index]); }

private:
    const std::filesystem::path& path_;
    std::vector<std::string_view> lines_;
};

HairAsset loadTfx2(const std::filesystem::path& path, const std::string& data)
{
    TextFile file(path, data);
    glm::vec3 scale(1.0f), rotationDeg(0.0f), translation(0.0f);
    bool bothEnds = false;
    uint64_t numStrands = 0;
    size_t numStrandsLine = 0; // 1-based; 0 while not seen

    size_t i = 0;
    for (; i < file.lineCount(); ++i) {
        size_t line = i + 1;
        std::vector<std::string_view> w = file.words(i);
        if (w.empty())
            continue;
        std::string_view key = w.front();
        if (key == "strand")
            break;
        auto needs = [&](size_t n, const char* what) {
            if (w.size() < n + 1)
                file.fail(line, "'" + std::string(key) + "' needs " + what);
        };
        if (key == "scale") {
            needs(1, "1 or 3 numbers");
            scale = w.size() >= 4 ? glm::vec3(file.number(line, w[1]), file.number(line, w[2]), file.number(line, w[3]))
                                  : glm::vec3(file.number(line, w[1]));
        } else if (key == "rotation" || key == "translation") {
            needs(3, "3 numbers");
            glm::vec3 v(file.number(line, w[1]), file.number(line, w[2]), file.number(line, w[3]));
            (key == "rotation" ? rotationDeg : translation) = v;
        } else if (key == "bothEndsImmovable") {
            needs(1, "0 or 1");
            uint64_t v = file.count(line, w[1]);
            if (v > 1)
                file.fail(line, "'bothEndsImmovable' must be 0 or 1, found " + str(v));
            bothEnds = v == 1;
        } else if (key == "numStrands") {
            needs(1, "a count");
            numStrands = file.count(line, w[1]);
            numStrandsLine = line;
        } else if (key == "version" || key == "maxRadiusAroundGuideHair") {
            needs(1, "a number");
            file.number(line, w[1]);
        } else if (key == "maxNumVerticesInStrand" || key == "numFollowHairsPerGuideHair") {
            needs(1, "a count");
            file.count(line, w[1]);
        } else if (!std::isalpha(static_cast<unsigned char>(key.front()))) {
            file.fail(line, "expected a header key or a 'strand' line, found '" + file.text(i) + "'");
        } // other keys ("is sorted 1", exporter extras) carry nothing Wisp uses
    }
    size_t lastLine = std::max<size_t>(file.lineCount(), 1);
    if (numStrandsLine == 0)
        file.fail(i < file.lineCount() ? i + 1 : lastLine, "the header has no numStrands");
    if (numStrands == 0)
        file.fail(numStrandsLine, "numStrands is 0: the file holds no strands");
    if (numStrands > kMaxPoints / 2)
        file.fail(numStrandsLine,
                  "numStrands " + str(numStrands) + " is more than Wisp reads (" + str(kMaxPoints / 2) + ")");
    size_t following = file.lineCount() - i;
    if (numStrands * 3 > following)
        file.fail(numStrandsLine, "numStrands " + str(numStrands) + " needs at least " + str(numStrands * 3) +
                                      " lines (a strand line and 2 points each) but only " + str(following) +
                                      " follow the header");

    // The header's scale, rotation and translation, applied to each point as it is read.
    bool rotate = rotationDeg != glm::vec3(0.0f);
    bool transform = scale != glm::vec3(1.0f) || rotate || translation != glm::vec3(0.0f);
    glm::mat3 r = rotate ? rotationXyzDegrees(rotationDeg) : glm::mat3(1.0f);

    HairAsset asset;
    asset.format = HairFormat::Tfx2;
    asset.strands.resize(numStrands);
    uint64_t total = 0;
    auto nextWords = [&](std::vector<std::string_view>& w) {
        for (; i < file.lineCount(); ++i) {
            w = file.words(i);
            if (!w.empty())
                return true;
        }
        return false;
    };
    std::vector<std::string_view> w;
    for (uint64_t s = 0; s < numStrands; ++s) {
        if (!nextWords(w))
            file.fail(lastLine, "the file ends after " + str(s) + " of numStrands " + str(numStrands) + " strands");
        size_t line = i + 1;
        if (w.size() < 4 || w[0] != "strand" || w[2] != "numVerts")
            file.fail(line, "expected 'strand " + str(s) + " numVerts K texcoord U V', found '" + file.text(i) + "'");
        if (uint64_t index = file.count(line, w[1]); index != s)
            file.fail(line, "strand " + str(index) + " is out of order: expected strand " + str(s));
        uint64_t k = file.count(line, w[3]); // texcoord u v (v written as 000000 by the exporter): not used
        if (k < 2)
            file.fail(line, "strand " + str(s) + " has " + str(k) + " points: a strand needs at least 2");
        if (k > file.lineCount() - line)
            file.fail(line, "strand " + str(s) + " numVerts " + str(k) + " but only " + str(file.lineCount() - line) +
                                " lines follow");
        total += k;
        if (total > kMaxPoints)
            file.fail(line, "the strands hold more than the " + str(kMaxPoints) + " points Wisp reads");
        ++i;
        HairStrand& strand = asset.strands[s];
        strand.pinnedTip = bothEnds;
        strand.points.reserve(k);
        for (uint64_t v = 0; v < k; ++v, ++i) {
            if (!nextWords(w))
                file.fail(lastLine, "the file ends after point " + str(v) + " of strand " + str(s) + " (numVerts " +
                                        str(k) + ")");
            size_t pointLine = i + 1;
            if (w.size() != 3)
                file.fail(pointLine, "expected 'x y z' for point " + str(v) + " of strand " + str(s) + ", found '" +
                                         file.text(i) + "'");
            glm::vec3 p(file.coordinate(pointLine, w[0]), file.coordinate(pointLine, w[1]),
                        file.coordinate(pointLine, w[2]));
            if (transform) {
                p = r * (scale * p) + translation;
                if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
                    file.fail(pointLine, "point " + str(v) + " of strand " + str(s) +
                                             " is not finite once scaled, rotated and translated by the header");
                for (int axis = 0; axis < 3; ++axis)
                    if (std::string error = coordinateRangeError(p[axis]); !error.empty())
                        file.fail(pointLine, "point " + str(v) + " of strand " + str(s) +
                                                 " once scaled, rotated and translated by the header: " + error);
            }
            strand.points.push_back(p);
        }
    }
    if (nextWords(w))
        file.fail(i + 1, "more strands than numStrands " + str(numStrands) + " (line " + str(numStrandsLine) + ")");
    return asset;
}

// ---- format detection ---------------------------------------------------------------------------

// The first word of a text file (after a UTF-8 byte order mark and blank space) and its line.
std::string_view firstWord(const std::string& data, size_t& line)
{
    std::string_view all = textOf(data);
    size_t start = all.find_first_not_of(" \t\r\n");
    if (start == std::string_view::npos)
        return {};
    line = lineOfByte(all, start);
    all.remove_prefix(start);
    return all.substr(0, std::min(all.find_first_of(std::string_view(" \t\r\n\0", 5)), size_t(64)));
}

// No control bytes in the first 256 but line endings, tabs and, with `nulAllowed`, NULs (in a
// file that starts with a TressFX 2 key, the text reader reports a NUL with its line).
bool looksLikeText(const std::string& data, bool nulAllowed)
{
    size_t n = std::min(data.size(), size_t(256));
    for (size_t k = 0; k < n; ++k) {
        unsigned char c = static_cast<unsigned char>(data[k]);
        if (c < 0x20 && c != '\n' && c != '\r' && c != '\t' && !(nulAllowed && c == '\0'))
            return false;
    }
    return n > 0;
}

std::string readWholeFile(const std::filesystem::path& path)
{
    std::error_code ec;
    if (!std::filesystem::exists(path, ec))
        throw UserError(path.string() + ": no such hair file");
    if (std::filesystem::is_directory(path, ec))
        throw UserError(path.string() + ": is a directory, not a hair file");
    uint64_t size = std::filesystem::file_size(path, ec);
    if (ec)
        throw UserError(path.string() + ": cannot read hair file: " + ec.message());
    if (size > kMaxFileBytes)
        throw UserError(path.string() + ": byte 0: the file is " + str(size) + " bytes, more than the " +
                        str(kMaxFileBytes) + " a hair file Wisp reads may have");
    std::ifstream in(path, std::ios::binary);
    if (!in)
        throw UserError(path.string() + ": cannot open hair file");
    std::string data(size, '\0');
    in.read(data.data(), static_cast<std::streamsize>(size));
    if (static_cast<uint64_t>(in.gcount()) != size)
        throw UserError(path.string() + ": read error");
    return data;
}

} // namespace

const char* formatName(HairFormat format)
{
    switch (format) {
    case HairFormat::Tfx2:
        return "tfx2";
    case HairFormat::Tfx3:
        return "tfx3";
    case HairFormat::Tfx4:
        return "tfx4";
    case HairFormat::CyHair:
        return "cyhair";
    }
    return "unknown";
}

size_t HairAsset::totalVertices() const
{
    size_t n = 0;
    for (const HairStrand& s : strands)
        n += s.points.size();
    return n;
}

uint32_t HairAsset::minVertices() const
{
    if (strands.empty())
        return 0;
    size_t n = strands.front().points.size();
    for (const HairStrand& s : strands)
        n = std::min(n, s.points.size());
    return static_cast<uint32_t>(n);
}

uint32_t HairAsset::maxVertices() const
{
    size_t n = 0;
    for (const HairStrand& s : strands)
        n = std::max(n, s.points.size());
    return static_cast<uint32_t>(n);
}

Bounds HairAsset::bounds() const
{
    Bounds b;
    bool first = true;
    for (const HairStrand& s : strands) {
        for (const glm::vec3& p : s.points) {
            b.min = first ? p : glm::min(b.min, p);
            b.max = first ? p : glm::max(b.max, p);
            first = false;
        }
    }
    return b;
}

HairAsset loadHairAsset(const std::filesystem::path& path)
{
    return parseHairAsset(readWholeFile(path), path);
}

HairAsset parseHairAsset(const std::string& data, const std::filesystem::path& path)
{
    BinaryFile binary(path, data);
    if (data.empty())
        binary.fail(0, "the file is empty");

    HairAsset asset;
    if (data.starts_with("HAIR")) {
        asset = loadCyHair(binary);
    } else if (data.size() >= 4 && binary.f32(0) == 3.0f) {
        asset = loadTfx3(binary);
    } else if (data.size() >= 4 && binary.f32(0) == 4.0f) {
        asset = loadTfx4(binary);
    } else {
        size_t line = 1;
        std::string_view word = firstWord(data, line);
        if (looksLikeText(data, true) && isTfx2Key(word)) {
            asset = loadTfx2(path, data);
        } else if (looksLikeText(data, false)) {
            throw UserError(path.string() + ":" + str(line) + ": unrecognised hair file: '" + quoteText(word) +
                            "' is not a TressFX 2 header key, and the file is not binary TressFX or cyHair");
        } else {
            binary.fail(0, "unrecognised hair file: neither the cyHair magic 'HAIR', a TressFX 2 text header, nor "
                           "a TressFX 3/4 version float (3.0 or 4.0)");
        }
    }
    asset.source = path;
    return asset;
}

std::vector<glm::vec3> resampleStrand(const std::vector<glm::vec3>& points, uint32_t count)
{
    if (count < 2)
        throw std::invalid_argument("resampleStrand: count must be at least 2, got " + str(count));
    if (points.empty())
        throw std::invalid_argument("resampleStrand: the strand has no points");
    std::vector<double> arc(points.size(), 0.0); // arc length from the root to each point
    for (size_t k = 1; k < points.size(); ++k)
        arc[k] = arc[k - 1] + glm::length(glm::dvec3(points[k]) - glm::dvec3(points[k - 1]));
    double total = arc.back();
    if (!(total > 0.0))
        return std::vector<glm::vec3>(count, points.front());

    std::vector<glm::vec3> out;
    out.reserve(count);
    out.push_back(points.front());
    size_t seg = 1; // the segment [seg - 1, seg] holding the current target
    for (uint32_t k = 1; k + 1 < count; ++k) {
        double target = total * k / (count - 1);
        while (seg + 1 < points.size() && arc[seg] < target)
            ++seg;
        double length = arc[seg] - arc[seg - 1];
        double t = length > 0.0 ? std::clamp((target - arc[seg - 1]) / length, 0.0, 1.0) : 0.0;
        out.push_back(glm::vec3(glm::mix(glm::dvec3(points[seg - 1]), glm::dvec3(points[seg]), t)));
    }
    out.push_back(points.back());
    return out;
}

HairPlacement autoPlacement(const HairAsset& asset, const Bounds& headBounds)
{
    HairPlacement placement;
    placement.zUpToYUp = asset.zUp;
    placement.mirrorZ = asset.mirroredZ;
    double hair = asset.bounds().diagonal();
    double head = headBounds.diagonal();
    if (hair > 0.0 && head > 0.0 && std::isfinite(hair) && std::isfinite(head)) {
        double ratio = hair / head;
        if (ratio < kSameUnitsMinRatio || ratio > kSameUnitsMaxRatio)
            placement.scale = static_cast<float>(std::pow(10.0, std::round(-std::log10(ratio))));
    }
    return placement;
}

glm::vec3 applyPlacement(const HairPlacement& placement, glm::vec3 point)
{
    glm::vec3 p = placement.scale * point;
    if (placement.mirrorZ)
        p.z = -p.z;
    if (placement.zUpToYUp)
        p = glm::vec3(p.x, p.z, -p.y);
    if (placement.halfTurn)
        p = glm::vec3(-p.x, p.y, -p.z);
    return p + placement.offset;
}

float strandLength(const std::vector<glm::vec3>& points)
{
    double length = 0.0;
    for (size_t k = 1; k < points.size(); ++k)
        length += glm::length(glm::dvec3(points[k]) - glm::dvec3(points[k - 1]));
    return float(length);
}

nlohmann::json describeHairAsset(const HairAsset& asset)
{
    Bounds b = asset.bounds();
    return {{"kind", "hair"},
            {"format", formatName(asset.format)},
            {"strands", asset.strands.size()},
            {"vertices", asset.totalVertices()},
            {"vertices_per_strand", {asset.minVertices(), asset.maxVertices()}},
            {"bbox", {{b.min.x, b.min.y, b.min.z}, {b.max.x, b.max.y, b.max.z}}}};
}

} // namespace wisp
