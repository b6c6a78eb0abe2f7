// gpu/frame.cpp: per-slot command buffers and fences, deferred deletion, and barriers
// derived from the passes' declarations.
#include "gpu/frame.h"

#include "gpu/check.h"
#include "gpu/context.h"

#include <algorithm>
#include <string>

namespace wisp {

AccessInfo describe(Access access)
{
    switch (access) {
    case Access::ColorAttachment:
        return {VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                VK_ACCESS_2_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT,
                VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, true};
    case Access::DepthAttachment:
        return {VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT,
                VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_READ_BIT | VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT,
                VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL, true};
    case Access::DepthTestOnly:
        return {VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT,
                VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_READ_BIT, VK_IMAGE_LAYOUT_DEPTH_READ_ONLY_OPTIMAL, false};
    case Access::DepthSampled:
        return {VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_SAMPLED_READ_BIT,
                VK_IMAGE_LAYOUT_DEPTH_READ_ONLY_OPTIMAL, false};
    case Access::ResolveTarget:
        return {VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT, VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT,
                VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, true};
    case Access::TransferSrc:
        return {VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_READ_BIT,
                VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, false};
    case Access::TransferDst:
        return {VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, true};
    case Access::GraphicsSampled:
        return {VK_PIPELINE_STAGE_2_VERTEX_SHADER_BIT | VK_PIPELINE_STAGE_2_TESSELLATION_CONTROL_SHADER_BIT |
                    VK_PIPELINE_STAGE_2_TESSELLATION_EVALUATION_SHADER_BIT | VK_PIPELINE_STAGE_2_GEOMETRY_SHADER_BIT |
                    VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT,
                VK_ACCESS_2_SHADER_SAMPLED_READ_BIT, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, false};
    case Access::FragmentSampled:
        return {VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT, VK_ACCESS_2_SHADER_SAMPLED_READ_BIT,
                VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, false};
    case Access::ComputeSampled:
        return {VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_SAMPLED_READ_BIT,
                VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, false};
    case Access::ComputeRead:
        return {VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_READ_BIT, VK_IMAGE_LAYOUT_GENERAL,
                false};
    case Access::ComputeWrite:
        return {VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, VK_IMAGE_LAYOUT_GENERAL,
                true};
    case Access::VertexShaderRead:
        return {VK_PIPELINE_STAGE_2_VERTEX_SHADER_BIT | VK_PIPELINE_STAGE_2_TESSELLATION_CONTROL_SHADER_BIT |
                    VK_PIPELINE_STAGE_2_TESSELLATION_EVALUATION_SHADER_BIT | VK_PIPELINE_STAGE_2_GEOMETRY_SHADER_BIT,
                VK_ACCESS_2_SHADER_STORAGE_READ_BIT, VK_IMAGE_LAYOUT_GENERAL, false};
    case Access::FragmentStorageRead:
        return {VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_READ_BIT, VK_IMAGE_LAYOUT_GENERAL,
                false};
    case Access::FragmentStorageWrite:
        return {VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT,
                VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, VK_IMAGE_LAYOUT_GENERAL,
                true};
    case Access::VertexInput:
        return {VK_PIPELINE_STAGE_2_VERTEX_ATTRIBUTE_INPUT_BIT, VK_ACCESS_2_VERTEX_ATTRIBUTE_READ_BIT,
                VK_IMAGE_LAYOUT_UNDEFINED, false};
    case Access::IndirectRead:
        return {VK_PIPELINE_STAGE_2_DRAW_INDIRECT_BIT, VK_ACCESS_2_INDIRECT_COMMAND_READ_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
                false};
    case Access::Present:
        return {VK_PIPELINE_STAGE_2_NONE, VK_ACCESS_2_NONE, VK_IMAGE_LAYOUT_PRESENT_SRC_KHR, false};
    }
    return {VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, VK_ACCESS_2_MEMORY_READ_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT,
            VK_IMAGE_LAYOUT_GENERAL, true};
}

Frame::Frame(const vk::Context& ctx, uint32_t framesInFlight) : ctx_(ctx)
{
    for (uint32_t i = 0; i < framesInFlight; ++i) {
        std::string name = "frame" + std::to_string(i);
        Slot slot{.pool = ctx.createCommandPool((name + ".pool").c_str()),
                  .fence = ctx.createFence(true, (name + ".fence").c_str()),
                  .timer = vk::GpuTimer(ctx, kMaxScopes, (name + ".timestamps").c_str()),
                  .context = {},
                  .submitted = false};
        VkCommandBufferAllocateInfo info{.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO,
                                         .commandPool = slot.pool,
                                         .level = VK_COMMAND_BUFFER_LEVEL_PRIMARY,
                                         .commandBufferCount = 1};
        VK_CHECK(vkAllocateCommandBuffers(ctx.device(), &info, &slot.context.cmd));
        ctx.setName(slot.context.cmd, VK_OBJECT_TYPE_COMMAND_BUFFER, (name + ".cmd").c_str());
        slot.context.slot = i;
        slots_.push_back(std::move(slot));
    }
}

Frame::~Frame()
{
    vkDeviceWaitIdle(ctx_.device()); // unchecked: after a lost device it fails at once, and destructors do not throw
}

void Frame::retireSlot(Slot& slot)
{
    VkFence fence = slot.fence;
    VK_CHECK(vkWaitForFences(ctx_.device(), 1, &fence, VK_TRUE, UINT64_MAX));
    if (slot.submitted) {
        timings_ = slot.timer.read();
        slot.submitted = false;
    }
    slot.context.retired.clear(); // the GPU is done with them: destroy now
}

FrameContext& Frame::begin(std::span<TrackedImage* const> transientImages)
{
    Slot& slot = slots_[frameNumber_ % slots_.size()];
    retireSlot(slot);
    VkFence fence = slot.fence;
    VK_CHECK(vkResetFences(ctx_.device(), 1, &fence));
    VK_CHECK(vkResetCommandPool(ctx_.device(), slot.pool, 0));
    VkCommandBufferBeginInfo beginInfo{.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO,
                                       .flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT};
    VK_CHECK(vkBeginCommandBuffer(slot.context.cmd, &beginInfo));
    slot.timer.reset(slot.context.cmd);
    slot.context.frameNumber = frameNumber_++;
    for (TrackedImage* image : transientImages)
        *image = TrackedImage{.image = image->image, .aspect = image->aspect, .transient = true};
    return slot.context;
}

void Frame::barrier(VkCommandBuffer cmd, const PassIo& io)
{
    std::vector<VkImageMemoryBarrier2> imageBarriers;
    std::vector<VkBufferMemoryBarrier2> bufferBarriers;

    for (const PassIo::ImageUse& use : io.images) {
        TrackedImage& t = *use.image;
        AccessInfo next = describe(use.access);
        bool layoutChange = t.layout != next.layout;
        bool hazard = t.written || (next.writes && t.stages != VK_PIPELINE_STAGE_2_NONE);
        // A read in a stage the last write (or transition) was not made visible to.
        bool unseen = t.dirty && (next.stage & ~t.visible) != 0;
        if (layoutChange || hazard || unseen) {
            bool chained = !layoutChange && !hazard; // only visibility for new stages
            imageBarriers.push_back({.sType = VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2,
                                     .srcStageMask = chained ? t.visible : t.stages,
                                     .srcAccessMask = t.written ? t.accesses : VK_ACCESS_2_NONE,
                                     .dstStageMask = next.stage,
                                     .dstAccessMask = next.access,
                                     .oldLayout = t.layout,
                                     .newLayout = next.layout,
                                     .srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED,
                                     .dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED,
                                     .image = t.image,
                                     .subresourceRange = {t.aspect, 0, 1, 0, 1}});
            if (chained) {
                t.stages |= next.stage;
                t.accesses |= next.access;
                t.visible |= next.stage;
            } else {
                t.dirty = t.dirty || layoutChange || t.written || next.writes;
                t.stages = next.stage;
                t.accesses = next.access;
                t.written = next.writes;
                t.layout = next.layout;
                t.visible = next.stage;
            }
        } else { // read after read in the same layout: later writers must wait for both
            t.stages |= next.stage;
            t.accesses |= next.access;
        }
    }
    // A buffer a pass uses in several ways (say, as indirect arguments and as storage) is one use
    // of all those stages and accesses, so that one barrier makes the last write visible to each.
    std::vector<std::pair<TrackedBuffer*, AccessInfo>> buffers;
    for (const PassIo::BufferUse& use : io.buffers) {
        AccessInfo info = describe(use.access);
        auto same = std::find_if(buffers.begin(), buffers.end(), [&](const auto& b) { return b.first == use.buffer; });
        if (same == buffers.end()) {
            buffers.push_back({use.buffer, info});
            continue;
        }
        same->second.stage |= info.stage;
        same->second.access |= info.access;
        same->second.writes = same->second.writes || info.writes;
    }
    for (const auto& [buffer, next] : buffers) {
        TrackedBuffer& t = *buffer;
        bool hazard = t.written || (next.writes && t.stages != VK_PIPELINE_STAGE_2_NONE);
        bool unseen = t.dirty && (next.stage & ~t.visible) != 0;
        if (hazard || unseen) {
            bufferBarriers.push_back({.sType = VK_STRUCTURE_TYPE_BUFFER_MEMORY_BARRIER_2,
                                      .srcStageMask = hazard ? t.stages : t.visible,
                                      .srcAccessMask = t.written ? t.accesses : VK_ACCESS_2_NONE,
                                      .dstStageMask = next.stage,
                                      .dstAccessMask = next.access,
                                      .srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED,
                                      .dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED,
                                      .buffer = t.buffer,
                                      .offset = 0,
                                      .size = VK_WHOLE_SIZE});
            if (hazard) {
                t.dirty = t.dirty || t.written || next.writes;
                t.stages = next.stage;
                t.accesses = next.access;
                t.written = next.writes;
                t.visible = next.stage;
            } else {
                t.stages |= next.stage;
                t.accesses |= next.access;
                t.visible |= next.stage;
            }
        } else {
            t.stages |= next.stage;
            t.accesses |= next.access;
            t.written = t.written || next.writes;
            t.dirty = t.dirty || next.writes;
            if (next.writes)
                t.visible = VK_PIPELINE_STAGE_2_NONE;
        }
    }
    if (imageBarriers.empty() && bufferBarriers.empty())
        return;
    VkDependencyInfo dependency{.sType = VK_STRUCTURE_TYPE_DEPENDENCY_INFO,
                                .bufferMemoryBarrierCount = static_cast<uint32_t>(bufferBarriers.size()),
                                .pBufferMemoryBarriers = bufferBarriers.data(),
                                .imageMemoryBarrierCount = static_cast<uint32_t>(imageBarriers.size()),
                                .pImageMemoryBarriers = imageBarriers.data()};
    vkCmdPipelineBarrier2(cmd, &dependency);
}

void Frame::run(FrameContext& frame, std::span<Pass* const> passes)
{
    Slot& slot = slots_[frame.slot];
    for (Pass* pass : passes) {
        PassIo io;
        pass->declare(io);
        barrier(frame.cmd, io);
        slot.timer.begin(frame.cmd, pass->name());
        pass->record(frame.cmd, frame);
        slot.timer.end(frame.cmd);
    }
}

void Frame::transition(FrameContext& frame, TrackedImage& image, Access access)
{
    PassIo io;
    io.use(image, access);
    barrier(frame.cmd, io);
}

void Frame::submit(FrameContext& frame, VkSemaphore wait, VkPipelineStageFlags2 waitStage, VkSemaphore signal)
{
    Slot& slot = slots_[frame.slot];
    VK_CHECK(vkEndCommandBuffer(frame.cmd));
    VkSemaphoreSubmitInfo waitInfo{
        .sType = VK_STRUCTURE_TYPE_SEMAPHORE_SUBMIT_INFO, .semaphore = wait, .stageMask = waitStage};
    VkSemaphoreSubmitInfo signalInfo{.sType = VK_STRUCTURE_TYPE_SEMAPHORE_SUBMIT_INFO,
                                     .semaphore = signal,
                                     .stageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT};
    VkCommandBufferSubmitInfo cmdInfo{.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_SUBMIT_INFO,
                                      .commandBuffer = frame.cmd};
    VkSubmitInfo2 submit{.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO_2,
                         .waitSemaphoreInfoCount = wait ? 1u : 0u,
                         .pWaitSemaphoreInfos = &waitInfo,
                         .commandBufferInfoCount = 1,
                         .pCommandBufferInfos = &cmdInfo,
                         .signalSemaphoreInfoCount = signal ? 1u : 0u,
                         .pSignalSemaphoreInfos = &signalInfo};
    VK_CHECK(ctx_.queueSubmit(submit, slot.fence));
    slot.submitted = true;
}

void Frame::waitIdle()
{
    // Oldest first, so timings() ends up holding the newest frame's.
    for (size_t i = 0; i < slots_.size(); ++i)
        retireSlot(slots_[(frameNumber_ + i) % slots_.size()]);
}

} // namespace wisp
