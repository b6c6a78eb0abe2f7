// physics/cpu_solver.cpp: the reference solver. integrateStrand walks each strand with the
// shared algorithm (shaders/shared/sim_strand.h, as sim_integrate.comp does) in the CPU's
// strand-major order; the grid functions mirror the GPU's splat (sim_integrate.comp), its zeroed
// sums and grid_gather.comp (which takes each node's velocity as it reads it) over the
// shared grid math (shaders/shared/sim.h, and sim_grid.h for the gather's update).
#include "physics/cpu_solver.h"

#include <vector>

namespace gpu {

// The strand's vertices as sim_strand.h reaches them: strand-major, vertex i at base + i.
struct StrandRef {
    std::vector<vec4>* positions;
    std::vector<vec4>* velocities;
    const std::vector<RestVertex>* rest;
    uint base;
};
inline vec3 strandPosition(const StrandRef& s, uint i)
{
    return vec3((*s.positions)[s.base + i]);
}
inline vec3 strandVelocity(const StrandRef& s, uint i)
{
    return vec3((*s.velocities)[s.base + i]);
}
inline void strandSetVertex(const StrandRef& s, uint i, vec3 p, vec3 v)
{
    (*s.velocities)[s.base + i] = vec4(v, 0.0f);
    (*s.positions)[s.base + i] = vec4(p, (*s.positions)[s.base + i].w);
}
inline float strandRestLength(const StrandRef& s, uint i)
{
    return (*s.rest)[s.base + i].segmentLength;
}

// The normalized grid as sim_grid.h reaches it: the node velocities, a node's density in w.
struct GridRef {
    const std::vector<vec4>* velocity;
    uint resolution;
};
inline float gridNodeDensity(const GridRef& grid, ivec3 node)
{
    return (*grid.velocity)[gridIndex(node, grid.resolution)].w;
}

} // namespace gpu

#include "shaders/shared/sim_grid.h"
#include "shaders/shared/sim_strand.h"

#include <algorithm>

namespace wisp {

using namespace gpu;

std::vector<RestVertex> restVertices(const StrandSet& strands)
{
    std::vector<RestVertex> out(strands.vertexCount());
    uint32_t V = strands.verticesPerStrand;
    for (size_t g = 0; g < out.size(); ++g) {
        out[g].position = strands.rest[g];
        out[g].segmentLength = g % V == 0 ? 0.0f : glm::length(strands.rest[g] - strands.rest[g - 1]);
    }
    return out;
}

CpuSolver::CpuSolver(const StrandSet& strands, const SimSetup& setup, const glm::mat4& headTransform)
    : strands_(strands), setup_(setup), rest_(restVertices(strands)), state_(initialState(strands, headTransform)),
      sdf_(setup.sdf ? buildMeshSdf(*setup.sdf) : MeshSdf{}), grid_(setup.params.gridNodeCount),
      gridVelocity_(setup.params.gridNodeCount), reached_(setup.params.gridNodeCount)
{
}

void CpuSolver::step(const SimStep& first)
{
    SimStep sub = first;
    for (uint32_t k = 0; k < setup_.substeps; ++k) {
        sub.time = first.time + float(k) * setup_.params.dt;
        for (uint32_t s = 0; s < setup_.params.strandCount; ++s)
            integrateStrand(s, sub);
    }
    gridClear();
    gridSplat(first);
    gridNormalize();
    gridGather(first);
}

void CpuSolver::integrateStrand(uint32_t s, const SimStep& step)
{
    const SimParams& params = setup_.params;
    [[maybe_unused]] const float* sdfField = sdf_.values.data();
    std::vector<vec4>& positions = state_.positions;
    std::vector<vec4>& velocities = state_.velocities;
    std::vector<vec4>& tangents = state_.tangents;
    uint32_t V = params.verticesPerStrand;
    uint32_t base = s * V; // strand-major: vertex i is at base + i
    auto write = [&](uint32_t g, const WalkedVertex& v) {
        positions[g] = vec4(v.position, positions[g].w);
        velocities[g] = vec4(v.velocity, 0.0f);
        tangents[g] = vec4(v.tangent, 0.0f);
    };
    StrandWalk walk = strandWalkBegin(params, step, sdfField, strands_.strands[s], vec3(positions[base]),
                                      rest_[base].position, step.time);
    for (uint32_t i = 1; i < V; ++i) {
        uint32_t g = base + i;
        write(g - 1, strandWalkStep(params, step, sdfField, walk, i, V, vec3(positions[g]), vec3(velocities[g]),
                                    rest_[g], rest_[g - 1].position));
    }
    write(base + V - 1, strandWalkTip(params, step, sdfField, walk));
    if (pinnedAtBothEnds(strands_.strands[s], V)) {
        strandBend(params, step, sdfField, StrandRef{&positions, &velocities, &rest_, base}, strands_.strands[s], V,
                   walk.finite);
        for (uint32_t i = 0; i < V; ++i) {
            uint32_t j = std::min(i + 1u, V - 1u);
            tangents[base + i] = vec4(normalize(vec3(positions[base + j]) - vec3(positions[base + j - 1u])), 0.0f);
        }
    }

    if (!walk.finite) {
        for (uint32_t i = 0; i < V; ++i) {
            uint32_t j = base + std::min(i + 1u, V - 1u); // the segment ending at vertex j
            write(base + i, restVertex(params, step, sdfField, rest_[base + i].position, rest_[j - 1].position,
                                       rest_[j].position));
        }
        state_.nonfiniteResets += 1;
    }
}

// Only the nodes the last splat reached hold anything: clearing and normalizing them alone is the
// kernels' result over every node (the others stay zero), at the cost of the hair's vertices
// rather than the grid's nodes (256³ nodes are 16.7 million).
void CpuSolver::gridClear()
{
    for (uint32_t n : touched_) {
        grid_[n] = GridNode{vec3(0.0f), 0.0f};
        gridVelocity_[n] = vec4(0.0f);
        reached_[n] = 0;
    }
    touched_.clear();
}

void CpuSolver::gridSplat(const SimStep& step)
{
    const SimParams& params = setup_.params;
    [[maybe_unused]] const float* sdfField = sdf_.values.data();
    for (size_t g = 0; g < state_.positions.size(); ++g) {
        GridCell cell = gridCell(vec3(state_.positions[g]), step.gridOrigin, params.gridCellSize);
        if (!cellInside(cell.base, params.gridResolution))
            continue;
        vec3 v = clampSpeed(vec3(state_.velocities[g]), params.gridMaxSplatSpeed);
        for (uint32_t k = 0; k < 8; ++k) {
            float w = cornerWeight(cell.frac, k);
            uint32_t n = gridIndex(cell.base + cornerOffset(k), params.gridResolution);
            if (!reached_[n]) {
                reached_[n] = 1;
                touched_.push_back(n);
            }
            grid_[n].density += w;
            grid_[n].momentum += w * v;
        }
    }
}

void CpuSolver::gridNormalize()
{
    for (uint32_t n : touched_) {
        const GridNode& node = grid_[n];
        vec3 velocity = node.density > kGridMinDensity ? node.momentum / node.density : vec3(0.0f);
        gridVelocity_[n] = vec4(velocity, node.density);
    }
}

void CpuSolver::gridGather(const SimStep& step)
{
    const SimParams& params = setup_.params;
    [[maybe_unused]] const float* sdfField = sdf_.values.data();
    for (size_t g = 0; g < state_.positions.size(); ++g) {
        if (state_.positions[g].w == 0.0f)
            continue;
        GridCell cell = gridCell(vec3(state_.positions[g]), step.gridOrigin, params.gridCellSize);
        if (!cellInside(cell.base, params.gridResolution))
            continue;
        GridSample gs = gridSampleZero();
        for (uint32_t k = 0; k < 8; ++k) {
            vec4 node = gridVelocity_[gridIndex(cell.base + cornerOffset(k), params.gridResolution)];
            gs = gridAccumulate(gs, cell.frac, k, vec3(node), node.w);
        }
        vec3 v = gridGatherVelocity(params, step, sdfField, GridRef{&gridVelocity_, params.gridResolution}, cell,
                                    vec3(state_.positions[g]), vec3(state_.velocities[g]), gs);
        state_.velocities[g] = vec4(v, 0.0f);
    }
}

} // namespace wisp
