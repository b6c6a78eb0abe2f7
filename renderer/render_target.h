// renderer/render_target.h: where the scene is drawn: a (multisampled) colour and depth pair and
// the single-sample sRGB image they resolve into, which readback copies to the host and the
// window blits to its swapchain. Also the ReadbackPass that copies the result to a host buffer.
#pragma once

#include "gpu/pass.h"
#include "gpu/resources.h"

#include <glm/glm.hpp>

#include <cstdint>
#include <vector>

namespace wisp {

namespace vk {
class Context;
}

class RenderTarget {
public:
    static constexpr VkFormat kColorFormat = VK_FORMAT_R8G8B8A8_SRGB;
    static constexpr VkFormat kDepthFormat = VK_FORMAT_D32_SFLOAT;

    // The device memory of a target of `extent` and `samples`: the multisampled colour (when
    // samples > 1), the depth and the resolved colour.
    static constexpr uint64_t deviceBytes(VkExtent2D extent, uint32_t samples)
    {
        uint64_t pixels = uint64_t(extent.width) * extent.height, n = samples > 1 ? samples : 1;
        return pixels * ((n > 1 ? n * vk::formatBytes(kColorFormat) : 0) + n * vk::formatBytes(kDepthFormat) +
                         vk::formatBytes(kColorFormat));
    }

    // The samples a target drawn with `requested` gets on a device whose colour and depth targets
    // support `supported`: the most of requested, requested / 2, ... the device has (1 at least).
    static uint32_t samplesFor(VkSampleCountFlags supported, uint32_t requested);

    RenderTarget(const vk::Context& ctx, VkExtent2D extent, uint32_t requestedSamples);
    // Recreates the images at a new size (passes keep their references); device must be idle.
    void resize(VkExtent2D extent);

    VkExtent2D extent() const { return extent_; }
    VkSampleCountFlagBits samples() const { return samples_; }
    bool multisampled() const { return samples_ != VK_SAMPLE_COUNT_1_BIT; }

    // How a drawing pass uses the depth: tests and writes it, only tests it (the read-only layout,
    // in which compute passes sample it too: no layout change between them), or not at all.
    enum class DepthUse { Write, TestOnly, None };
    // Declares the attachments a drawing pass writes.
    void declareDraw(PassIo& io, DepthUse depth = DepthUse::Write);
    // Begins dynamic rendering; the first pass to draw after beginFrame() clears.
    void beginRendering(VkCommandBuffer cmd, const glm::vec3& clearColor, DepthUse depth = DepthUse::Write);
    void endRendering(VkCommandBuffer cmd);
    // A pass that draws depth alone (no colour attachment: nothing to clear or resolve).
    void declareDepth(PassIo& io);
    void beginDepthRendering(VkCommandBuffer cmd);
    void beginFrame()
    {
        colorCleared_ = false;
        depthCleared_ = false;
    }

    TrackedImage& result() { return resolvedTrack_; } // single-sample, sRGB
    // The meshes' depth (multisampled like the colour), which the compute hair path reads.
    TrackedImage& depth() { return depthTrack_; }
    const vk::Image& depthImage() const { return depth_; }
    const vk::Image& resultImage() const { return resolved_; }
    std::vector<TrackedImage*> transientImages();

private:
    const vk::Context& ctx_;
    VkExtent2D extent_{};
    VkSampleCountFlagBits samples_;
    vk::Image color_; // multisampled; empty when samples_ == 1
    vk::Image depth_;
    vk::Image resolved_;
    TrackedImage colorTrack_, depthTrack_, resolvedTrack_;
    bool colorCleared_ = false;
    bool depthCleared_ = false;
};

// Copies the render target's result into a host-visible buffer (tightly packed RGBA8).
class ReadbackPass : public Pass {
public:
    ReadbackPass(const vk::Context& ctx, RenderTarget& target);
    const char* name() const override { return "readback"; }
    void declare(PassIo& io) override;
    void record(VkCommandBuffer cmd, FrameContext& frame) override;
    // Valid once the frame that recorded this pass has completed.
    std::vector<uint8_t> pixels() const;

private:
    RenderTarget& target_;
    vk::Buffer buffer_;
};

} // namespace wisp
