// assets/hair_asset.h: hair assets as files hold them: strands of points in the file's own units,
// read from TressFX 2 text, TressFX 3 and 4 binary and cyHair .hair files (see FORMATS.md), with
// the format told by content. Also arc-length resampling of a strand, placing an asset on a head
// (scale, axis fixes, offset) and the JSON summary `wisp inspect` prints.
#pragma once

#include "assets/mesh.h"

#include <glm/glm.hpp>
#include <nlohmann/json_fwd.hpp>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace wisp {

enum class HairFormat { Tfx2, Tfx3, Tfx4, CyHair };

// "tfx2" | "tfx3" | "tfx4" | "cyhair"
const char* formatName(HairFormat format);

struct HairStrand {
    std::vector<glm::vec3> points; // root first, file units, as stored (no axis fixes applied)
    uint32_t pinnedRoot = 1;       // leading vertices that are immovable (>= 1)
    bool pinnedTip = false;        // tfx2/tfx3 bothEndsImmovable
};

struct HairAsset {
    HairFormat format = HairFormat::Tfx4;
    std::filesystem::path source;
    std::vector<HairStrand> strands;
    bool zUp = false;       // cyHair files are z-up (FORMATS.md)
    bool mirroredZ = false; // TressFX 3 files are left-handed: z mirrored against their meshes

    size_t totalVertices() const; // sum over strands, as in the file
    uint32_t minVertices() const; // 0 when there are no strands
    uint32_t maxVertices() const;
    Bounds bounds() const; // of every point; zero bounds when there are none
};

// Reads a hair file, telling the format by content: "HAIR" magic -> cyHair; text starting with a
// TressFX 2 header key -> tfx2; a leading float 3.0 / 4.0 -> tfx3 / tfx4. Sizes and counts are
// checked against the file length before anything is read. Throws UserError naming the file and
// the byte offset (binary) or line (text) for a missing, unrecognised, truncated or malformed file.
// tfx2 scale / rotation (degrees, R = Rz * Ry * Rx) / translation headers are applied as
// p' = R * (scale * p) + translation.
HairAsset loadHairAsset(const std::filesystem::path& path);
// The same from a file's bytes already in memory (the fuzz targets use it); `source` names the
// data in errors and becomes HairAsset::source.
HairAsset parseHairAsset(const std::string& data, const std::filesystem::path& source);

// `count` points (>= 2, else std::invalid_argument) evenly spaced by arc length along the polyline,
// the first and last points preserved exactly. A polyline of zero length gives `count` copies of
// its first point.
std::vector<glm::vec3> resampleStrand(const std::vector<glm::vec3>& points, uint32_t count);

// Placing an asset on a head: scale, then axis fixes (mirrorZ in the file's frame, then z-up to
// y-up as a rotation of -90 degrees about x: (x, y, z) -> (x, z, -y)), then a half turn about the
// up axis when asked ((x, y, z) -> (-x, y, -z): the groom's front to the back), then offset.
struct HairPlacement {
    float scale = 1.0f;
    glm::vec3 offset{0.0f};
    bool zUpToYUp = false;
    bool mirrorZ = false;
    bool halfTurn = false;
};

// Bounding-box diagonals of asset and head whose ratio lies outside this range are taken to be in
// different units.
inline constexpr float kSameUnitsMinRatio = 0.2f;
inline constexpr float kSameUnitsMaxRatio = 5.0f;

// zUpToYUp for z-up assets, mirrorZ for left-handed ones, and where units clearly differ (diagonal
// ratio outside [kSameUnitsMinRatio, kSameUnitsMaxRatio]) the power-of-ten scale that brings the
// diagonals closest; offset 0.
HairPlacement autoPlacement(const HairAsset& asset, const Bounds& headBounds);
glm::vec3 applyPlacement(const HairPlacement& placement, glm::vec3 point);

// Arc length of a polyline (0 for one point).
float strandLength(const std::vector<glm::vec3>& points);

// Strands too short to simulate in floats: resampled to V vertices, their segments would be
// shorter than kMinSegmentFraction of the head's bounding-box diagonal (about 0.6 mm on a bust),
// where rounding is a large part of a segment (measured: a fur groom with 278 such strands of
// 48,113 reset 100 times and stretched 0.92 in 50 steps). Wisp keeps them rigid: they follow the
// head and are drawn, but not simulated. Strands of no length at all are dropped.
inline constexpr float kMinSegmentFraction = 1e-3f;
inline float shortStrandLength(float headDiagonal, uint32_t verticesPerStrand)
{
    return kMinSegmentFraction * headDiagonal * float(verticesPerStrand - 1);
}

// `wisp inspect FILE` for hair: {"kind":"hair","format":"tfx4","strands":N,"vertices":N,
// "vertices_per_strand":[min,max],"bbox":[[x,y,z],[x,y,z]]}
nlohmann::json describeHairAsset(const HairAsset& asset);

} // namespace wisp
