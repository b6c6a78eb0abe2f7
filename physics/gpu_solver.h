// physics/gpu_solver.h: the GPU solver's buffers and dispatch sequence. One step records
//   sim_integrate (every substep; the last one also splats into this step's grid sums) |
//   grid_gather (reads them; zeroes the other set, the next step's)
// with a compute->compute barrier after each (a workgroup barrier() does not order work across
// workgroups). Each kernel is a compute stage (gpu/compute_stage.h), one list of what it touches
// from which its descriptors and the frame's declarations (PhysicsPass) come. The two sets of sums take turns, so a
// step needs no clear or normalize pass; the turn flips as each step is recorded, so every recorded step must be
// submitted (reset() starts the turns again). It talks to the device only through gpu/; the model and the maths stay in
// physics/ and shaders/shared/.
#pragma once

#include "gpu/compute_stage.h"
#include "gpu/handle.h"
#include "gpu/pass.h"
#include "gpu/resources.h"
#include "gpu/timestamps.h"
#include "physics/gpu_mesh_sdf.h"
#include "physics/simulation.h"

#include <array>
#include <memory>

namespace wisp {

namespace vk {
class Context;
}

class GpuSolver {
public:
    enum class Stage { Integrate, GridGather };
    static constexpr Stage kStages[] = {Stage::Integrate, Stage::GridGather}; // a step's, in order

    GpuSolver(const vk::Context& ctx, const StrandSet& strands, const SimSetup& setup, const glm::mat4& headTransform);

    // Records one fixed step (all substeps and the grid). step.time is the step's start. With a
    // timer, each kernel's dispatch is a timed scope: integrate (all substeps and the splat) and
    // grid_gather.
    void recordStep(VkCommandBuffer cmd, const gpu::SimStep& step, vk::GpuTimer* timer = nullptr);
    // The sums the next recorded step splats into (0 or 1); takeTurn returns it and flips it, as
    // recordStep does, for a step recorded stage by stage (stage(), layout()).
    uint32_t turn() const { return turn_; }
    uint32_t takeTurn();
    // A stage's timed scope: integrate (all substeps and the splat) or grid_gather.
    static const char* scopeName(Stage stage) { return stage == Stage::Integrate ? "integrate" : "grid_gather"; }
    // What the steps of a frame touch: each stage's list declared (both sets of grid sums written).
    void declare(PassIo& io);

    // A kernel of `step` as the one list of what it touches (binding, resource, access) and its
    // dispatch, splatting into grid sums `turn` (0 or 1) and zeroing the other set.
    ComputeStage stage(Stage stage, const gpu::SimStep& step, uint32_t turn);
    const StageLayout& layout() const { return layout_; }

    // Makes the kernels' pipelines again from their SPIR-V as it is now on disk (a shader reload);
    // the device must be idle.
    void reloadPipelines();
    // Puts every strand back in its rest pose around `headTransform`, at rest. The device must be
    // idle (the window waits for it).
    void reset(const glm::mat4& headTransform);

    // Copies the state back in strand-major order (waits for the device): for metrics and tests.
    // On the GPU, vertex i of strand s is at gpu::vertexSlot(s, i, V).
    SimState readState() const;
    // The last recorded step's grid sums (waits for the device).
    std::vector<gpu::GridNode> readGrid() const;

    const SimSetup& setup() const { return setup_; }
    const vk::Buffer& positions() const { return positions_; }
    const vk::Buffer& params() const { return params_; } // the SimParams uniform block (colliders)
    // The head mesh's field the solver reads (built with it; none without setup.sdf).
    const GpuMeshSdf* meshSdf() const { return sdf_.get(); }
    // For passes that read the simulation's output in the same frame.
    TrackedBuffer& positionsTrack() { return positionsTrack_; }
    uint32_t vertexCount() const { return vertexCount_; }
    uint64_t deviceBytes() const { return deviceBytes_; }
    // True when the grid sums in 64-bit fixed point (deterministic), false for float atomics.
    bool fixedPointGrid() const { return fixedGrid_; }

private:
    std::vector<uint8_t> download(const vk::Buffer& buffer) const;
    void createPipelines();

    const vk::Context& ctx_;
    SimSetup setup_;
    StrandSet model_; // the strands as given, kept for reset()
    uint32_t vertexCount_ = 0;
    uint32_t slotCount_ = 0; // vertices in the interleaved buffers, padding included
    bool fixedGrid_ = false;
    uint64_t deviceBytes_ = 0;
    vk::Buffer params_, positions_, velocities_, rest_, strands_, tangents_, counters_;
    std::array<vk::Buffer, 2>
        grids_; // the grid's sums: one step splats into grids_[turn_], its gather zeroes the other
    uint32_t turn_ = 0;
    TrackedBuffer positionsTrack_, velocitiesTrack_, tangentsTrack_, countersTrack_;
    std::array<TrackedBuffer, 2> gridTracks_;
    mutable vk::Buffer readback_; // host-visible, reused by every readState/readGrid
    StageLayout layout_;
    vk::ComputeKernel integrate_, gather_;
    std::unique_ptr<GpuMeshSdf> sdf_; // the head mesh's field (setup.sdf), built by its kernels
    vk::Buffer sdfNone_;              // one float bound in its place when there is none
};

} // namespace wisp
