// renderer/physics_pass.h: the simulation as a pass of the frame: records the fixed steps due
// this frame on the GPU solver and declares what its stages list (the guide buffers it writes
// among them), so the frame puts a barrier between it and any pass that draws them.
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
    void declare(PassIo& io) override { solver_.declare(io); }
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
