// gpu/compute_stage.cpp: a stage's list turned into the frame's declarations, the pushed
// descriptors and the shared layout, and the checks on the commands a stage records.
#include "gpu/compute_stage.h"

#include "gpu/context.h"
#include "gpu/frame.h"
#include "gpu/pipeline.h"

#include <algorithm>
#include <cstdio>
#include <stdexcept>

namespace wisp {

namespace {

std::string handleText(uint64_t handle)
{
    char text[32];
    std::snprintf(text, sizeof(text), "0x%llx", static_cast<unsigned long long>(handle));
    return text;
}

const char* accessName(Access access)
{
    switch (access) {
    case Access::ComputeRead:
        return "ComputeRead";
    case Access::ComputeWrite:
        return "ComputeWrite";
    case Access::ComputeSampled:
        return "ComputeSampled";
    case Access::DepthSampled:
        return "DepthSampled";
    case Access::TransferSrc:
        return "TransferSrc";
    case Access::TransferDst:
        return "TransferDst";
    case Access::IndirectRead:
        return "IndirectRead";
    default:
        return "another access";
    }
}

void expectAccess(bool allowed, const char* what, Access access)
{
    if (!allowed)
        throw std::logic_error(std::string(what) + " cannot be used as " + accessName(access) + " by a compute stage");
}

} // namespace

StageUse storageBuffer(uint32_t binding, TrackedBuffer& buffer, Access access)
{
    expectAccess(access == Access::ComputeRead || access == Access::ComputeWrite, "a storage buffer", access);
    return {.binding = binding, .type = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, .access = access, .buffer = &buffer};
}

StageUse storageImage(uint32_t binding, TrackedImage& image, VkImageView view, Access access)
{
    expectAccess(access == Access::ComputeRead || access == Access::ComputeWrite, "a storage image", access);
    return {.binding = binding,
            .type = VK_DESCRIPTOR_TYPE_STORAGE_IMAGE,
            .access = access,
            .image = &image,
            .imageInfo = {VK_NULL_HANDLE, view, describe(access).layout}};
}

StageUse sampledImage(uint32_t binding, TrackedImage& image, VkImageView view, VkSampler sampler, Access access)
{
    expectAccess(access == Access::ComputeSampled || access == Access::DepthSampled, "a sampled image", access);
    return {.binding = binding,
            .type = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER,
            .access = access,
            .image = &image,
            .imageInfo = {sampler, view, describe(access).layout}};
}

StageUse uniformBlock(uint32_t binding, std::span<const VkDescriptorBufferInfo> perSlot)
{
    return {.binding = binding, .type = VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, .perSlot = perSlot};
}

StageUse uniformBlock(uint32_t binding, VkBuffer buffer)
{
    return {.binding = binding, .type = VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, .bufferInfo = {buffer, 0, VK_WHOLE_SIZE}};
}

StageUse constantBuffer(uint32_t binding, VkBuffer buffer)
{
    return {.binding = binding, .type = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, .bufferInfo = {buffer, 0, VK_WHOLE_SIZE}};
}

StageUse constantImage(uint32_t binding, const VkDescriptorImageInfo& info)
{
    return {.binding = binding,
            .type = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER,
            .access = Access::ComputeSampled,
            .imageInfo = info};
}

StageUse commandUse(TrackedBuffer& buffer, Access access)
{
    expectAccess(access == Access::TransferSrc || access == Access::TransferDst || access == Access::IndirectRead,
                 "a buffer outside the descriptors", access);
    return {.access = access, .buffer = &buffer};
}

StageUse commandUse(TrackedImage& image, Access access)
{
    expectAccess(access == Access::TransferSrc || access == Access::TransferDst, "an image outside the descriptors",
                 access);
    return {.access = access, .image = &image};
}

void ComputeStage::declare(PassIo& io) const
{
    for (size_t i = 0; i < uses.size(); ++i) {
        const StageUse& u = uses[i];
        if (!u.bound || !u.tracked())
            continue;
        bool again = std::any_of(uses.begin(), uses.begin() + ptrdiff_t(i), [&](const StageUse& earlier) {
            return earlier.bound && earlier.buffer == u.buffer && earlier.image == u.image &&
                   earlier.access == u.access;
        });
        if (again) // (one image under two bindings: declared once)
            continue;
        if (u.buffer)
            io.use(*u.buffer, u.access);
        else
            io.use(*u.image, u.access);
    }
}

StageCommands::StageCommands(const vk::Context& ctx, VkPipelineLayout layout, VkCommandBuffer cmd, uint32_t slot,
                             const ComputeStage& stage, std::string name)
    : ctx_(ctx), layout_(layout), cmd_(cmd), slot_(slot), stage_(stage), name_(std::move(name))
{
    bufferInfos_.resize(stage.uses.size());
    imageInfos_.resize(stage.uses.size());
    for (size_t i = 0; i < stage.uses.size(); ++i) {
        const StageUse& u = stage.uses[i];
        if (!u.bound || u.binding == StageUse::kNoBinding)
            continue;
        VkWriteDescriptorSet write{.sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET,
                                   .dstBinding = u.binding,
                                   .descriptorCount = 1,
                                   .descriptorType = u.type};
        if (u.type == VK_DESCRIPTOR_TYPE_STORAGE_BUFFER || u.type == VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER) {
            if (u.buffer)
                bufferInfos_[i] = {u.buffer->buffer, 0, VK_WHOLE_SIZE};
            else if (!u.perSlot.empty())
                bufferInfos_[i] = u.perSlot[u.perSlot.size() > 1 ? slot : 0];
            else
                bufferInfos_[i] = u.bufferInfo;
            write.pBufferInfo = &bufferInfos_[i];
        } else {
            imageInfos_[i] = u.imageInfo;
            write.pImageInfo = &imageInfos_[i];
        }
        writes_.push_back(write);
    }
}

void StageCommands::bind(const vk::ComputeKernel& kernel, const void* push, uint32_t bytes)
{
    for (uint32_t binding : kernel.bindings) {
        bool listed = std::any_of(writes_.begin(), writes_.end(),
                                  [&](const VkWriteDescriptorSet& w) { return w.dstBinding == binding; });
        if (!listed)
            throw std::logic_error("compute stage '" + name_ + "' dispatches " + kernel.name +
                                   ", whose shader uses binding " + std::to_string(binding) +
                                   ", which the stage does not list (or lists unbound): add it to the stage's uses");
    }
    vkCmdBindPipeline(cmd_, VK_PIPELINE_BIND_POINT_COMPUTE, kernel.get());
    if (!writes_.empty())
        ctx_.pushDescriptorSet(cmd_, VK_PIPELINE_BIND_POINT_COMPUTE, layout_, 0, uint32_t(writes_.size()),
                               writes_.data());
    vkCmdPushConstants(cmd_, layout_, VK_SHADER_STAGE_COMPUTE_BIT, 0, bytes, push);
}

void StageCommands::require(const TrackedBuffer& buffer, Access access, const char* verb) const
{
    for (const StageUse& u : stage_.uses)
        if (u.bound && u.buffer == &buffer && u.access == access)
            return;
    throw std::logic_error("compute stage '" + name_ + "' " + verb + " buffer " + handleText(uint64_t(buffer.buffer)) +
                           ", which it does not list as " + accessName(access) +
                           ": add it to the stage's uses, so that the frame orders it");
}

void StageCommands::require(const TrackedImage& image, Access access, const char* verb) const
{
    for (const StageUse& u : stage_.uses)
        if (u.bound && u.image == &image && u.access == access)
            return;
    throw std::logic_error("compute stage '" + name_ + "' " + verb + " image " + handleText(uint64_t(image.image)) +
                           ", which it does not list as " + accessName(access) +
                           ": add it to the stage's uses, so that the frame orders it");
}

void StageCommands::fill(TrackedBuffer& buffer, uint32_t value)
{
    require(buffer, Access::TransferDst, "fills");
    vkCmdFillBuffer(cmd_, buffer.buffer, 0, VK_WHOLE_SIZE, value);
}

void StageCommands::copyBufferToImage(TrackedBuffer& src, TrackedImage& dst, const VkBufferImageCopy& region)
{
    require(src, Access::TransferSrc, "copies from");
    require(dst, Access::TransferDst, "copies into");
    vkCmdCopyBufferToImage(cmd_, src.buffer, dst.image, describe(Access::TransferDst).layout, 1, &region);
}

void StageCommands::copyImage(TrackedImage& src, TrackedImage& dst, const VkImageCopy& region)
{
    require(src, Access::TransferSrc, "copies from");
    require(dst, Access::TransferDst, "copies into");
    vkCmdCopyImage(cmd_, src.image, describe(Access::TransferSrc).layout, dst.image,
                   describe(Access::TransferDst).layout, 1, &region);
}

void StageCommands::copyToHost(TrackedBuffer& src, const vk::Buffer& host, VkDeviceSize bytes)
{
    require(src, Access::TransferSrc, "copies from");
    VkBufferCopy region{0, 0, bytes};
    vkCmdCopyBuffer(cmd_, src.buffer, host, 1, &region);
    vk::transferToHostBarrier(cmd_);
}

void StageCommands::setConstantBuffer(uint32_t binding, VkBuffer buffer)
{
    for (size_t i = 0; i < stage_.uses.size(); ++i) {
        const StageUse& u = stage_.uses[i];
        if (u.bound && u.binding == binding && !u.tracked() && u.type == VK_DESCRIPTOR_TYPE_STORAGE_BUFFER) {
            bufferInfos_[i] = {buffer, 0, VK_WHOLE_SIZE};
            return;
        }
    }
    throw std::logic_error("compute stage '" + name_ + "' replaces binding " + std::to_string(binding) +
                           ", which it does not list as a constant buffer");
}

StageLayout::StageLayout(const vk::Context& ctx, std::span<const ComputeStage> stages, uint32_t pushConstantBytes,
                         const char* name)
    : ctx_(&ctx)
{
    std::vector<vk::DescriptorBinding> bindings;
    for (const ComputeStage& stage : stages) {
        for (const StageUse& u : stage.uses) {
            if (u.binding == StageUse::kNoBinding)
                continue;
            auto same = std::find_if(bindings.begin(), bindings.end(),
                                     [&](const vk::DescriptorBinding& b) { return b.binding == u.binding; });
            if (same == bindings.end())
                bindings.push_back({u.binding, u.type, VK_SHADER_STAGE_COMPUTE_BIT});
            else if (same->type != u.type)
                throw std::logic_error(std::string(name) + ": binding " + std::to_string(u.binding) +
                                       " is listed with two descriptor types");
        }
    }
    std::sort(bindings.begin(), bindings.end(),
              [](const vk::DescriptorBinding& a, const vk::DescriptorBinding& b) { return a.binding < b.binding; });
    for (const vk::DescriptorBinding& b : bindings)
        bindings_.push_back(b.binding);
    vk::PipelineLayoutBundle bundle = vk::createPipelineLayout(ctx, {.bindings = bindings,
                                                                     .pushConstantBytes = pushConstantBytes,
                                                                     .pushConstantStages = VK_SHADER_STAGE_COMPUTE_BIT,
                                                                     .name = name});
    setLayout_ = std::move(bundle.setLayout);
    layout_ = std::move(bundle.layout);
}

void StageLayout::record(const ComputeStage& stage, VkCommandBuffer cmd, uint32_t slot, const std::string& name) const
{
    StageCommands commands(*ctx_, layout_, cmd, slot, stage, name);
    stage.record(commands);
}

void ComputeStagePass::record(VkCommandBuffer cmd, FrameContext& frame)
{
    layout_.record(describe_(), cmd, frame.slot, name_);
}

} // namespace wisp
