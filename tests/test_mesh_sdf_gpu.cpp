// tests/test_mesh_sdf_gpu.cpp: the mesh's signed distance field built by the GPU kernels
// (physics/gpu_mesh_sdf.h) against their CPU twin (physics/mesh_sdf.h), node for node, at awkward
// sizes (grids of odd node counts, work items not a multiple of the group, a box's large triangles
// split into many items); and the build's time on Sintel's bust, said (skipped without the data).
#include "assets/mesh.h"
#include "physics/gpu_mesh_sdf.h"
#include "sdf_meshes.h"
#include "test_support.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>

using namespace wisp;

namespace {

// The GPU's field against the twin's: each node within a key's distance quantum (the two may pick
// different triangles at a near tie, each at most a quantum farther than the nearest) and of the
// same sign wherever either lies farther than that from the surface.
void expectSameField(const MeshSdf& gpuField, const MeshSdf& cpuField)
{
    ASSERT_EQ(gpuField.values.size(), cpuField.values.size());
    const gpu::SdfGrid& g = cpuField.grid;
    float quantum = g.band.x / float((1u << (32u - g.dims.w)) - 2u);
    float tolerance = 2.0f * quantum + 1e-6f * g.band.x;
    size_t failures = 0, inside = 0;
    for (size_t i = 0; i < cpuField.values.size(); ++i) {
        float a = gpuField.values[i], b = cpuField.values[i];
        inside += b < 0.0f;
        if (std::abs(a - b) > tolerance && ++failures <= 5) {
            ADD_FAILURE() << "node " << i << ": GPU " << a << ", CPU " << b;
        }
    }
    EXPECT_EQ(failures, 0u);
    EXPECT_GT(inside, 0u);
}

} // namespace

TEST(GpuMeshSdf, MatchesItsCpuTwinAtAwkwardSizes)
{
    vk::Context ctx(test::validatedOptions());
    struct Case {
        Mesh mesh;
        uint32_t resolution;
    };
    Case cases[] = {
        {test::sdfSphereMesh(0.1f, glm::vec3(0.02f, 1.3f, -0.05f), 13, 29), 37},
        {test::sdfSphereMesh(3.0f, glm::vec3(-5.0f, 0.5f, 2.0f), 24, 48), 61}, // another unit
        {test::sdfBoxMesh(glm::vec3(0.3f, 0.5f, 0.2f), glm::vec3(0.1f, -0.2f, 0.05f)), 45},
        {test::sdfBoxMesh(glm::vec3(0.3f, 0.5f, 0.2f), glm::vec3(0.0f), true), 19}, // open at its bottom
    };
    size_t partialGroups = 0;
    for (const Case& c : cases) {
        SdfPlan plan = planMeshSdf(c.mesh, c.resolution);
        partialGroups += plan.items.size() % gpu::kSdfGroupSize != 0;
        GpuMeshSdf field(ctx, plan);
        expectSameField(field.read(), buildMeshSdf(plan));
        EXPECT_GT(field.buildMs(), 0.0);
    }
    EXPECT_GE(partialGroups, 3u) << "work items that end inside a group";
    EXPECT_EQ(ctx.validationMessages(), 0u);
}

TEST(GpuMeshSdf, SintelsBustBuildsLikeItsTwin)
{
    std::filesystem::path path = WISP_SHARED_DATA "/sintel/sintel.obj";
    if (!std::filesystem::exists(path))
        GTEST_SKIP() << "Sintel's bust is not in the shared data (" << path << ")";
    vk::Context ctx(test::validatedOptions());
    Mesh mesh = loadMesh(path);
    SdfPlan plan = planMeshSdf(mesh, kSdfResolutionTypical);
    GpuMeshSdf field(ctx, plan);
    expectSameField(field.read(), buildMeshSdf(plan));
    std::printf("sdf build: %zu triangles, %u x %u x %u nodes, %zu work items: %.1f ms on %s\n", mesh.triangleCount(),
                plan.grid.dims.x, plan.grid.dims.y, plan.grid.dims.z, plan.items.size(), field.buildMs(),
                ctx.report().name.c_str());
    EXPECT_EQ(ctx.validationMessages(), 0u);
}
