// assets/hair_writer.cpp: cyHair and TressFX 4 encoders (FORMATS.md), every count checked against
// what the format and Wisp's reader hold before a byte is encoded, and the atomic write.
#include "assets/hair_writer.h"

#include "core/atomic_file.h"
#include "core/error.h"

#include <algorithm>
#include <bit>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <limits>

namespace wisp {

namespace {

constexpr uint32_t kCyHairHeaderBytes = 128;
constexpr uint32_t kCyHairInfoBytes = 88;
constexpr uint32_t kCySegments = 1u << 0;
constexpr uint32_t kCyPoints = 1u << 1;
constexpr uint32_t kTfx4HeaderBytes = 160;
constexpr uint32_t kTfx4MaxVerticesPerStrand = 1024; // what loadHairAsset reads
constexpr uint64_t kMaxPoints = 100'000'000;         // the same limit as the readers'

std::string str(uint64_t n)
{
    return std::to_string(n);
}

void appendU32(std::string& s, uint32_t v)
{
    for (int k = 0; k < 4; ++k)
        s.push_back(char((v >> (8 * k)) & 0xffu));
}

void appendU16(std::string& s, uint16_t v)
{
    s.push_back(char(v & 0xffu));
    s.push_back(char(v >> 8));
}

void appendF32(std::string& s, float v)
{
    appendU32(s, std::bit_cast<uint32_t>(v));
}

// The checks both formats share: some strands, each of at least 2 finite points, a total Wisp reads.
uint64_t checkStrands(const GroomToWrite& groom, const char* format)
{
    if (groom.strands.empty())
        throw UserError(std::string("cannot write ") + format + ": the groom has no strands");
    uint64_t points = 0;
    for (size_t s = 0; s < groom.strands.size(); ++s) {
        const std::vector<glm::vec3>& p = groom.strands[s].points;
        if (p.size() < 2)
            throw UserError(std::string("cannot write ") + format + ": strand " + str(s) + " has " + str(p.size()) +
                            " point(s); a strand needs at least 2");
        for (size_t i = 0; i < p.size(); ++i)
            if (!std::isfinite(p[i].x) || !std::isfinite(p[i].y) || !std::isfinite(p[i].z))
                throw UserError(std::string("cannot write ") + format + ": point " + str(i) + " of strand " + str(s) +
                                " is not finite");
        points += p.size();
    }
    if (points > kMaxPoints)
        throw UserError(std::string("cannot write ") + format + ": " + str(points) + " points are more than the " +
                        str(kMaxPoints) + " Wisp reads back");
    return points;
}

} // namespace

HairFormat hairFormatForOutput(const std::filesystem::path& path)
{
    std::string ext = path.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    if (ext == ".hair")
        return HairFormat::CyHair;
    if (ext == ".tfx")
        return HairFormat::Tfx4;
    throw UserError(path.string() + ": unknown groom format '" + path.extension().string() +
                    "': write .hair (cyHair) or .tfx (TressFX 4)");
}

std::string encodeCyHair(const GroomToWrite& groom)
{
    uint64_t points = checkStrands(groom, "cyHair");
    size_t first = groom.strands.front().points.size();
    bool uniform = std::all_of(groom.strands.begin(), groom.strands.end(),
                               [&](const HairStrand& s) { return s.points.size() == first; });
    for (size_t s = 0; s < groom.strands.size() && !uniform; ++s)
        if (groom.strands[s].points.size() - 1 > std::numeric_limits<uint16_t>::max())
            throw UserError("cannot write cyHair: strand " + str(s) + " has " +
                            str(groom.strands[s].points.size() - 1) +
                            " segments; the segments array holds at most 65535");
    if (groom.strands.size() > std::numeric_limits<uint32_t>::max())
        throw UserError("cannot write cyHair: " + str(groom.strands.size()) + " strands do not fit hair_count");

    std::string b = "HAIR";
    appendU32(b, uint32_t(groom.strands.size()));
    appendU32(b, uint32_t(points));
    appendU32(b, uniform ? kCyPoints : (kCySegments | kCyPoints));
    appendU32(b, uniform ? uint32_t(first - 1) : 0u); // d_segments
    appendF32(b, groom.thickness);                    // d_thickness
    appendF32(b, 0.0f);                               // d_transparency
    for (int k = 0; k < 3; ++k)
        appendF32(b, 0.0f); // d_color
    std::string info = groom.info.substr(0, kCyHairInfoBytes - 1);
    info.resize(kCyHairInfoBytes, '\0');
    b += info;
    if (b.size() != kCyHairHeaderBytes)
        throw std::logic_error("encodeCyHair: the header is " + str(b.size()) + " bytes, not 128");
    if (!uniform)
        for (const HairStrand& s : groom.strands)
            appendU16(b, uint16_t(s.points.size() - 1));
    b.reserve(b.size() + 12 * points);
    for (const HairStrand& s : groom.strands)
        for (const glm::vec3& p : s.points) { // y-up (x, y, z) is z-up (x, -z, y)
            appendF32(b, p.x);
            appendF32(b, -p.z);
            appendF32(b, p.y);
        }
    return b;
}

std::string encodeTfx4(const GroomToWrite& groom)
{
    checkStrands(groom, "TressFX 4");
    size_t perStrand = groom.strands.front().points.size();
    for (size_t s = 0; s < groom.strands.size(); ++s)
        if (groom.strands[s].points.size() != perStrand)
            throw UserError("cannot write TressFX 4: strand " + str(s) + " has " + str(groom.strands[s].points.size()) +
                            " points but strand 0 has " + str(perStrand) +
                            ": every strand of a TressFX 4 file has the same number");
    if (perStrand > kTfx4MaxVerticesPerStrand)
        throw UserError("cannot write TressFX 4: " + str(perStrand) + " points a strand are more than the " +
                        str(kTfx4MaxVerticesPerStrand) + " Wisp reads back");
    if (groom.strands.size() > std::numeric_limits<uint32_t>::max())
        throw UserError("cannot write TressFX 4: " + str(groom.strands.size()) + " strands do not fit its count");

    std::string b;
    appendF32(b, 4.0f);
    appendU32(b, uint32_t(groom.strands.size()));
    appendU32(b, uint32_t(perStrand));
    appendU32(b, kTfx4HeaderBytes); // offsetVertexPosition
    for (int k = 0; k < 4; ++k)
        appendU32(b, 0); // strand UVs, vertex UVs, strand thicknesses, vertex colours: absent
    b.append(32 * 4, '\0');
    if (b.size() != kTfx4HeaderBytes)
        throw std::logic_error("encodeTfx4: the header is " + str(b.size()) + " bytes, not 160");
    b.reserve(b.size() + 16 * perStrand * groom.strands.size());
    for (const HairStrand& s : groom.strands)
        for (size_t i = 0; i < perStrand; ++i) {
            bool pinned = i < s.pinnedRoot || (s.pinnedTip && i + 1 == perStrand);
            appendF32(b, s.points[i].x);
            appendF32(b, s.points[i].y);
            appendF32(b, s.points[i].z);
            appendF32(b, pinned ? 0.0f : 1.0f); // inverse mass
        }
    return b;
}

void writeHairFile(const std::filesystem::path& path, const GroomToWrite& groom)
{
    HairFormat format = hairFormatForOutput(path);
    std::string bytes = format == HairFormat::CyHair ? encodeCyHair(groom) : encodeTfx4(groom);
    writeFileAtomically(path, bytes);
}

} // namespace wisp
