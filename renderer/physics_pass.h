// renderer/physics_pass.h: the simulation as a pass of the frame: records the fixed steps due
// this frame on the GPU solver and declares the guide buffers it writes, so the frame puts a
// barrier between it and any pass that draws them.
#pragma once

#include "gpu/pass.h"
#include "physics/gpu_solver.h"

#include <vector>

namespace wisp {

class PhysicsPass : public Pass {
public:
    explicit PhysicsPass(GpuSolver& solver) : solver_(solver) {}
    const char* name() const override { return "physics"; }
    // Each step carries its pose and its wind (gpu::SimStep).
    void setSteps(std::vector<gpu::SimStep> steps) { steps_ = std::move(steps); }
    size_t stepCount() const { return steps_.size(); }
    void declare(PassIo& io) override
    {
        io.use(solver_.positionsTrack(), Access::ComputeWrite);
        io.use(solver_.tangentsTrack(), Access::ComputeWrite);
    }
    void record(VkCommandBuffer cmd, FrameContext&) override
    {
        for (const gpu::SimStep& step : steps_)
            solver_.recordStep(cmd, step);
    }

private:
    GpuSolver& solver_;
    std::vector<gpu::SimStep> steps_;
};

} // namespace wisp
