// renderer/frame_uniforms.cpp: one persistently mapped uniform buffer per frame in flight.
#include "renderer/frame_uniforms.h"

#include "gpu/context.h"

#include <cstring>

namespace wisp {

FrameUniforms::FrameUniforms(const vk::Context& ctx, uint32_t framesInFlight)
{
    for (uint32_t i = 0; i < framesInFlight; ++i)
        buffers_.push_back(ctx.createBuffer({.size = sizeof(gpu::FrameParams),
                                             .usage = vk::kUniform,
                                             .memory = vk::Memory::Upload,
                                             .name = "frame.params"}));
    for (uint32_t i = 0; i < framesInFlight; ++i)
        descriptors_.push_back(descriptor(i));
}

void FrameUniforms::write(uint32_t slot, const gpu::FrameParams& params)
{
    std::memcpy(buffers_[slot].mapped(), &params, sizeof(params));
}

VkDescriptorBufferInfo FrameUniforms::descriptor(uint32_t slot) const
{
    return {buffers_[slot].get(), 0, sizeof(gpu::FrameParams)};
}

void FrameUniforms::push(const vk::Context& ctx, VkCommandBuffer cmd, VkPipelineLayout layout, uint32_t slot) const
{
    VkDescriptorBufferInfo params = descriptor(slot);
    VkWriteDescriptorSet write{.sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET,
                               .dstBinding = gpu::kFrameParamsBinding,
                               .descriptorCount = 1,
                               .descriptorType = VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER,
                               .pBufferInfo = &params};
    ctx.pushDescriptorSet(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, layout, 0, 1, &write);
}

} // namespace wisp
