// renderer/frame_uniforms.h: the FrameParams uniform block, one host-visible copy per frame in
// flight so the CPU never writes a block the GPU may still read.
#pragma once

#include "gpu/resources.h"
#include "shaders/shared/frame_params.h"

#include <span>
#include <vector>

namespace wisp {

namespace vk {
class Context;
}

class FrameUniforms {
public:
    FrameUniforms(const vk::Context& ctx, uint32_t framesInFlight);
    void write(uint32_t slot, const gpu::FrameParams& params);
    VkDescriptorBufferInfo descriptor(uint32_t slot) const;
    // Every slot's block, by slot (a compute stage's uniformBlock).
    std::span<const VkDescriptorBufferInfo> descriptors() const { return descriptors_; }
    // Pushes this slot's block at kFrameParamsBinding of set 0 (a push-descriptor set).
    void push(const vk::Context& ctx, VkCommandBuffer cmd, VkPipelineLayout layout, uint32_t slot) const;

private:
    std::vector<vk::Buffer> buffers_;
    std::vector<VkDescriptorBufferInfo> descriptors_;
};

} // namespace wisp
