// renderer/hair_lut_image.h: the lookup mode's tables (shading/hair_lut.h) as a layered image on
// the device, sampled by both hair paths (the graphics path's fragments, the compute path's
// strand vertices). The Renderer owns it and uploads new tables when the look changes.
#pragma once

#include "gpu/handle.h"
#include "gpu/resources.h"
#include "shaders/shared/hair_shading.h"
#include "shading/hair_lut.h"

namespace wisp {

namespace vk {
class Context;
}
struct FrameContext;

class HairLutImage {
public:
    static constexpr VkFormat kFormat = VK_FORMAT_R32G32B32A32_SFLOAT; // the tables' layers
    static constexpr uint64_t kBytes =
        uint64_t(gpu::kHairLutSize) * gpu::kHairLutSize * gpu::kHairLutLayers * vk::formatBytes(kFormat);

    explicit HairLutImage(const vk::Context& ctx);
    // Uploads `lut` (waits for the upload); the image it replaces goes to `frame`'s deletion list
    // when given (it may still be in use), else is freed at once.
    void upload(const shading::HairLut& lut, FrameContext* frame);
    // The tables' descriptor: linear filtering, shader-read layout.
    const VkDescriptorImageInfo& info() const { return info_; }

private:
    const vk::Context& ctx_;
    vk::Image image_;
    vk::Sampler sampler_;
    VkDescriptorImageInfo info_{};
};

} // namespace wisp
