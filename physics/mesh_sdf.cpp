// physics/mesh_sdf.cpp: the field's plan (grid, pseudonormals, work items) and its CPU build, the
// twin of mesh_sdf_splat.comp and mesh_sdf_sign.comp.
#include "physics/mesh_sdf.h"

#include "assets/signed_distance.h"
#include "core/error.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace wisp {

SdfPlan planMeshSdf(const Mesh& mesh, uint32_t resolution, float minBand)
{
    SdfPlan plan;
    size_t triangles = mesh.triangleCount();
    if (triangles > (size_t(1) << kSdfMaxTriangleBits))
        throw UserError("the head's mesh has " + std::to_string(triangles) +
                        " triangles: its distance field takes at most " +
                        std::to_string(size_t(1) << kSdfMaxTriangleBits));
    uint32_t bits = 1;
    while ((size_t(1) << bits) < triangles)
        ++bits;
    Bounds b = mesh.bounds();
    glm::vec3 size = b.size();
    float longest = std::max({size.x, size.y, size.z});
    float cell = longest / float(std::max(resolution, 1u));
    float band = std::max(float(gpu::kSdfBandCells) * cell, minBand);
    float margin = band + 2.0f * cell;
    glm::vec3 origin = b.min - glm::vec3(margin);
    glm::uvec3 dims = glm::uvec3(glm::ceil((size + glm::vec3(2.0f * margin)) / cell)) + glm::uvec3(1u);
    plan.grid.origin = glm::vec4(origin, cell);
    plan.grid.dims = glm::uvec4(dims, bits);
    plan.grid.band = glm::vec4(band, 0.0f, 0.0f, 0.0f);
    plan.triangles = sdfTriangles(mesh);

    glm::ivec3 top = glm::ivec3(dims) - glm::ivec3(1);
    for (uint32_t t = 0; t < triangles; ++t) {
        const gpu::SdfTriangle& tri = plan.triangles[t];
        glm::vec3 lo = glm::min(glm::min(glm::vec3(tri.a), glm::vec3(tri.b)), glm::vec3(tri.c)) - glm::vec3(band);
        glm::vec3 hi = glm::max(glm::max(glm::vec3(tri.a), glm::vec3(tri.b)), glm::vec3(tri.c)) + glm::vec3(band);
        glm::ivec3 n0 = glm::clamp(glm::ivec3(glm::ceil((lo - origin) / cell)), glm::ivec3(0), top);
        glm::ivec3 n1 = glm::clamp(glm::ivec3(glm::floor((hi - origin) / cell)), glm::ivec3(0), top);
        if (glm::any(glm::lessThan(n1, n0)))
            continue;
        // Slabs of whole planes of the box along z, or strips of rows along y when a plane is too many.
        uint32_t nx = uint32_t(n1.x - n0.x + 1), ny = uint32_t(n1.y - n0.y + 1);
        uint32_t rows = std::max(1u, gpu::kSdfMaxItemNodes / nx);
        auto pack = [](int a, int c) { return uint32_t(a) | (uint32_t(c) << 16); };
        if (nx * ny <= gpu::kSdfMaxItemNodes) {
            int planes = int(std::max(1u, gpu::kSdfMaxItemNodes / (nx * ny)));
            for (int z = n0.z; z <= n1.z; z += planes)
                plan.items.push_back({t, pack(n0.x, n1.x), pack(n0.y, n1.y), pack(z, std::min(n1.z, z + planes - 1))});
        } else {
            for (int z = n0.z; z <= n1.z; ++z)
                for (int y = n0.y; y <= n1.y; y += int(rows))
                    plan.items.push_back({t, pack(n0.x, n1.x), pack(y, std::min(n1.y, y + int(rows) - 1)), pack(z, z)});
        }
    }
    plan.grid.counts = glm::uvec4(uint32_t(plan.items.size()), 0u, 0u, 0u);
    return plan;
}

MeshSdf buildMeshSdf(const SdfPlan& plan)
{
    const gpu::SdfGrid& g = plan.grid;
    std::vector<uint32_t> keys(plan.nodeCount(), gpu::kSdfNoKey);
    // mesh_sdf_splat.comp
    for (const glm::uvec4& item : plan.items) {
        const gpu::SdfTriangle& t = plan.triangles[item.x];
        glm::uvec3 lo = gpu::sdfItemLow(item), hi = gpu::sdfItemHigh(item);
        for (uint32_t z = lo.z; z <= hi.z; ++z)
            for (uint32_t y = lo.y; y <= hi.y; ++y)
                for (uint32_t x = lo.x; x <= hi.x; ++x) {
                    glm::uvec3 node(x, y, z);
                    uint32_t key = gpu::sdfSplatKey(g, t, item.x, node);
                    uint32_t& k = keys[gpu::sdfNodeIndex(g, node)];
                    k = std::min(k, key);
                }
    }
    // mesh_sdf_sign.comp
    MeshSdf out;
    out.grid = g;
    out.values.resize(plan.nodeCount());
    for (size_t row = 0; row < plan.rowCount(); ++row) {
        uint32_t y = uint32_t(row % g.dims.y), z = uint32_t(row / g.dims.y);
        float sign = 1.0f;
        for (uint32_t x = 0; x < g.dims.x; ++x) {
            glm::uvec3 node(x, y, z);
            uint32_t key = keys[gpu::sdfNodeIndex(g, node)];
            if (key == gpu::kSdfNoKey)
                continue;
            sign = gpu::sdfBandValue(g, plan.triangles[gpu::sdfKeyTriangle(g, key)], node) < 0.0f ? -1.0f : 1.0f;
            break;
        }
        for (uint32_t x = 0; x < g.dims.x; ++x) {
            glm::uvec3 node(x, y, z);
            uint32_t index = gpu::sdfNodeIndex(g, node);
            uint32_t key = keys[index];
            if (key == gpu::kSdfNoKey) {
                out.values[index] = sign * g.band.x;
                continue;
            }
            float d = gpu::sdfBandValue(g, plan.triangles[gpu::sdfKeyTriangle(g, key)], node);
            sign = d < 0.0f ? -1.0f : 1.0f;
            out.values[index] = d;
        }
    }
    return out;
}

} // namespace wisp
