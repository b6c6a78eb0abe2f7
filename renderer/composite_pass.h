// renderer/composite_pass.h: a premultiplied hair image laid over the target by a full-screen
// triangle (shaders/oit_composite.frag). Both paths use it: the graphics path for its linked
// lists' resolve (oit.composite), the compute path for its rasterizer's image (hair.composite).
#pragma once

#include "gpu/handle.h"
#include "gpu/pass.h"
#include "gpu/resources.h"

namespace wisp {

namespace vk {
class Context;
}
class RenderTarget;

// Lays a premultiplied hair image (the OIT resolve's, or the compute rasterizer's) over the target.
class CompositePass : public Pass {
public:
    CompositePass(const vk::Context& ctx, RenderTarget& target, const char* name);
    const char* name() const override { return name_; }
    // The image to lay over (set before each frame it changes; tracked, sampled in fragments).
    void setSource(TrackedImage* track, const vk::Image* image)
    {
        track_ = track;
        image_ = image;
    }
    void declare(PassIo& io) override;
    void record(VkCommandBuffer cmd, FrameContext& frame) override;

private:
    const vk::Context& ctx_;
    RenderTarget& target_;
    const char* name_;
    TrackedImage* track_ = nullptr;
    const vk::Image* image_ = nullptr;
    vk::DescriptorSetLayout setLayout_;
    vk::PipelineLayout layout_;
    vk::Pipeline pipeline_;
    vk::Sampler sampler_;
};

} // namespace wisp
