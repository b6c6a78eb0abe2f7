// renderer/light_maps.cpp: the light's maps, their samplers, and the shadow and opacity passes.
#include "renderer/light_maps.h"

#include "gpu/check.h"
#include "gpu/context.h"
#include "gpu/frame.h"
#include "gpu/pipeline.h"
#include "renderer/mesh_pass.h"
#include "shaders/shared/shadows.h"

#include <cstring>

namespace wisp {

LightMaps::LightMaps(const vk::Context& ctx, uint32_t size) : ctx_(ctx)
{
    compare_ = vk::createSampler(ctx, VK_FILTER_LINEAR, true, "light.sampler.compare");
    nearest_ = vk::createSampler(ctx, VK_FILTER_NEAREST, false, "light.sampler.nearest");
    linear_ = vk::createSampler(ctx, VK_FILTER_LINEAR, false, "light.sampler.linear");
    resize(size);
}

void LightMaps::resize(uint32_t size)
{
    size_ = size;
    VkExtent2D extent{size, size};
    // Transfer source too: the tests read the maps back.
    // Transfer destination and storage: the compute hair path writes the hair's maps.
    constexpr VkImageUsageFlags kDepthUsage = VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT |
                                              VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
    headDepth_ =
        ctx_.createImage({.format = kDepthFormat, .extent = extent, .usage = kDepthUsage, .name = "light.head_depth"});
    hairDepth_ =
        ctx_.createImage({.format = kDepthFormat, .extent = extent, .usage = kDepthUsage, .name = "light.hair_depth"});
    hairValues_ = ctx_.createImage(
        {.format = kDepthValueFormat,
         .extent = extent,
         .usage = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT,
         .name = "light.hair_depth_values"});
    opacity_ = ctx_.createImage({.format = kOpacityFormat,
                                 .extent = extent,
                                 .usage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT |
                                          VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_STORAGE_BIT,
                                 .name = "light.opacity"});
    headTrack_ = {.image = headDepth_.get(), .aspect = VK_IMAGE_ASPECT_DEPTH_BIT, .transient = false};
    drawnKey_ = HeadShadowKey{}; // a new map: drawn again
    headStale_ = true;
    hairTrack_ = {.image = hairDepth_.get(), .aspect = VK_IMAGE_ASPECT_DEPTH_BIT};
    valuesTrack_ = {.image = hairValues_.get()};
    opacityTrack_ = {.image = opacity_.get()};
    updateInfos();
}

void LightMaps::updateInfos()
{
    constexpr VkImageLayout kRead = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
    infos_[0] = {compare_, headDepth_.view(), kRead};
    infos_[1] = {compare_, hairDepth_.view(), kRead};
    infos_[2] = {nearest_, values_ ? hairValues_.view() : hairDepth_.view(), kRead};
    infos_[3] = {linear_, opacity_.view(), kRead};
}

void LightMaps::setHeadKey(const HeadShadowKey& key)
{
    key_ = key;
    headStale_ = headStale_ || drawnKey_.size == 0 || std::memcmp(&key_, &drawnKey_, sizeof(key_)) != 0;
}

void LightMaps::useHairDepthValues(bool values)
{
    values_ = values;
    updateInfos();
}

void LightMaps::declareRead(PassIo& io, Access access)
{
    io.use(headTrack_, access);
    io.use(hairTrack_, access); // (bound to the hair's PCF either way)
    if (values_)
        io.use(valuesTrack_, access);
    io.use(opacityTrack_, access);
}

std::array<VkWriteDescriptorSet, 4> LightMaps::descriptorWrites() const
{
    constexpr VkDescriptorType kSampler = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
    return {vk::imageWrite(gpu::kBindingShadowHead, kSampler, &infos_[0]),
            vk::imageWrite(gpu::kBindingShadowHair, kSampler, &infos_[1]),
            vk::imageWrite(gpu::kBindingHairDepth, kSampler, &infos_[2]),
            vk::imageWrite(gpu::kBindingOpacity, kSampler, &infos_[3])};
}

std::array<StageUse, 4> LightMaps::computeReads()
{
    TrackedImage& hairDepth = values_ ? valuesTrack_ : hairTrack_;
    return {sampledImage(gpu::kBindingShadowHead, headTrack_, infos_[0].imageView, infos_[0].sampler),
            sampledImage(gpu::kBindingShadowHair, hairTrack_, infos_[1].imageView, infos_[1].sampler),
            sampledImage(gpu::kBindingHairDepth, hairDepth, infos_[2].imageView, infos_[2].sampler),
            sampledImage(gpu::kBindingOpacity, opacityTrack_, infos_[3].imageView, infos_[3].sampler)};
}

VkWriteDescriptorSet LightMaps::hairDepthWrite() const
{
    return vk::imageWrite(gpu::kBindingHairDepth, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, &infos_[2]);
}

namespace {

void beginRendering(VkCommandBuffer cmd, uint32_t size, const VkRenderingAttachmentInfo* color,
                    const VkRenderingAttachmentInfo* depth)
{
    VkRenderingInfo info{.sType = VK_STRUCTURE_TYPE_RENDERING_INFO,
                         .renderArea = {{0, 0}, {size, size}},
                         .layerCount = 1,
                         .colorAttachmentCount = color ? 1u : 0u,
                         .pColorAttachments = color,
                         .pDepthAttachment = depth};
    vkCmdBeginRendering(cmd, &info);
    VkViewport viewport{0.0f, 0.0f, float(size), float(size), 0.0f, 1.0f};
    VkRect2D scissor{{0, 0}, {size, size}};
    vkCmdSetViewport(cmd, 0, 1, &viewport);
    vkCmdSetScissor(cmd, 0, 1, &scissor);
}

} // namespace

void LightMaps::beginDepth(VkCommandBuffer cmd, const vk::Image& image) const
{
    VkRenderingAttachmentInfo depth{.sType = VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO,
                                    .imageView = image.view(),
                                    .imageLayout = VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL,
                                    .loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR,
                                    .storeOp = VK_ATTACHMENT_STORE_OP_STORE,
                                    .clearValue = {.depthStencil = {1.0f, 0}}};
    beginRendering(cmd, size_, nullptr, &depth);
}

void LightMaps::beginOpacity(VkCommandBuffer cmd) const
{
    VkRenderingAttachmentInfo color{.sType = VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO,
                                    .imageView = opacity_.view(),
                                    .imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
                                    .loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR,
                                    .storeOp = VK_ATTACHMENT_STORE_OP_STORE,
                                    .clearValue = {.color = {{0.0f, 0.0f, 0.0f, 0.0f}}}};
    beginRendering(cmd, size_, &color, nullptr);
}

void ShadowPass::declare(PassIo& io)
{
    if (maps_.headDepthStale())
        io.use(maps_.headDepth(), Access::DepthAttachment);
    if (!hairDepth_)
        return;
    io.use(maps_.hairDepth(), Access::DepthAttachment);
    if (hair_)
        hair_->declareFromLight(io);
}

void ShadowPass::record(VkCommandBuffer cmd, FrameContext& frame)
{
    if (maps_.headDepthStale()) {
        maps_.beginDepth(cmd, maps_.headDepthImage());
        if (enabled_)
            meshes_.recordFromLight(cmd, frame);
        vkCmdEndRendering(cmd);
        maps_.headDepthDrawn();
    }
    if (!hairDepth_)
        return;
    maps_.beginDepth(cmd, maps_.hairDepthImage());
    if (enabled_ && hair_)
        hair_->recordFromLight(cmd, frame, LightMap::Depth);
    vkCmdEndRendering(cmd);
}

void OpacityPass::declare(PassIo& io)
{
    io.use(maps_.hairDepth(), Access::FragmentSampled);
    io.use(maps_.opacity(), Access::ColorAttachment);
    if (hair_)
        hair_->declareFromLight(io);
}

void OpacityPass::record(VkCommandBuffer cmd, FrameContext& frame)
{
    maps_.beginOpacity(cmd);
    if (enabled_ && hair_)
        hair_->recordFromLight(cmd, frame, LightMap::Opacity);
    vkCmdEndRendering(cmd);
}

} // namespace wisp
