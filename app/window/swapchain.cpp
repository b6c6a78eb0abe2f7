// app/window/swapchain.cpp: the swapchain made and made again, acquire and present.
#include "app/window/swapchain.h"

#include "core/error.h"
#include "gpu/check.h"
#include "gpu/context.h"

#include <algorithm>
#include <utility>

namespace wisp {

Swapchain::Swapchain(const vk::Context& ctx, VkSurfaceKHR surface, VkExtent2D wanted) : ctx_(ctx), surface_(surface)
{
    recreate(wanted);
}

void Swapchain::destroy()
{
    renderDone_.clear();
    images_.clear();
    if (handle_)
        vkDestroySwapchainKHR(ctx_.device(), std::exchange(handle_, VK_NULL_HANDLE), nullptr);
}

void Swapchain::recreate(VkExtent2D wanted)
{
    const vk::Context& ctx = ctx_;
    VkSurfaceKHR surface = surface_;
    VkSurfaceCapabilitiesKHR caps;
    VK_CHECK(vkGetPhysicalDeviceSurfaceCapabilitiesKHR(ctx.physicalDevice(), surface, &caps));
    uint32_t formatCount = 0;
    VK_CHECK(vkGetPhysicalDeviceSurfaceFormatsKHR(ctx.physicalDevice(), surface, &formatCount, nullptr));
    std::vector<VkSurfaceFormatKHR> formats(formatCount);
    VK_CHECK(vkGetPhysicalDeviceSurfaceFormatsKHR(ctx.physicalDevice(), surface, &formatCount, formats.data()));
    VkSurfaceFormatKHR format = formats.front();
    for (const VkSurfaceFormatKHR& f : formats)
        if ((f.format == VK_FORMAT_B8G8R8A8_SRGB || f.format == VK_FORMAT_R8G8B8A8_SRGB) &&
            f.colorSpace == VK_COLOR_SPACE_SRGB_NONLINEAR_KHR)
            format = f;
    VkExtent2D extent =
        caps.currentExtent.width != UINT32_MAX
            ? caps.currentExtent
            : VkExtent2D{std::clamp(wanted.width, caps.minImageExtent.width, caps.maxImageExtent.width),
                         std::clamp(wanted.height, caps.minImageExtent.height, caps.maxImageExtent.height)};
    uint32_t imageCount = caps.minImageCount + 1;
    if (caps.maxImageCount > 0)
        imageCount = std::min(imageCount, caps.maxImageCount);
    if (!(caps.supportedUsageFlags & VK_IMAGE_USAGE_TRANSFER_DST_BIT))
        throw UserError("the window surface does not accept transfers (VK_IMAGE_USAGE_TRANSFER_DST_BIT)");

    VkSwapchainKHR old = handle_;
    VkSwapchainCreateInfoKHR info{.sType = VK_STRUCTURE_TYPE_SWAPCHAIN_CREATE_INFO_KHR,
                                  .surface = surface,
                                  .minImageCount = imageCount,
                                  .imageFormat = format.format,
                                  .imageColorSpace = format.colorSpace,
                                  .imageExtent = extent,
                                  .imageArrayLayers = 1,
                                  .imageUsage = VK_IMAGE_USAGE_TRANSFER_DST_BIT | VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT,
                                  .imageSharingMode = VK_SHARING_MODE_EXCLUSIVE,
                                  .preTransform = caps.currentTransform,
                                  .compositeAlpha = VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR,
                                  .presentMode = VK_PRESENT_MODE_FIFO_KHR,
                                  .clipped = VK_TRUE,
                                  .oldSwapchain = old};
    VkSwapchainKHR handle = VK_NULL_HANDLE;
    VK_CHECK(vkCreateSwapchainKHR(ctx.device(), &info, nullptr, &handle));
    handle_ = VK_NULL_HANDLE; // keep `old` alive until the new one exists
    destroy();
    if (old)
        vkDestroySwapchainKHR(ctx.device(), old, nullptr);
    handle_ = handle;
    extent_ = extent;
    ctx.setName(handle, VK_OBJECT_TYPE_SWAPCHAIN_KHR, "window.swapchain");

    uint32_t count = 0;
    VK_CHECK(vkGetSwapchainImagesKHR(ctx.device(), handle, &count, nullptr));
    std::vector<VkImage> images(count);
    VK_CHECK(vkGetSwapchainImagesKHR(ctx.device(), handle, &count, images.data()));
    for (VkImage image : images) {
        images_.push_back({.image = image});
        renderDone_.push_back(ctx.createSemaphore("window.renderDone"));
    }
}

bool Swapchain::acquire(VkSemaphore acquired, uint32_t& index)
{
    VkResult got = vkAcquireNextImageKHR(ctx_.device(), handle_, UINT64_MAX, acquired, VK_NULL_HANDLE, &index);
    if (got == VK_ERROR_OUT_OF_DATE_KHR)
        return false;
    if (got != VK_SUBOPTIMAL_KHR)
        VK_CHECK(got);
    return true;
}

TrackedImage& Swapchain::beginImage(uint32_t index)
{
    TrackedImage& image = images_[index];
    image.layout = VK_IMAGE_LAYOUT_UNDEFINED;            // its previous contents are not needed
    image.stages = VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT; // wait for the acquire semaphore's stage
    image.accesses = VK_ACCESS_2_NONE;
    image.written = false;
    return image;
}

bool Swapchain::present(uint32_t index)
{
    VkSemaphore done = renderDone_[index];
    VkPresentInfoKHR info{.sType = VK_STRUCTURE_TYPE_PRESENT_INFO_KHR,
                          .waitSemaphoreCount = 1,
                          .pWaitSemaphores = &done,
                          .swapchainCount = 1,
                          .pSwapchains = &handle_,
                          .pImageIndices = &index};
    VkResult presented = vkQueuePresentKHR(ctx_.queue(), &info);
    if (presented == VK_ERROR_OUT_OF_DATE_KHR || presented == VK_SUBOPTIMAL_KHR)
        return false;
    VK_CHECK(presented);
    return true;
}

} // namespace wisp
