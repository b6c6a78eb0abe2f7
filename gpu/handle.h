// gpu/handle.h: move-only owners of single Vulkan objects created from a VkDevice.
// DeviceHandle<T, Destroy> holds the device and the handle, defaults to VK_NULL_HANDLE, and
// destroys the object when it goes out of scope. Buffers and images (which also own memory)
// live in resources.h.
#pragma once

#include <utility>
#include <vulkan/vulkan.h>

namespace wisp::vk {

template <typename T, void (*Destroy)(VkDevice, T, const VkAllocationCallbacks*)> class DeviceHandle {
public:
    DeviceHandle() = default;
    DeviceHandle(VkDevice device, T handle) : device_(device), handle_(handle) {}
    ~DeviceHandle() { reset(); }
    DeviceHandle(DeviceHandle&& other) noexcept
        : device_(other.device_), handle_(std::exchange(other.handle_, VK_NULL_HANDLE))
    {
    }
    DeviceHandle& operator=(DeviceHandle&& other) noexcept
    {
        if (this != &other) {
            reset();
            device_ = other.device_;
            handle_ = std::exchange(other.handle_, VK_NULL_HANDLE);
        }
        return *this;
    }
    DeviceHandle(const DeviceHandle&) = delete;
    DeviceHandle& operator=(const DeviceHandle&) = delete;

    void reset()
    {
        if (handle_ != VK_NULL_HANDLE)
            Destroy(device_, std::exchange(handle_, VK_NULL_HANDLE), nullptr);
    }
    T get() const { return handle_; }
    operator T() const { return handle_; } // NOLINT: handles pass straight into vk* calls
    explicit operator bool() const { return handle_ != VK_NULL_HANDLE; }

private:
    VkDevice device_ = VK_NULL_HANDLE;
    T handle_ = VK_NULL_HANDLE;
};

using ShaderModule = DeviceHandle<VkShaderModule, vkDestroyShaderModule>;
using PipelineLayout = DeviceHandle<VkPipelineLayout, vkDestroyPipelineLayout>;
using Pipeline = DeviceHandle<VkPipeline, vkDestroyPipeline>;
using DescriptorSetLayout = DeviceHandle<VkDescriptorSetLayout, vkDestroyDescriptorSetLayout>;
using Sampler = DeviceHandle<VkSampler, vkDestroySampler>;
using ImageView = DeviceHandle<VkImageView, vkDestroyImageView>;
using Fence = DeviceHandle<VkFence, vkDestroyFence>;
using Semaphore = DeviceHandle<VkSemaphore, vkDestroySemaphore>;
using CommandPool = DeviceHandle<VkCommandPool, vkDestroyCommandPool>;
using QueryPool = DeviceHandle<VkQueryPool, vkDestroyQueryPool>;
using RenderPass = DeviceHandle<VkRenderPass, vkDestroyRenderPass>;
using Framebuffer = DeviceHandle<VkFramebuffer, vkDestroyFramebuffer>;
using DescriptorPool = DeviceHandle<VkDescriptorPool, vkDestroyDescriptorPool>;

} // namespace wisp::vk
