// renderer/hair_lut_image.cpp: the tables' upload (a staging buffer, one copy, one wait).
#include "renderer/hair_lut_image.h"

#include "gpu/context.h"
#include "gpu/frame.h"
#include "gpu/pipeline.h"

#include <cstring>

namespace wisp {

HairLutImage::HairLutImage(const vk::Context& ctx) : ctx_(ctx)
{
    sampler_ = vk::createSampler(ctx, VK_FILTER_LINEAR, false, "hair.lut.sampler");
}

void HairLutImage::upload(const shading::HairLut& lut, FrameContext* frame)
{
    uint32_t n = lut.size;
    vk::Image image = ctx_.createImage({.format = kFormat,
                                        .extent = {n, n},
                                        .usage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT,
                                        .layers = gpu::kHairLutLayers,
                                        .name = "hair.lut"});
    vk::Buffer staging = ctx_.createBuffer(
        {.size = lut.bytes(), .usage = vk::kTransferSrc, .memory = vk::Memory::Upload, .name = "hair.lut.staging"});
    std::memcpy(staging.mapped(), lut.texels.data(), lut.bytes());
    ctx_.submitAndWait([&](VkCommandBuffer cmd) {
        VkImageSubresourceRange range{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, gpu::kHairLutLayers};
        VkImageMemoryBarrier2 toCopy{.sType = VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2,
                                     .srcStageMask = VK_PIPELINE_STAGE_2_NONE,
                                     .dstStageMask = VK_PIPELINE_STAGE_2_COPY_BIT,
                                     .dstAccessMask = VK_ACCESS_2_TRANSFER_WRITE_BIT,
                                     .oldLayout = VK_IMAGE_LAYOUT_UNDEFINED,
                                     .newLayout = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                                     .image = image.get(),
                                     .subresourceRange = range};
        VkDependencyInfo dep{
            .sType = VK_STRUCTURE_TYPE_DEPENDENCY_INFO, .imageMemoryBarrierCount = 1, .pImageMemoryBarriers = &toCopy};
        vkCmdPipelineBarrier2(cmd, &dep);
        VkBufferImageCopy region{.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, gpu::kHairLutLayers},
                                 .imageExtent = {n, n, 1}};
        vkCmdCopyBufferToImage(cmd, staging, image.get(), VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &region);
        VkImageMemoryBarrier2 toRead{.sType = VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2,
                                     .srcStageMask = VK_PIPELINE_STAGE_2_COPY_BIT,
                                     .srcAccessMask = VK_ACCESS_2_TRANSFER_WRITE_BIT,
                                     .dstStageMask = VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT,
                                     .dstAccessMask = VK_ACCESS_2_SHADER_SAMPLED_READ_BIT,
                                     .oldLayout = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                                     .newLayout = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
                                     .image = image.get(),
                                     .subresourceRange = range};
        dep.pImageMemoryBarriers = &toRead;
        vkCmdPipelineBarrier2(cmd, &dep);
    });
    if (frame && image_)
        frame->retire(std::move(image_));
    image_ = std::move(image);
    info_ = {sampler_, image_.view(), VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
}

} // namespace wisp
