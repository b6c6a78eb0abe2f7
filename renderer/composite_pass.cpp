// renderer/composite_pass.cpp: the composite's pipeline and its one draw.
#include "renderer/composite_pass.h"

#include "gpu/context.h"
#include "gpu/frame.h"
#include "gpu/pipeline.h"
#include "renderer/render_target.h"

namespace wisp {

CompositePass::CompositePass(const vk::Context& ctx, RenderTarget& target, const char* name)
    : ctx_(ctx), target_(target), name_(name)
{
    sampler_ = vk::createSampler(ctx, VK_FILTER_NEAREST, false, "composite.sampler");
    vk::PipelineLayoutBundle layout = vk::createPipelineLayout(
        ctx, {.bindings = {{0, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, VK_SHADER_STAGE_FRAGMENT_BIT}},
              .name = "composite.layout"});
    setLayout_ = std::move(layout.setLayout);
    layout_ = std::move(layout.layout);
    pipeline_ = vk::createGraphicsPipeline(ctx, {.layout = layout_,
                                                 .shaders = {"fullscreen.vert", "oit_composite.frag"},
                                                 .cullMode = VK_CULL_MODE_NONE,
                                                 .depthTest = false,
                                                 .depthWrite = false,
                                                 .blend = vk::Blend::Premultiplied,
                                                 .colorFormat = RenderTarget::kColorFormat,
                                                 .samples = target.samples(),
                                                 .name = "composite.pipeline"});
}

void CompositePass::declare(PassIo& io)
{
    io.use(*track_, Access::FragmentSampled);
    target_.declareDraw(io, RenderTarget::DepthUse::None); // laid over everything: no depth
}

void CompositePass::record(VkCommandBuffer cmd, FrameContext&)
{
    target_.beginRendering(cmd, glm::vec3(0.0f), RenderTarget::DepthUse::None);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline_);
    VkDescriptorImageInfo image{sampler_, image_->view(), VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
    VkWriteDescriptorSet write{.sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET,
                               .dstBinding = 0,
                               .descriptorCount = 1,
                               .descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER,
                               .pImageInfo = &image};
    ctx_.pushDescriptorSet(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, layout_, 0, 1, &write);
    vkCmdDraw(cmd, 3, 1, 0, 0);
    target_.endRendering(cmd);
}

} // namespace wisp
