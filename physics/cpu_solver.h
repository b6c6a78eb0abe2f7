// physics/cpu_solver.h: the CPU reference solver: the same steps as the compute kernels
// (shaders/sim_integrate.comp, grid_*.comp), over the same shared algorithm and math
// (shaders/shared/sim_strand.h, sim.h), in plain C++. Tests run both on the same input and compare; it is also a
// readable statement of the algorithm. Single-threaded and meant for small workloads.
#pragma once

#include "physics/mesh_sdf.h"
#include "physics/simulation.h"

#include <cstdint>
#include <vector>

namespace wisp {

class CpuSolver {
public:
    CpuSolver(const StrandSet& strands, const SimSetup& setup, const glm::mat4& headTransform);

    // One fixed step: `substeps` integrate/FTL passes, then the hair-hair grid.
    // `step.time` is the time at the step's start.
    void step(const gpu::SimStep& step);

    const SimState& state() const { return state_; }
    SimState& state() { return state_; }
    // The grid accumulators after the last step's splat (density, momentum), for tests.
    const std::vector<gpu::GridNode>& grid() const { return grid_; }

private:
    void integrateStrand(uint32_t s, const gpu::SimStep& step);
    void gridClear();
    void gridSplat(const gpu::SimStep& step);
    void gridNormalize();
    void gridGather(const gpu::SimStep& step);

    const StrandSet& strands_;
    const SimSetup& setup_;
    std::vector<gpu::RestVertex> rest_;
    SimState state_;
    MeshSdf sdf_; // the head mesh's field, built by the GPU kernels' twin (empty: none)
    std::vector<gpu::GridNode> grid_;
    std::vector<glm::vec4> gridVelocity_;
    std::vector<uint8_t> reached_;  // 1: the node is in touched_
    std::vector<uint32_t> touched_; // the nodes the last splat reached
};

// Rest vertices as the GPU stores them (position + segment length).
std::vector<gpu::RestVertex> restVertices(const StrandSet& strands);

} // namespace wisp
