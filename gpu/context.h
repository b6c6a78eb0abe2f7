// gpu/context.h: the Vulkan instance, the validation messenger (which counts messages),
// the chosen physical device with the features Wisp needs checked up front, the logical device
// and its one graphics+compute queue. Also the factory for buffers and images, debug names and
// one-off command submission. Everything else in renderer/ borrows a Context&.
#pragma once

#include "gpu/handle.h"
#include "gpu/resources.h"

#include <atomic>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace wisp::vk {

struct ContextOptions {
    bool validation = false;                     // Khronos validation layer + messenger
    bool synchronizationValidation = false;      // also the layer's synchronization checks
    std::string gpu;                             // "" = best device; an index; or a name substring
    std::vector<std::string> instanceExtensions; // e.g. what GLFW needs for a surface
    bool presentation = false;                   // enable VK_KHR_swapchain on the device
};

// What one physical device offers of what Wisp uses; `wisp info` prints it and the Context
// refuses a device whose missing() is not empty.
struct DeviceReport {
    uint32_t index = 0;
    std::string name;
    VkPhysicalDeviceType type = VK_PHYSICAL_DEVICE_TYPE_OTHER;
    uint32_t apiVersion = 0;
    std::string driverName;
    std::string driverInfo;
    uint32_t queueFamily = UINT32_MAX; // first graphics+compute family
    bool vulkan13 = false;             // dynamic rendering and synchronization2 are core there
    bool dynamicRendering = false;
    bool synchronization2 = false;
    bool maintenance4 = false; // glslang's SPIR-V 1.6 uses LocalSizeId, which needs it
    bool tessellationShader = false;
    bool geometryShader = false;
    bool fragmentStoresAndAtomics = false;
    bool vertexPipelineStoresAndAtomics = false;
    bool pipelineStatisticsQuery = false;
    bool timestamps = false;     // timestampComputeAndGraphics and valid bits on the queue
    bool pushDescriptor = false; // VK_KHR_push_descriptor
    bool floatAtomicAdd = false; // VK_EXT_shader_atomic_float shaderBufferFloat32AtomicAdd
    bool int64Atomics = false;   // shaderInt64 and shaderBufferInt64Atomics (the fixed-point grid)
    bool swapchain = false;      // VK_KHR_swapchain
    uint32_t timestampValidBits = 0;
    float timestampPeriodNs = 0.0f;
    uint32_t maxTessellationGenerationLevel = 0;
    uint32_t maxTessellationPatchSize = 0;
    uint32_t maxGeometryOutputVertices = 0;
    VkSampleCountFlags colorDepthSampleCounts = 0;
    uint64_t deviceLocalBytes = 0;
    uint32_t maxStorageBufferRange = 0;

    // Names of required features this device lacks; empty when Wisp can run on it.
    std::vector<std::string> missing(bool needSwapchain) const;
    const char* typeName() const;
};

// Fills a report from raw Vulkan data; separate so the feature check can be tested on any input.
// Test-only: WISP_HIDE_FEATURE=NAME[,NAME...] reports the named features as absent on every
// device (names as missing() gives them: geometryShader, VK_KHR_push_descriptor, ...), so a device
// lacking one can be tested where every device has them all.
std::vector<DeviceReport> queryDevices(VkInstance instance);
// Best first: discrete > integrated > virtual > CPU, then by index.
int deviceTypeRank(VkPhysicalDeviceType type);
// Picks a device for `selector` ("" = best usable, an index, or a case-insensitive name
// substring). Throws UserError naming the devices when none matches or the match lacks features.
const DeviceReport& selectDevice(const std::vector<DeviceReport>& devices, const std::string& selector,
                                 bool needSwapchain);

class Context {
public:
    explicit Context(const ContextOptions& options);
    ~Context();
    Context(const Context&) = delete;
    Context& operator=(const Context&) = delete;

    VkInstance instance() const { return instance_; }
    VkPhysicalDevice physicalDevice() const { return physical_; }
    VkDevice device() const { return device_; }
    VkQueue queue() const { return queue_; }
    uint32_t queueFamily() const { return report_.queueFamily; }
    const DeviceReport& report() const { return report_; }
    bool validationEnabled() const { return messenger_ != VK_NULL_HANDLE; }
    // WISP_SHADER_STATS=1 and the device reports pipeline statistics (profiling only).
    bool shaderStats() const { return shaderStats_; }
    // Validation warnings and errors seen since creation (0 when validation is off).
    uint32_t validationMessages() const { return validationMessages_.load(); }

    Buffer createBuffer(const BufferDesc& desc) const;
    Image createImage(const ImageDesc& desc) const;
    // A device-local buffer filled from host memory through a staging copy (load-time use).
    Buffer createBufferWithData(const BufferDesc& desc, const void* data, size_t bytes) const;
    Fence createFence(bool signaled, const char* name) const;
    Semaphore createSemaphore(const char* name) const;
    CommandPool createCommandPool(const char* name) const;

    // Records with `record`, submits, and waits for the queue: for uploads and readbacks.
    void submitAndWait(const std::function<void(VkCommandBuffer)>& record) const;
    // Every queue submission goes through here (callers VK_CHECK the result). Test-only fault
    // injection: with WISP_INJECT_DEVICE_LOST=N in the environment (read when the context is
    // created), the N-th submission and every later one return VK_ERROR_DEVICE_LOST without
    // reaching the driver, as on a lost device; from there on the code runs as after a real loss.
    VkResult queueSubmit(const VkSubmitInfo2& info, VkFence fence) const;
    void setName(uint64_t handle, VkObjectType type, const char* name) const;
    template <typename T> void setName(T handle, VkObjectType type, const char* name) const
    {
        setName(reinterpret_cast<uint64_t>(handle), type, name);
    }
    void pushDescriptorSet(VkCommandBuffer cmd, VkPipelineBindPoint bindPoint, VkPipelineLayout layout, uint32_t set,
                           uint32_t count, const VkWriteDescriptorSet* writes) const;

    uint32_t memoryTypeIndex(uint32_t typeBits, VkMemoryPropertyFlags required, VkMemoryPropertyFlags preferred) const;

private:
    void destroy();

    VkInstance instance_ = VK_NULL_HANDLE;
    VkDebugUtilsMessengerEXT messenger_ = VK_NULL_HANDLE;
    VkPhysicalDevice physical_ = VK_NULL_HANDLE;
    VkDevice device_ = VK_NULL_HANDLE;
    VkQueue queue_ = VK_NULL_HANDLE;
    DeviceReport report_;
    VkPhysicalDeviceMemoryProperties memory_{};
    CommandPool uploadPool_;
    PFN_vkSetDebugUtilsObjectNameEXT setObjectName_ = nullptr;
    PFN_vkCmdPushDescriptorSetKHR cmdPushDescriptorSet_ = nullptr;
    mutable std::atomic<uint32_t> validationMessages_{0};
    uint64_t deviceLostAtSubmission_ = 0;
    bool shaderStats_ = false; // WISP_INJECT_DEVICE_LOST; 0: none
    mutable uint64_t submissions_ = 0;

    static VKAPI_ATTR VkBool32 VKAPI_CALL onMessage(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                                    VkDebugUtilsMessageTypeFlagsEXT types,
                                                    const VkDebugUtilsMessengerCallbackDataEXT* data, void* user);
};

} // namespace wisp::vk

namespace wisp::vk {
// Every physical device with its report, from a short-lived instance (for `wisp info`).
std::vector<DeviceReport> enumerateDevices();
} // namespace wisp::vk
