// renderer/physics_pass.h: the simulation as a pass of the frame: records the fixed steps due
// this frame on the GPU solver and declares the guide buffers it writes, so the frame puts a
// barrier between it and any pass that draws them.
#pragma once

#include "physics/gpu_solver.h"
#include "gpu/pass.h"

#include <vector>

namespace wisp {

class PhysicsPass : public Pass {
public:
    explicit PhysicsPass(GpuSolver& solver) : solver_(solver) {}
    const char* name() const override { return "physics"; }
    // `winds` (head units / s², empty: the solver's stays) gives each step its own wind.
    void setSteps(std::vector<gpu::SimStep> steps, std::vector<glm::vec3> winds = {})
    {
        steps_ = std::move(steps);
        winds_ = std::move(winds);
    }
    size_t stepCount() const { return steps_.size(); }
    void declare(PassIo& io) override
    {
        io.use(solver_.positionsTrack(), Access::ComputeWrite);
        io.use(solver_.tangentsTrack(), Access::ComputeWrite);
    }
    void record(VkCommandBuffer cmd, FrameContext&) override
    {
        for (size_t i = 0; i < steps_.size(); ++i) {
            if (i < winds_.size() && winds_[i] != solver_.wind())
                solver_.setWind(winds_[i]);
            solver_.recordStep(cmd, steps_[i]);
        }
    }

private:
    GpuSolver& solver_;
    std::vector<gpu::SimStep> steps_;
    std::vector<glm::vec3> winds_;
};

}  // namespace wisp
