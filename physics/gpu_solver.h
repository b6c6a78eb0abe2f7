// physics/gpu_solver.h: the GPU solver's buffers and dispatch sequence. One step records
//   sim_integrate (every substep; the last one also splats into this step's grid sums) |
//   grid_gather (reads them; zeroes the other set, the next step's)
// with a compute->compute barrier after each (a workgroup barrier() does not order work across
// workgroups). The two sets of sums take turns, so a step needs no clear or normalize pass; the
// turn flips as each step is recorded, so every recorded step must be submitted (reset() starts
// the turns again). It talks to the device only through gpu/; the
// model and the maths stay in physics/ and shaders/shared/.
#pragma once

#include "gpu/handle.h"
#include "gpu/pass.h"
#include "gpu/resources.h"
#include "gpu/timestamps.h"
#include "physics/simulation.h"

#include <array>

namespace wisp {

namespace vk {
class Context;
}

class GpuSolver {
public:
    GpuSolver(const vk::Context& ctx, const StrandSet& strands, const SimSetup& setup, const glm::mat4& headTransform);

    // Records one fixed step (all substeps and the grid). step.time is the step's start. With a
    // timer, each kernel's dispatch is a timed scope: integrate (all substeps and the splat) and
    // grid_gather.
    void recordStep(VkCommandBuffer cmd, const gpu::SimStep& step, vk::GpuTimer* timer = nullptr);

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
    const vk::Buffer& tangents() const { return tangents_; }
    const vk::Buffer& params() const { return params_; } // the SimParams uniform block (colliders)
    // For passes that read the simulation's output in the same frame.
    TrackedBuffer& positionsTrack() { return positionsTrack_; }
    TrackedBuffer& tangentsTrack() { return tangentsTrack_; }
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
    TrackedBuffer positionsTrack_, tangentsTrack_;
    mutable vk::Buffer readback_; // host-visible, reused by every readState/readGrid
    vk::DescriptorSetLayout setLayout_;
    vk::PipelineLayout layout_;
    vk::Pipeline integrate_, gather_;
};

} // namespace wisp
