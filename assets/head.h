// assets/head.h: a head as Wisp uses it: the mesh plus its description (models/head.json):
// units, orientation, the scalp region rule and the collision ellipsoids. `--head` takes either
// a description (.json, which names its mesh) or a bare mesh file.
#pragma once

#include "assets/mesh.h"

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace wisp {

struct Ellipsoid {
    std::string name;
    glm::vec3 center{0.0f};      // asset units
    glm::vec3 radii{1.0f};       // asset units, > 0
    glm::vec3 rotationDeg{0.0f}; // XYZ Euler angles in degrees, applied as R = Rz * Ry * Rx
    bool operator==(const Ellipsoid&) const = default;
};

// Which triangles grow hair: centroid above the plane (dot(c - planePoint, planeNormal) > 0),
// excluding the face: triangles whose normal points along faceDirection more than faceMaxDot.
struct ScalpRule {
    glm::vec3 planePoint{0.0f};
    glm::vec3 planeNormal{0.0f, 1.0f, 0.0f};
    glm::vec3 faceDirection{0.0f, 0.0f, 1.0f};
    float faceMaxDot = 0.35f;
};

struct HeadDescription {
    std::string name;
    std::filesystem::path meshPath; // resolved against the description's folder
    std::string units = "m";
    glm::vec3 up{0.0f, 1.0f, 0.0f};
    glm::vec3 front{0.0f, 0.0f, 1.0f};
    std::optional<ScalpRule> scalp; // absent for a bare mesh
    std::vector<Ellipsoid> colliders;
};

struct Head {
    HeadDescription description;
    Mesh mesh;
};

// Parses a head description; throws UserError naming the file and the offending key or byte.
HeadDescription loadHeadDescription(const std::filesystem::path& path);
// A .json description with its mesh, or a bare mesh file (no scalp rule, no colliders).
Head loadHead(const std::filesystem::path& path);
// Indices of the triangles the rule selects as scalp.
std::vector<uint32_t> scalpTriangles(const Mesh& mesh, const ScalpRule& rule);
// models/head.json beside the executable's install or in the source tree.
std::filesystem::path defaultHeadPath();

} // namespace wisp
