// tests/groom_files.h: small groom files written by the tests (FORMATS.md), from strands given as
// points: TressFX 4 (with pinned root vertices), TressFX 3 (with bothEndsImmovable), TressFX 2 text
// and cyHair; and a groom grown on the default head to place elsewhere.
#pragma once

#include "physics/hair_scene.h"

#include <glm/glm.hpp>

#include <bit>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace wisp::test {

using Strands = std::vector<std::vector<glm::vec3>>;

inline void appendU32(std::string& s, uint32_t v)
{
    for (int k = 0; k < 4; ++k)
        s.push_back(char((v >> (8 * k)) & 0xffu));
}
inline void appendF32(std::string& s, float v) { appendU32(s, std::bit_cast<uint32_t>(v)); }

inline void writeBytes(const std::filesystem::path& path, const std::string& bytes)
{
    std::ofstream out(path, std::ios::binary);
    out << bytes;
}

// TressFX 4: every strand must have the same number of points; the root vertex is pinned (w = 0).
inline void writeTfx4(const std::filesystem::path& path, const Strands& strands)
{
    std::string b;
    appendF32(b, 4.0f);
    appendU32(b, uint32_t(strands.size()));
    appendU32(b, uint32_t(strands.front().size()));
    appendU32(b, 160);
    b.append(4 * 4 + 32 * 4, '\0');
    for (const auto& s : strands)
        for (size_t v = 0; v < s.size(); ++v) {
            appendF32(b, s[v].x);
            appendF32(b, s[v].y);
            appendF32(b, s[v].z);
            appendF32(b, v == 0 ? 0.0f : 1.0f);
        }
    writeBytes(path, b);
}

// TressFX 3 (left-handed: Wisp mirrors z when it loads one, so z is written mirrored here).
inline void writeTfx3(const std::filesystem::path& path, const Strands& strands, bool bothEndsImmovable)
{
    std::string b;
    appendF32(b, 3.0f);
    appendU32(b, uint32_t(strands.size()));
    appendU32(b, uint32_t(strands.front().size()));
    appendU32(b, 4);
    appendU32(b, bothEndsImmovable ? 1u : 0u);
    b.append(31 * 4, '\0');
    appendU32(b, 296);
    b.append(5 * 4 + 32 * 4, '\0');
    for (const auto& s : strands)
        for (const glm::vec3& p : s) {
            appendF32(b, p.x);
            appendF32(b, p.y);
            appendF32(b, -p.z);
        }
    writeBytes(path, b);
}

// cyHair: z-up (Wisp turns it y-up when it loads one, so y-up points are written z-up here).
inline void writeCyHair(const std::filesystem::path& path, const Strands& strands)
{
    uint32_t points = 0;
    for (const auto& s : strands)
        points += uint32_t(s.size());
    std::string b = "HAIR";
    appendU32(b, uint32_t(strands.size()));
    appendU32(b, points);
    appendU32(b, 1u | 2u);
    appendU32(b, 0);
    for (int k = 0; k < 5; ++k)
        appendF32(b, 0.0f);
    b.append(88, '\0');
    for (const auto& s : strands) {
        uint16_t segments = uint16_t(s.size() - 1);
        b.push_back(char(segments & 0xffu));
        b.push_back(char(segments >> 8));
    }
    for (const auto& s : strands)
        for (const glm::vec3& p : s) {  // (x, y, z) y-up is (x, -z, y) z-up
            appendF32(b, p.x);
            appendF32(b, -p.z);
            appendF32(b, p.y);
        }
    writeBytes(path, b);
}

// `guides` strands grown on the default head, as points in head units (metres), `transform` applied.
template <class Transform>
Strands grownStrands(uint32_t guides, uint32_t vertices, Transform transform)
{
    GrowthSettings g;
    g.guides = guides;
    g.verticesPerStrand = vertices;
    HairScene scene = buildGrownScene(defaultHeadPath(), g);
    Strands out(scene.strands.strandCount());
    for (size_t s = 0; s < out.size(); ++s)
        for (uint32_t i = 0; i < vertices; ++i)
            out[s].push_back(transform(scene.strands.rest[s * vertices + i]));
    return out;
}

}  // namespace wisp::test
