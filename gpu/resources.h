// gpu/resources.h: move-only buffers and images that own their device memory (one
// allocation each; Wisp has few, large resources), described with designated initializers:
//   Buffer b = ctx.createBuffer({.size = bytes, .usage = kStorage, .name = "guide.positions"});
#pragma once

#include <cstdint>
#include <vulkan/vulkan.h>

namespace wisp::vk {

// Bytes per texel of the image formats Wisp allocates (0 for any other): the owners' memory
// estimates (RenderTarget::deviceBytes, ...) count with it.
constexpr uint64_t formatBytes(VkFormat format)
{
    switch (format) {
    case VK_FORMAT_R8G8B8A8_SRGB:
    case VK_FORMAT_R8G8B8A8_UNORM:
    case VK_FORMAT_D32_SFLOAT:
    case VK_FORMAT_R32_SFLOAT:
        return 4;
    case VK_FORMAT_R16G16B16A16_SFLOAT:
        return 8;
    case VK_FORMAT_R32G32B32A32_SFLOAT:
        return 16;
    default:
        return 0;
    }
}

inline constexpr VkBufferUsageFlags kStorage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
inline constexpr VkBufferUsageFlags kUniform = VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT;
inline constexpr VkBufferUsageFlags kVertex = VK_BUFFER_USAGE_VERTEX_BUFFER_BIT;
inline constexpr VkBufferUsageFlags kIndex = VK_BUFFER_USAGE_INDEX_BUFFER_BIT;
inline constexpr VkBufferUsageFlags kTransferSrc = VK_BUFFER_USAGE_TRANSFER_SRC_BIT;
inline constexpr VkBufferUsageFlags kTransferDst = VK_BUFFER_USAGE_TRANSFER_DST_BIT;

enum class Memory {
    DeviceLocal, // fastest for the GPU; filled by copies or shaders
    Upload,      // host-visible, coherent, persistently mapped: written by the CPU each frame
    Readback,    // host-visible, cached where possible, persistently mapped: read by the CPU
};

struct BufferDesc {
    VkDeviceSize size = 0;
    VkBufferUsageFlags usage = 0;
    Memory memory = Memory::DeviceLocal;
    const char* name = "unnamed buffer";
};

class Buffer {
public:
    Buffer() = default;
    Buffer(VkDevice device, VkBuffer buffer, VkDeviceMemory memory, VkDeviceSize size, void* mapped);
    ~Buffer() { reset(); }
    Buffer(Buffer&& other) noexcept { *this = static_cast<Buffer&&>(other); }
    Buffer& operator=(Buffer&& other) noexcept;
    Buffer(const Buffer&) = delete;
    Buffer& operator=(const Buffer&) = delete;
    void reset();

    VkBuffer get() const { return buffer_; }
    operator VkBuffer() const { return buffer_; } // NOLINT
    VkDeviceSize size() const { return size_; }
    void* mapped() const { return mapped_; } // null for device-local memory
    explicit operator bool() const { return buffer_ != VK_NULL_HANDLE; }

private:
    VkDevice device_ = VK_NULL_HANDLE;
    VkBuffer buffer_ = VK_NULL_HANDLE;
    VkDeviceMemory memory_ = VK_NULL_HANDLE;
    VkDeviceSize size_ = 0;
    void* mapped_ = nullptr;
};

struct ImageDesc {
    VkFormat format = VK_FORMAT_UNDEFINED;
    VkExtent2D extent = {0, 0};
    VkImageUsageFlags usage = 0;
    VkSampleCountFlagBits samples = VK_SAMPLE_COUNT_1_BIT;
    uint32_t layers = 1; // more than one: a 2D array (and its view)
    const char* name = "unnamed image";
};

class Image {
public:
    Image() = default;
    Image(VkDevice device, VkImage image, VkDeviceMemory memory, VkImageView view, const ImageDesc& desc);
    ~Image() { reset(); }
    Image(Image&& other) noexcept { *this = static_cast<Image&&>(other); }
    Image& operator=(Image&& other) noexcept;
    Image(const Image&) = delete;
    Image& operator=(const Image&) = delete;
    void reset();

    VkImage get() const { return image_; }
    VkImageView view() const { return view_; }
    VkFormat format() const { return format_; }
    VkExtent2D extent() const { return extent_; }
    VkSampleCountFlagBits samples() const { return samples_; }
    VkImageAspectFlags aspect() const;
    explicit operator bool() const { return image_ != VK_NULL_HANDLE; }

private:
    VkDevice device_ = VK_NULL_HANDLE;
    VkImage image_ = VK_NULL_HANDLE;
    VkDeviceMemory memory_ = VK_NULL_HANDLE;
    VkImageView view_ = VK_NULL_HANDLE;
    VkFormat format_ = VK_FORMAT_UNDEFINED;
    VkExtent2D extent_ = {0, 0};
    VkSampleCountFlagBits samples_ = VK_SAMPLE_COUNT_1_BIT;
};

bool isDepthFormat(VkFormat format);

// Device memory Wisp holds (Context's allocations, which Buffer and Image free): a long run
// reports it at its start and end to show it does not grow. Memory the ImGui backend allocates
// for itself is not counted.
struct DeviceMemoryStats {
    uint64_t allocations = 0;
    uint64_t bytes = 0;
};
DeviceMemoryStats deviceMemoryStats();
void trackDeviceMemory(VkDeviceMemory memory, VkDeviceSize bytes);
void freeDeviceMemory(VkDevice device, VkDeviceMemory memory); // vkFreeMemory, and forgets it

} // namespace wisp::vk
