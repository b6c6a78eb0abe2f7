// gpu/resources.cpp: moves and destruction of Buffer and Image (their creation is in
// Context, which knows the memory types).
#include "gpu/resources.h"

#include <mutex>
#include <unordered_map>
#include <utility>

namespace wisp::vk {

namespace {

// Every live allocation and its size: a soak reports them at its start and end (they must match).
struct AllocationTable {
    std::mutex mutex;
    std::unordered_map<VkDeviceMemory, VkDeviceSize> sizes;
    DeviceMemoryStats stats;
};

AllocationTable& allocationTable()
{
    static AllocationTable table;
    return table;
}

} // namespace

void trackDeviceMemory(VkDeviceMemory memory, VkDeviceSize bytes)
{
    AllocationTable& t = allocationTable();
    std::lock_guard lock(t.mutex);
    t.sizes[memory] = bytes;
    t.stats.allocations += 1;
    t.stats.bytes += bytes;
}

void freeDeviceMemory(VkDevice device, VkDeviceMemory memory)
{
    vkFreeMemory(device, memory, nullptr); // unmaps too
    AllocationTable& t = allocationTable();
    std::lock_guard lock(t.mutex);
    if (auto it = t.sizes.find(memory); it != t.sizes.end()) {
        t.stats.allocations -= 1;
        t.stats.bytes -= it->second;
        t.sizes.erase(it);
    }
}

DeviceMemoryStats deviceMemoryStats()
{
    AllocationTable& t = allocationTable();
    std::lock_guard lock(t.mutex);
    return t.stats;
}

Buffer::Buffer(VkDevice device, VkBuffer buffer, VkDeviceMemory memory, VkDeviceSize size, void* mapped)
    : device_(device), buffer_(buffer), memory_(memory), size_(size), mapped_(mapped)
{
}

Buffer& Buffer::operator=(Buffer&& other) noexcept
{
    if (this != &other) {
        reset();
        device_ = other.device_;
        buffer_ = std::exchange(other.buffer_, VK_NULL_HANDLE);
        memory_ = std::exchange(other.memory_, VK_NULL_HANDLE);
        size_ = std::exchange(other.size_, 0);
        mapped_ = std::exchange(other.mapped_, nullptr);
    }
    return *this;
}

void Buffer::reset()
{
    if (buffer_)
        vkDestroyBuffer(device_, std::exchange(buffer_, VK_NULL_HANDLE), nullptr);
    if (memory_)
        freeDeviceMemory(device_, std::exchange(memory_, VK_NULL_HANDLE));
    mapped_ = nullptr;
    size_ = 0;
}

Image::Image(VkDevice device, VkImage image, VkDeviceMemory memory, VkImageView view, const ImageDesc& desc)
    : device_(device), image_(image), memory_(memory), view_(view), format_(desc.format), extent_(desc.extent),
      samples_(desc.samples)
{
}

Image& Image::operator=(Image&& other) noexcept
{
    if (this != &other) {
        reset();
        device_ = other.device_;
        image_ = std::exchange(other.image_, VK_NULL_HANDLE);
        memory_ = std::exchange(other.memory_, VK_NULL_HANDLE);
        view_ = std::exchange(other.view_, VK_NULL_HANDLE);
        format_ = other.format_;
        extent_ = other.extent_;
        samples_ = other.samples_;
    }
    return *this;
}

void Image::reset()
{
    if (view_)
        vkDestroyImageView(device_, std::exchange(view_, VK_NULL_HANDLE), nullptr);
    if (image_)
        vkDestroyImage(device_, std::exchange(image_, VK_NULL_HANDLE), nullptr);
    if (memory_)
        freeDeviceMemory(device_, std::exchange(memory_, VK_NULL_HANDLE));
}

VkImageAspectFlags Image::aspect() const
{
    return isDepthFormat(format_) ? VK_IMAGE_ASPECT_DEPTH_BIT : VK_IMAGE_ASPECT_COLOR_BIT;
}

bool isDepthFormat(VkFormat format)
{
    switch (format) {
    case VK_FORMAT_D16_UNORM:
    case VK_FORMAT_D32_SFLOAT:
    case VK_FORMAT_X8_D24_UNORM_PACK32:
        return true;
    default:
        return false;
    }
}

} // namespace wisp::vk
