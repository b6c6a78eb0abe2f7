// renderer/physics_pass.h: the simulation as a pass of the frame: records the fixed steps due
// this frame on the GPU solver and declares what its stages list (the guide buffers it writes
// among them), so the frame puts a barrier between it and any pass that draws them.
#pragma once

#include "gpu/pass.h"
#include "physics/gpu_solver.h"

#include <stdexcept>
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

// One kernel of one step, recorded in front of another pass of the frame (the host) with no
// barrier between them: one barrier covers what both touch, then the kernel's few workgroups take
// their places on the GPU first and the host's fill the rest around them, so that the physics,
// latency-bound on a few warps an SM, runs beside the host instead of before it (the Renderer's
// steps ahead). Timed as the host (its name), or as "physics" without one.
class PhysicsKernelPass : public Pass {
public:
    PhysicsKernelPass(GpuSolver& solver, GpuSolver::Stage stage, const gpu::SimStep& step, uint32_t turn, Pass* host)
        : solver_(solver), stage_(stage), step_(step), turn_(turn), host_(host)
    {
    }
    const char* name() const override { return host_ ? host_->name() : "physics"; }
    void declare(PassIo& io) override
    {
        solver_.stage(stage_, step_, turn_).declare(io);
        if (host_)
            host_->declare(io);
    }
    void record(VkCommandBuffer cmd, FrameContext& frame) override
    {
        // The step's turn, taken as it is recorded (steps recorded before it took theirs).
        if (stage_ == GpuSolver::Stage::Integrate && solver_.takeTurn() != turn_)
            throw std::logic_error("physics: a step ahead recorded out of turn");
        solver_.layout().record(solver_.stage(stage_, step_, turn_), cmd, 0, GpuSolver::scopeName(stage_));
        if (host_)
            host_->record(cmd, frame);
    }

private:
    GpuSolver& solver_;
    GpuSolver::Stage stage_;
    gpu::SimStep step_;
    uint32_t turn_;
    Pass* host_;
};

} // namespace wisp
