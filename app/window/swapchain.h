// app/window/swapchain.h: the window's swapchain over its surface (made again on resize; FIFO, an sRGB
// format where there is one), its images as the frame tracks them, a semaphore per image that
// presenting waits on, and the pass that blits the render target's result into the acquired image.
#pragma once

#include "gpu/handle.h"
#include "gpu/pass.h"
#include "renderer/render_target.h"

#include <vulkan/vulkan.h>

#include <vector>

namespace wisp {

namespace vk {
class Context;
}

class Swapchain {
public:
    Swapchain(const vk::Context& ctx, VkSurfaceKHR surface, VkExtent2D wanted);
    ~Swapchain() { destroy(); }
    Swapchain(const Swapchain&) = delete;
    Swapchain& operator=(const Swapchain&) = delete;

    // Makes it again for the surface's size now (`wanted` where the surface leaves it open); the
    // device must be idle.
    void recreate(VkExtent2D wanted);
    VkExtent2D extent() const { return extent_; }
    // The next image, `acquired` signalled when it may be written; false when the swapchain is out
    // of date (recreate it).
    bool acquire(VkSemaphore acquired, uint32_t& index);
    // Image `index` as the frame tracks it, its old contents discarded, waiting on the acquire.
    TrackedImage& beginImage(uint32_t index);
    // The semaphore the frame that draws image `index` signals, and presenting waits on.
    VkSemaphore renderDone(uint32_t index) const { return renderDone_[index]; }
    // Presents image `index`; false when out of date or suboptimal (recreate it).
    bool present(uint32_t index);

private:
    void destroy();

    const vk::Context& ctx_;
    VkSurfaceKHR surface_;
    VkSwapchainKHR handle_ = VK_NULL_HANDLE;
    VkExtent2D extent_{};
    std::vector<TrackedImage> images_;
    std::vector<vk::Semaphore> renderDone_;
};

// Copies the render target's result into the acquired swapchain image (the window's last pass).
class PresentBlitPass : public Pass {
public:
    PresentBlitPass(RenderTarget& target) : target_(target) {}
    const char* name() const override { return "present"; }
    void setSwapchainImage(TrackedImage& image, VkExtent2D extent)
    {
        swapImage_ = &image;
        swapExtent_ = extent;
    }
    void declare(PassIo& io) override
    {
        io.use(target_.result(), Access::TransferSrc);
        io.use(*swapImage_, Access::TransferDst);
    }
    void record(VkCommandBuffer cmd, FrameContext&) override
    {
        VkExtent2D src = target_.extent();
        VkImageBlit2 region{.sType = VK_STRUCTURE_TYPE_IMAGE_BLIT_2,
                            .srcSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1},
                            .srcOffsets = {{0, 0, 0}, {int32_t(src.width), int32_t(src.height), 1}},
                            .dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1},
                            .dstOffsets = {{0, 0, 0}, {int32_t(swapExtent_.width), int32_t(swapExtent_.height), 1}}};
        VkBlitImageInfo2 info{.sType = VK_STRUCTURE_TYPE_BLIT_IMAGE_INFO_2,
                              .srcImage = target_.resultImage().get(),
                              .srcImageLayout = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                              .dstImage = swapImage_->image,
                              .dstImageLayout = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                              .regionCount = 1,
                              .pRegions = &region,
                              .filter = VK_FILTER_NEAREST};
        vkCmdBlitImage2(cmd, &info);
    }

private:
    RenderTarget& target_;
    TrackedImage* swapImage_ = nullptr;
    VkExtent2D swapExtent_{};
};

} // namespace wisp
