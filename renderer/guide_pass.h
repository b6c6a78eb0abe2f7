// renderer/guide_pass.h: draws the simulated guide strands as lines over the head, straight from
// the solver's positions buffer (the physics' view until the strands renderer takes over).
#pragma once

#include "gpu/handle.h"
#include "gpu/pass.h"
#include "gpu/resources.h"

namespace wisp {

namespace vk {
class Context;
}
class RenderTarget;
class FrameUniforms;
class GpuSolver;

class GuidePass : public Pass {
public:
    // The device memory of the lines' indices: two per segment of every guide.
    static constexpr uint64_t deviceBytes(uint64_t guides, uint32_t verticesPerStrand)
    {
        return guides * (verticesPerStrand > 0 ? verticesPerStrand - 1 : 0) * 2 * sizeof(uint32_t);
    }

    GuidePass(const vk::Context& ctx, RenderTarget& target, FrameUniforms& uniforms, GpuSolver& solver,
              uint32_t strandCount, uint32_t verticesPerStrand);
    const char* name() const override { return "guides"; }
    void declare(PassIo& io) override;
    void record(VkCommandBuffer cmd, FrameContext& frame) override;

private:
    const vk::Context& ctx_;
    RenderTarget& target_;
    FrameUniforms& uniforms_;
    GpuSolver& solver_;
    uint32_t verticesPerStrand_;
    uint32_t indexCount_;
    vk::DescriptorSetLayout setLayout_;
    vk::PipelineLayout layout_;
    vk::Pipeline pipeline_;
    vk::Buffer indices_;
};

} // namespace wisp
