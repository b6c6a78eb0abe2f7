// physics/mesh_sdf.h: a head mesh's signed distance field, a narrow band on a grid over the
// mesh's bounds and a margin (shaders/shared/mesh_sdf.h), in the head's units: its plan (the grid,
// the triangles with their pseudonormals, the work items) and its CPU build, the twin of the GPU
// kernels (physics/gpu_mesh_sdf.h). The solver reads it to keep the hair out of the mesh itself.
#pragma once

#include "assets/mesh.h"
#include "shaders/shared/mesh_sdf_sample.h"

#include <cstdint>
#include <vector>

namespace wisp {

// Cells along the mesh's longest extent: the setting's range, and the resolution the tests and
// `--set sdf_resolution=96` use (a cell about 1% of a bust's longest side).
inline constexpr uint32_t kSdfResolutionMin = 16;
inline constexpr uint32_t kSdfResolutionMax = 256;
inline constexpr uint32_t kSdfResolutionTypical = 96;
// The most triangles a field takes (a key's triangle bits).
inline constexpr uint32_t kSdfMaxTriangleBits = 24;

struct SdfPlan {
    gpu::SdfGrid grid{};
    std::vector<gpu::SdfTriangle> triangles;
    std::vector<glm::uvec4> items; // triangle, then its box of nodes packed (sdfItemLow / sdfItemHigh)
    size_t nodeCount() const { return size_t(grid.dims.x) * grid.dims.y * grid.dims.z; }
    size_t rowCount() const { return size_t(grid.dims.y) * grid.dims.z; }
};

// The grid for `mesh` at `resolution` cells along its longest extent (cubic cells), over its bounds
// grown by the band (kSdfBandCells cells, or `minBand` head units if more) and two cells; each triangle's box of nodes
// grown by the band, split into work items of at most gpu::kSdfMaxItemNodes nodes. Throws UserError for a mesh of more
// than 2^kSdfMaxTriangleBits triangles.
SdfPlan planMeshSdf(const Mesh& mesh, uint32_t resolution, float minBand = 0.0f);

// The field: a value per node (head units, negative inside), sampled trilinearly.
struct MeshSdf {
    gpu::SdfGrid grid{};
    std::vector<float> values;
    bool empty() const { return values.empty(); }
    float sample(glm::vec3 p) const { return gpu::sdfSample(values.data(), grid, p); }
    glm::vec3 gradient(glm::vec3 p) const { return gpu::sdfGradient(values.data(), grid, p); }
};

// The CPU twin of the GPU build: the same keys, the same rows.
MeshSdf buildMeshSdf(const SdfPlan& plan);

} // namespace wisp
