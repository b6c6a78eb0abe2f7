// assets/signed_distance.h: the exact signed distance to a head's mesh, in the head's own units,
// negative inside. The closest point comes from MeshDistance's hierarchy; the sign from the
// angle-weighted pseudonormal of the feature (face, edge or vertex) holding it
// (shaders/shared/mesh_sdf.h). Vertices within a millionth of the mesh's diagonal are welded
// first, so a mesh split at its normals' seams is one surface, and a triangle with two corners
// welded together (a pole's sliver) has no normal. An open mesh (a scan cut at the neck, a bust cut at the chest)
// reads as if its body went on past the cut: below the opening is inside, beside it outside. A
// part inside another (eyes, teeth in a head) has its own outside, which lies inside the head.
#pragma once

#include "assets/mesh.h"
#include "assets/placement.h"
#include "shaders/shared/mesh_sdf.h"

#include <vector>

namespace wisp {

class MeshSignedDistance {
public:
    // `mesh` must outlive this object.
    explicit MeshSignedDistance(const Mesh& mesh);
    struct Result {
        float distance = 0.0f; // signed: negative inside
        glm::vec3 point{0.0f}; // the closest point on the surface
        uint32_t triangle = 0;
    };
    Result query(glm::vec3 p) const;
    float operator()(glm::vec3 p) const { return query(p).distance; }
    // Every triangle with its features' pseudonormals, in the mesh's order (what the GPU field reads).
    const std::vector<gpu::SdfTriangle>& triangles() const { return triangles_; }

private:
    MeshDistance closest_;
    std::vector<gpu::SdfTriangle> triangles_;
};

// Every triangle of `mesh` with the pseudonormals of its features (vertices welded by position).
std::vector<gpu::SdfTriangle> sdfTriangles(const Mesh& mesh);

} // namespace wisp
