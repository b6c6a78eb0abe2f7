// tests/groom_files.h: small groom files written by the tests (FORMATS.md), from strands given as
// points: TressFX 4 (with pinned root vertices), TressFX 3 (with bothEndsImmovable), TressFX 2 text
// and cyHair; and a groom grown on the default head to place elsewhere.
#pragma once

#include "physics/groomed_head.h"

#include <glm/glm.hpp>

#include <algorithm>
#include <bit>
#include <cmath>
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
inline void appendF32(std::string& s, float v)
{
    appendU32(s, std::bit_cast<uint32_t>(v));
}

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
        for (const glm::vec3& p : s) { // (x, y, z) y-up is (x, -z, y) z-up
            appendF32(b, p.x);
            appendF32(b, -p.z);
            appendF32(b, p.y);
        }
    writeBytes(path, b);
}

// `guides` strands grown on the default head, as points in head units (metres), `transform` applied.
template <class Transform> Strands grownStrands(uint32_t guides, uint32_t vertices, Transform transform)
{
    GrowthSettings g;
    g.guides = guides;
    g.verticesPerStrand = vertices;
    GroomedHead scene = buildGrownHead(defaultHeadPath(), g);
    Strands out(scene.strands.strandCount());
    for (size_t s = 0; s < out.size(); ++s)
        for (uint32_t i = 0; i < vertices; ++i)
            out[s].push_back(transform(scene.strands.rest[s * vertices + i]));
    return out;
}

// A head like a 3D scan's: closed, of quads (triangles at the poles), with CRLF line endings, and
// far from an ellipsoid: boxy above the jaw, the back of the skull flattened, the crown raised,
// the jaw narrower, wider at the temples. Centimetres, y up, face toward +z.
inline void writeScanHead(const std::filesystem::path& path)
{
    constexpr int kRings = 40, kSegments = 64;
    auto surface = [](float theta, float phi) {
        glm::vec3 d(std::sin(theta) * std::sin(phi), std::cos(theta), std::sin(theta) * std::cos(phi));
        glm::vec3 r(8.0f, 11.0f, 10.0f);
        // Boxy above the jaw (a superellipsoid of exponent 4: flat top and sides, full corners).
        float box = std::pow(
            std::pow(std::abs(d.x), 4.0f) + std::pow(std::abs(d.y), 4.0f) + std::pow(std::abs(d.z), 4.0f), -0.25f);
        float scale = (d.y > -0.3f ? box : 1.0f) - 0.18f * std::pow(std::max(0.0f, -d.z), 3.0f) // flat back
                      + 0.08f * std::pow(std::max(0.0f, d.y), 4.0f)                             // raised crown
                      - 0.2f * std::pow(std::max(0.0f, -d.y), 2.0f)                             // narrow jaw
                      + 0.06f * std::pow(std::abs(d.x), 3.0f) * std::max(0.0f, d.y + 0.3f);     // temples
        return glm::vec3(0.0f, 150.0f, 0.0f) + scale * r * d;
    };
    std::string text = "# a scan-like head, quads\r\n";
    auto vertex = [&](glm::vec3 p) {
        text += "v " + std::to_string(p.x) + " " + std::to_string(p.y) + " " + std::to_string(p.z) + "\r\n";
    };
    vertex(surface(0.0f, 0.0f)); // 1: the top pole
    for (int i = 1; i < kRings; ++i)
        for (int j = 0; j < kSegments; ++j)
            vertex(surface(3.14159265f * float(i) / kRings, 6.2831853f * float(j) / kSegments));
    vertex(surface(3.14159265f, 0.0f)); // the bottom pole
    auto at = [&](int ring, int seg) { return 2 + (ring - 1) * kSegments + (seg % kSegments); };
    int bottom = 2 + (kRings - 1) * kSegments;
    for (int j = 0; j < kSegments; ++j) // counter-clockwise seen from outside
        text += "f 1 " + std::to_string(at(1, j)) + " " + std::to_string(at(1, j + 1)) + "\r\n";
    for (int i = 1; i < kRings - 1; ++i)
        for (int j = 0; j < kSegments; ++j)
            text += "f " + std::to_string(at(i, j)) + " " + std::to_string(at(i + 1, j)) + " " +
                    std::to_string(at(i + 1, j + 1)) + " " + std::to_string(at(i, j + 1)) + "\r\n";
    for (int j = 0; j < kSegments; ++j)
        text += "f " + std::to_string(at(kRings - 1, j)) + " " + std::to_string(bottom) + " " +
                std::to_string(at(kRings - 1, j + 1)) + "\r\n";
    writeBytes(path, text);
}

// The default mannequin deformed (wider above the ears, its back flattened) in metres, as an
// ASCII PLY read through assimp: a bust from another tool.
inline void writeDeformedBustPly(const std::filesystem::path& path)
{
    Mesh mesh = loadMesh(std::filesystem::path(WISP_SOURCE_DIR) / "models" / "head.obj");
    std::string text = "ply\nformat ascii 1.0\nelement vertex " + std::to_string(mesh.positions.size()) +
                       "\nproperty float x\nproperty float y\nproperty float z\nelement face " +
                       std::to_string(mesh.triangleCount()) + "\nproperty list uchar int vertex_indices\nend_header\n";
    for (glm::vec3 p : mesh.positions) {
        if (p.y > 0.12f)
            p.x *= 1.0f + 1.5f * (p.y - 0.12f);
        if (p.z < -0.03f && p.y > 0.05f)
            p.z = -0.03f + 0.7f * (p.z + 0.03f);
        text += std::to_string(p.x) + " " + std::to_string(p.y) + " " + std::to_string(p.z) + "\n";
    }
    for (size_t t = 0; t < mesh.triangleCount(); ++t)
        text += "3 " + std::to_string(mesh.indices[3 * t]) + " " + std::to_string(mesh.indices[3 * t + 1]) + " " +
                std::to_string(mesh.indices[3 * t + 2]) + "\n";
    writeBytes(path, text);
}

} // namespace wisp::test
