// physics/gpu_mesh_sdf.h: a head mesh's signed distance field built on the device from its plan
// (physics/mesh_sdf.h): the keys cleared, mesh_sdf_splat.comp, mesh_sdf_sign.comp, each a compute
// stage, in one submission when the head loads. The field stays on the device for the solver.
#pragma once

#include "gpu/compute_stage.h"
#include "gpu/frame.h"
#include "gpu/resources.h"
#include "physics/mesh_sdf.h"

#include <memory>
#include <vector>

namespace wisp {

namespace vk {
class Context;
}

class GpuMeshSdf {
public:
    GpuMeshSdf(const vk::Context& ctx, const SdfPlan& plan);
    const gpu::SdfGrid& grid() const { return grid_; }
    VkBuffer field() const { return field_.get(); }
    // The build's GPU time (the three stages' timestamps), milliseconds.
    double buildMs() const { return buildMs_; }
    // The field read back (a submission of its own), for tests and the CPU solver.
    MeshSdf read() const;

private:
    enum Stage { kClear = 0, kSplat = 1, kSign = 2, kStages = 3 };
    ComputeStage stage(int which);

    const vk::Context& ctx_;
    gpu::SdfGrid grid_{};
    uint32_t rows_ = 0;
    vk::Buffer triangles_, items_, keys_, field_;
    TrackedBuffer keysTrack_, fieldTrack_;
    StageLayout layout_;
    vk::ComputeKernel splat_, sign_;
    double buildMs_ = 0.0;
};

} // namespace wisp
