// tests/test_mesh_sdf.cpp: the mesh's signed distance field built on the CPU (physics/mesh_sdf.h,
// the twin of the GPU kernels) against the exact signed distance (assets/signed_distance.h) on a
// sphere and a box placed off the origin: every node within the band holds the exact value,
// every node past it +-band with the exact sign; trilinear samples and the gradient between nodes;
// a plate thinner than a cell; the plan's work items bounded and covering each triangle's box.
#include "assets/signed_distance.h"
#include "core/error.h"
#include "physics/mesh_sdf.h"
#include "sdf_meshes.h"
#include "shaders/shared/sim.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace wisp;

namespace {

// Every node of `field` against the exact distance to `mesh`; returns the nodes within the band.
size_t expectNodesExact(const Mesh& mesh, const MeshSdf& field)
{
    MeshSignedDistance exact(mesh);
    const gpu::SdfGrid& g = field.grid;
    float band = g.band.x;
    // A key's distance quantum: the chosen triangle is at most this much farther than the nearest.
    float quantum = band / float((1u << (32u - g.dims.w)) - 2u);
    float tolerance = 2.0f * quantum + 1e-6f * band;
    size_t within = 0, failures = 0;
    for (uint32_t z = 0; z < g.dims.z; ++z)
        for (uint32_t y = 0; y < g.dims.y; ++y)
            for (uint32_t x = 0; x < g.dims.x; ++x) {
                glm::uvec3 n(x, y, z);
                float e = exact(gpu::sdfNodePosition(g, n));
                float v = field.values[gpu::sdfNodeIndex(g, n)];
                bool ok = true;
                if (std::abs(e) < band * 0.999f) {
                    ++within;
                    ok = std::abs(v - e) <= tolerance;
                } else if (std::abs(e) > band * 1.001f) {
                    ok = v == (e < 0.0f ? -band : band);
                }
                if (!ok && ++failures <= 5) {
                    ADD_FAILURE() << "node " << x << "," << y << "," << z << ": field " << v << ", exact " << e;
                }
            }
    EXPECT_EQ(failures, 0u);
    return within;
}

} // namespace

TEST(MeshSdf, TwinHoldsTheExactDistanceOnASphere)
{
    Mesh sphere = test::sdfSphereMesh(0.1f, glm::vec3(0.02f, 1.3f, -0.05f), 24, 48);
    SdfPlan plan = planMeshSdf(sphere, 37);
    EXPECT_EQ(plan.grid.dims.w, 12u) << "2,304 triangles take 12 bits";
    MeshSdf field = buildMeshSdf(plan);
    EXPECT_GT(expectNodesExact(sphere, field), 1000u);
    // Deep inside and far outside, +-band.
    EXPECT_EQ(field.sample(glm::vec3(0.02f, 1.3f, -0.05f)), -plan.grid.band.x);
    EXPECT_EQ(field.sample(glm::vec3(0.02f, 1.3f, -0.05f) + glm::vec3(0.0f, 0.0f, 0.11f) + plan.grid.band.x),
              plan.grid.band.x);
}

TEST(MeshSdf, TwinHoldsTheExactDistanceOnABox)
{
    // 12 large triangles: each one's box is split into many work items.
    glm::vec3 h(0.3f, 0.5f, 0.2f), c(0.1f, -0.2f, 0.05f);
    Mesh box = test::sdfBoxMesh(h, c);
    SdfPlan plan = planMeshSdf(box, 53);
    EXPECT_GT(plan.items.size(), 12u * 3u);
    MeshSdf field = buildMeshSdf(plan);
    EXPECT_GT(expectNodesExact(box, field), 5000u);
}

TEST(MeshSdf, SamplesAndGradientBetweenNodes)
{
    glm::vec3 c(0.02f, 1.3f, -0.05f);
    float r = 0.1f;
    Mesh sphere = test::sdfSphereMesh(r, c, 32, 64);
    MeshSdf field = buildMeshSdf(planMeshSdf(sphere, 48));
    MeshSignedDistance exact(sphere);
    float cell = field.grid.origin.w, band = field.grid.band.x;
    uint32_t state = 3;
    int tested = 0;
    for (int k = 0; k < 4000; ++k) {
        // Near the surface: a direction, and a distance within the band either side.
        float u = gpu::hashToUnit(state++), v = gpu::hashToUnit(state++), w = gpu::hashToUnit(state++);
        glm::vec3 dir = glm::vec3(u, v, w) - glm::vec3(0.5f);
        if (glm::length(dir) < 0.05f)
            continue;
        glm::vec3 p = c + (r + (gpu::hashToUnit(state++) - 0.5f) * 2.0f * band) * glm::normalize(dir);
        MeshSignedDistance::Result e = exact.query(p);
        if (std::abs(e.distance) > band - 2.0f * cell)
            continue;
        ++tested;
        EXPECT_NEAR(field.sample(p), e.distance, 0.1f * cell);
        glm::vec3 normal = (p - e.point) / e.distance; // outward, both sides
        glm::vec3 g = field.gradient(p);
        EXPECT_GT(glm::dot(glm::normalize(g), normal), 0.95f);
        EXPECT_NEAR(glm::length(g), 1.0f, 0.1f);
    }
    EXPECT_GT(tested, 500);
    // Outside the grid the field says nothing: +band, no gradient.
    glm::vec3 far = c + glm::vec3(10.0f * r);
    EXPECT_EQ(field.sample(far), band);
    EXPECT_EQ(field.gradient(far), glm::vec3(0.0f));
}

TEST(MeshSdf, PlateThinnerThanACellHasTwoOutsides)
{
    // 2 mm thick, cells of 1 cm: no node inside it; both sides outside, every node past the band +band.
    glm::vec3 h(0.5f, 0.001f, 0.5f);
    Mesh plate = test::sdfBoxMesh(h);
    MeshSdf field = buildMeshSdf(planMeshSdf(plate, 100));
    for (float v : field.values)
        EXPECT_GE(v, -0.001f);
    EXPECT_GT(field.sample(glm::vec3(0.1f, 0.02f, 0.2f)), 0.015f);
    EXPECT_GT(field.sample(glm::vec3(0.1f, -0.02f, 0.2f)), 0.015f);
}

TEST(MeshSdf, PlanKeepsWorkItemsBoundedAndCoversEachTrianglesBox)
{
    Mesh box = test::sdfBoxMesh(glm::vec3(0.3f, 0.5f, 0.2f));
    SdfPlan plan = planMeshSdf(box, 200);
    std::vector<size_t> nodes(box.triangleCount(), 0);
    for (const glm::uvec4& item : plan.items) {
        glm::uvec3 lo = gpu::sdfItemLow(item), hi = gpu::sdfItemHigh(item);
        ASSERT_TRUE(glm::all(glm::lessThanEqual(lo, hi)));
        ASSERT_TRUE(glm::all(glm::lessThan(hi, glm::uvec3(plan.grid.dims))));
        size_t n = size_t(hi.x - lo.x + 1) * (hi.y - lo.y + 1) * (hi.z - lo.z + 1);
        EXPECT_LE(n, gpu::kSdfMaxItemNodes);
        nodes[item.x] += n;
    }
    // Each triangle's items hold its box grown by the band: the nodes from the first at or past its
    // lower corner to the last at or before its upper one.
    const gpu::SdfGrid& g = plan.grid;
    glm::vec3 origin(g.origin);
    float cell = g.origin.w, band = g.band.x;
    for (size_t t = 0; t < box.triangleCount(); ++t) {
        glm::vec3 lo(INFINITY), hi(-INFINITY);
        for (int k = 0; k < 3; ++k) {
            lo = glm::min(lo, box.positions[box.indices[3 * t + size_t(k)]]);
            hi = glm::max(hi, box.positions[box.indices[3 * t + size_t(k)]]);
        }
        glm::vec3 first = glm::ceil((lo - band - origin) / cell), last = glm::floor((hi + band - origin) / cell);
        glm::vec3 count = last - first + 1.0f;
        EXPECT_EQ(double(nodes[t]), double(count.x) * double(count.y) * double(count.z)) << t;
    }
    EXPECT_EQ(plan.grid.counts.x, plan.items.size());
}
