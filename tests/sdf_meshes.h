// tests/sdf_meshes.h: meshes whose signed distance is known, for the field's tests: a box (its
// mesh is the box) and a latitude-longitude sphere, both placed off the origin.
#pragma once

#include "assets/mesh.h"

#include <glm/glm.hpp>

namespace wisp::test {

// An axis-aligned box of half-extents h around c, 12 triangles counter-clockwise from outside;
// without its bottom (y = -h) face when `open`.
inline Mesh sdfBoxMesh(glm::vec3 h, glm::vec3 c = glm::vec3(0.0f), bool open = false)
{
    Mesh m;
    for (int k = 0; k < 8; ++k)
        m.positions.push_back(c + h * glm::vec3(k & 1 ? 1.0f : -1.0f, k & 2 ? 1.0f : -1.0f, k & 4 ? 1.0f : -1.0f));
    m.normals.assign(8, glm::vec3(0.0f, 1.0f, 0.0f));
    // Quads as corner indices, counter-clockwise seen from outside.
    const uint32_t quads[6][4] = {{0, 4, 6, 2}, {1, 3, 7, 5}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 2, 3, 1}, {4, 5, 7, 6}};
    for (int f = 0; f < 6; ++f) {
        if (open && f == 2) // the y = -h face
            continue;
        const uint32_t* q = quads[f];
        for (uint32_t i : {q[0], q[1], q[2], q[0], q[2], q[3]})
            m.indices.push_back(i);
    }
    m.sourceVertices = 8;
    return m;
}

inline float sdfBoxDistance(glm::vec3 p, glm::vec3 h, glm::vec3 c = glm::vec3(0.0f))
{
    glm::vec3 q = glm::abs(p - c) - h;
    return glm::length(glm::max(q, glm::vec3(0.0f))) + std::min(std::max(q.x, std::max(q.y, q.z)), 0.0f);
}

// makeSphereMesh's sphere of `radius` around `c`.
inline Mesh sdfSphereMesh(float radius, glm::vec3 c, uint32_t stacks, uint32_t slices)
{
    Mesh m = makeSphereMesh(stacks, slices);
    for (glm::vec3& p : m.positions)
        p = c + radius * p;
    return m;
}

} // namespace wisp::test
