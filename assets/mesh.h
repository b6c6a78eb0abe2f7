// assets/mesh.h: a triangle mesh as Wisp uses it (head, body, colliders): positions and unit
// normals per vertex, 32-bit triangle indices, in the file's own units. Loads .obj through
// tinyobjloader (checked line by line first, so errors name the line) and every other format
// through assimp; n-gons are triangulated and missing normals generated.
#pragma once

#include "core/bounds.h"

#include <glm/glm.hpp>

#include <cstdint>
#include <filesystem>
#include <iosfwd>
#include <string>
#include <vector>

namespace wisp {

struct Mesh {
    std::vector<glm::vec3> positions;
    std::vector<glm::vec3> normals; // same count as positions, unit length
    std::vector<uint32_t> indices;  // three per triangle, counter-clockwise seen from outside
    size_t sourceVertices = 0;      // distinct positions in the file (before splitting by normal)

    size_t triangleCount() const { return indices.size() / 3; }
    Bounds bounds() const;
};

// Throws UserError naming the file (and line, for .obj) when it is missing, unreadable,
// malformed, binary where text is expected (a NUL byte before the padding at its end), has a
// position past kMaxCoordinate (assets/text.h), or holds no triangles or only triangles of no
// area. Normals missing or zero are area-weighted averages of the triangles' normals.
Mesh loadMesh(const std::filesystem::path& path);
// Throws UserError naming `path` when no triangle of `mesh` has an area (all vertices at one
// point or on one line): nothing can be framed, fitted or grown on it.
void checkNotDegenerate(const Mesh& mesh, const std::filesystem::path& path);
// An OBJ file's text from a stream, as loadMesh reads a .obj file (lines ended by LF, CRLF or CR;
// trailing NULs and white space are padding); `source` names it in errors. The fuzz target uses it.
Mesh parseObj(std::istream& in, const std::filesystem::path& source);

// A unit sphere around the origin (latitude-longitude: `stacks` x `slices` quads), for the
// collision sphere and the light's marker.
Mesh makeSphereMesh(uint32_t stacks = 24, uint32_t slices = 48);

// Area-weighted vertex normals from the triangles (used when a file has none).
std::vector<glm::vec3> computeVertexNormals(const std::vector<glm::vec3>& positions,
                                            const std::vector<uint32_t>& indices);

} // namespace wisp
