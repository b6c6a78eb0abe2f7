// renderer/render_target.cpp: attachment creation, dynamic rendering begin/end, readback.
#include "renderer/render_target.h"

#include "gpu/context.h"
#include "gpu/pipeline.h"

#include <cstring>

namespace wisp {

uint32_t RenderTarget::samplesFor(VkSampleCountFlags supported, uint32_t requested)
{
    for (uint32_t s = requested; s > 1; s >>= 1)
        if (supported & s)
            return s;
    return 1;
}

RenderTarget::RenderTarget(const vk::Context& ctx, VkExtent2D extent, uint32_t requestedSamples)
    : ctx_(ctx),
      samples_(static_cast<VkSampleCountFlagBits>(samplesFor(ctx.report().colorDepthSampleCounts, requestedSamples)))
{
    resize(extent);
}

void RenderTarget::resize(VkExtent2D extent)
{
    const vk::Context& ctx = ctx_;
    extent_ = extent;
    if (multisampled())
        color_ =
            ctx.createImage({.format = kColorFormat,
                             .extent = extent,
                             .usage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSIENT_ATTACHMENT_BIT,
                             .samples = samples_,
                             .name = "target.color.msaa"});
    depth_ = ctx.createImage({.format = kDepthFormat,
                              .extent = extent,
                              .usage = VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT |
                                       VK_IMAGE_USAGE_TRANSFER_SRC_BIT,
                              .samples = samples_,
                              .name = "target.depth"});
    resolved_ = ctx.createImage({.format = kColorFormat,
                                 .extent = extent,
                                 .usage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT |
                                          VK_IMAGE_USAGE_TRANSFER_DST_BIT, // (the compute meshes' frame is copied in)
                                 .name = "target.color"});
    colorTrack_ = {.image = color_.get()};
    depthTrack_ = {.image = depth_.get(), .aspect = VK_IMAGE_ASPECT_DEPTH_BIT};
    resolvedTrack_ = {.image = resolved_.get()};
}

std::vector<TrackedImage*> RenderTarget::transientImages()
{
    std::vector<TrackedImage*> list = {&depthTrack_, &resolvedTrack_};
    if (multisampled())
        list.push_back(&colorTrack_);
    return list;
}

void RenderTarget::declareDraw(PassIo& io, DepthUse depth)
{
    if (multisampled()) {
        io.use(colorTrack_, Access::ColorAttachment);
        io.use(resolvedTrack_, Access::ResolveTarget);
    } else {
        io.use(resolvedTrack_, Access::ColorAttachment);
    }
    if (depth != DepthUse::None)
        io.use(depthTrack_, depth == DepthUse::Write ? Access::DepthAttachment : Access::DepthTestOnly);
}

void RenderTarget::beginRendering(VkCommandBuffer cmd, const glm::vec3& clearColor, DepthUse depthUse)
{
    VkAttachmentLoadOp load = colorCleared_ ? VK_ATTACHMENT_LOAD_OP_LOAD : VK_ATTACHMENT_LOAD_OP_CLEAR;
    VkAttachmentLoadOp depthLoad = depthCleared_ ? VK_ATTACHMENT_LOAD_OP_LOAD : VK_ATTACHMENT_LOAD_OP_CLEAR;
    colorCleared_ = true;
    depthCleared_ = depthCleared_ || depthUse != DepthUse::None;
    VkRenderingAttachmentInfo color{.sType = VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO,
                                    .imageView = multisampled() ? color_.view() : resolved_.view(),
                                    .imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
                                    .loadOp = load,
                                    .storeOp = VK_ATTACHMENT_STORE_OP_STORE,
                                    .clearValue = {.color = {{clearColor.r, clearColor.g, clearColor.b, 1.0f}}}};
    if (multisampled()) {
        color.resolveMode = VK_RESOLVE_MODE_AVERAGE_BIT;
        color.resolveImageView = resolved_.view();
        color.resolveImageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
    }
    VkRenderingAttachmentInfo depth{
        .sType = VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO,
        .imageView = depth_.view(),
        .imageLayout = depthUse == DepthUse::TestOnly ? VK_IMAGE_LAYOUT_DEPTH_READ_ONLY_OPTIMAL
                                                      : VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL,
        .loadOp = depthLoad,
        .storeOp = depthUse == DepthUse::TestOnly ? VK_ATTACHMENT_STORE_OP_NONE : VK_ATTACHMENT_STORE_OP_STORE,
        .clearValue = {.depthStencil = {1.0f, 0}}};
    VkRenderingInfo info{.sType = VK_STRUCTURE_TYPE_RENDERING_INFO,
                         .renderArea = {{0, 0}, extent_},
                         .layerCount = 1,
                         .colorAttachmentCount = 1,
                         .pColorAttachments = &color,
                         .pDepthAttachment = depthUse == DepthUse::None ? nullptr : &depth};
    vkCmdBeginRendering(cmd, &info);
    VkViewport viewport{0.0f, 0.0f, static_cast<float>(extent_.width), static_cast<float>(extent_.height), 0.0f, 1.0f};
    VkRect2D scissor{{0, 0}, extent_};
    vkCmdSetViewport(cmd, 0, 1, &viewport);
    vkCmdSetScissor(cmd, 0, 1, &scissor);
}

void RenderTarget::declareDepth(PassIo& io)
{
    io.use(depthTrack_, Access::DepthAttachment);
}

void RenderTarget::beginDepthRendering(VkCommandBuffer cmd)
{
    VkRenderingAttachmentInfo depth{.sType = VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO,
                                    .imageView = depth_.view(),
                                    .imageLayout = VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL,
                                    .loadOp = depthCleared_ ? VK_ATTACHMENT_LOAD_OP_LOAD : VK_ATTACHMENT_LOAD_OP_CLEAR,
                                    .storeOp = VK_ATTACHMENT_STORE_OP_STORE,
                                    .clearValue = {.depthStencil = {1.0f, 0}}};
    depthCleared_ = true;
    VkRenderingInfo info{.sType = VK_STRUCTURE_TYPE_RENDERING_INFO,
                         .renderArea = {{0, 0}, extent_},
                         .layerCount = 1,
                         .pDepthAttachment = &depth};
    vkCmdBeginRendering(cmd, &info);
    VkViewport viewport{0.0f, 0.0f, static_cast<float>(extent_.width), static_cast<float>(extent_.height), 0.0f, 1.0f};
    VkRect2D scissor{{0, 0}, extent_};
    vkCmdSetViewport(cmd, 0, 1, &viewport);
    vkCmdSetScissor(cmd, 0, 1, &scissor);
}

void RenderTarget::endRendering(VkCommandBuffer cmd)
{
    vkCmdEndRendering(cmd);
}

ReadbackPass::ReadbackPass(const vk::Context& ctx, RenderTarget& target) : target_(target)
{
    VkExtent2D e = target.extent();
    buffer_ = ctx.createBuffer({.size = VkDeviceSize(e.width) * e.height * 4,
                                .usage = vk::kTransferDst,
                                .memory = vk::Memory::Readback,
                                .name = "readback.pixels"});
}

void ReadbackPass::declare(PassIo& io)
{
    io.use(target_.result(), Access::TransferSrc);
}

void ReadbackPass::record(VkCommandBuffer cmd, FrameContext&)
{
    VkExtent2D e = target_.extent();
    VkBufferImageCopy region{.bufferOffset = 0,
                             .imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1},
                             .imageExtent = {e.width, e.height, 1}};
    vkCmdCopyImageToBuffer(cmd, target_.resultImage().get(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, buffer_, 1, &region);
    vk::transferToHostBarrier(cmd); // the host reads it once the fence signals
}

std::vector<uint8_t> ReadbackPass::pixels() const
{
    std::vector<uint8_t> out(static_cast<size_t>(buffer_.size()));
    std::memcpy(out.data(), buffer_.mapped(), out.size());
    // The picture is opaque: the attachment's alpha holds hair coverage (alpha-to-coverage), not
    // transparency, and must not make image viewers blend the PNG with their own background.
    for (size_t i = 3; i < out.size(); i += 4)
        out[i] = 255;
    return out;
}

} // namespace wisp
