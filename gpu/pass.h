// gpu/pass.h: what a pass is. Each pass declares the images and buffers it reads and writes
// (with the kind of access) and records its commands; gpu/frame.cpp runs passes in order and
// inserts the barriers that the declarations call for.
#pragma once

#include <vulkan/vulkan.h>

#include <vector>

namespace wisp {

struct FrameContext;

// The ways a pass touches a resource. Each maps to a stage, an access mask and, for images, a layout.
enum class Access {
    ColorAttachment,      // written (and blended) as a colour attachment
    DepthAttachment,      // depth tested and written
    DepthTestOnly,        // depth tested, not written (read-only depth layout: it can be sampled meanwhile)
    DepthSampled,         // a depth image sampled in compute shaders, in the read-only depth layout
    ResolveTarget,        // written by a multisample resolve at the end of rendering
    TransferSrc,          // copied or blitted from
    TransferDst,          // copied or blitted to
    FragmentSampled,      // sampled in fragment shaders
    GraphicsSampled,      // sampled in any graphics stage (vertex, tessellation, geometry, fragment)
    ComputeSampled,       // sampled (or fetched) in compute shaders
    ComputeRead,          // storage read in compute shaders
    ComputeWrite,         // storage write (or read-modify-write) in compute shaders
    VertexShaderRead,     // storage read in vertex, tessellation or geometry shaders
    FragmentStorageRead,  // storage read in fragment shaders
    FragmentStorageWrite, // storage write (atomics included) in fragment shaders
    VertexInput,          // read as a vertex buffer
    IndirectRead,         // read as the arguments of an indirect draw or dispatch
    Present,              // handed to the presentation engine
};

struct AccessInfo {
    VkPipelineStageFlags2 stage;
    VkAccessFlags2 access;
    VkImageLayout layout;
    bool writes;
};
AccessInfo describe(Access access);

// A resource as the frame tracks it: the last accesses since the last barrier.
struct TrackedImage {
    VkImage image = VK_NULL_HANDLE;
    VkImageAspectFlags aspect = VK_IMAGE_ASPECT_COLOR_BIT;
    bool transient = true; // contents do not survive the frame: starts each frame undefined
    VkImageLayout layout = VK_IMAGE_LAYOUT_UNDEFINED;
    VkPipelineStageFlags2 stages = VK_PIPELINE_STAGE_2_NONE;
    VkAccessFlags2 accesses = VK_ACCESS_2_NONE;
    bool written = false; // the last access set includes a write
    // Since the last write or layout transition: the stages a barrier has made it visible to.
    // A later read in another stage needs a barrier of its own, chained from these.
    VkPipelineStageFlags2 visible = VK_PIPELINE_STAGE_2_NONE;
    bool dirty = false; // a write or layout transition has happened (its visibility matters)
};

struct TrackedBuffer {
    VkBuffer buffer = VK_NULL_HANDLE;
    VkPipelineStageFlags2 stages = VK_PIPELINE_STAGE_2_NONE;
    VkAccessFlags2 accesses = VK_ACCESS_2_NONE;
    bool written = false;
    VkPipelineStageFlags2 visible = VK_PIPELINE_STAGE_2_NONE; // as for images
    bool dirty = false;
};

struct PassIo {
    struct ImageUse {
        TrackedImage* image;
        Access access;
    };
    struct BufferUse {
        TrackedBuffer* buffer;
        Access access;
    };
    std::vector<ImageUse> images;
    std::vector<BufferUse> buffers;

    void use(TrackedImage& image, Access access) { images.push_back({&image, access}); }
    void use(TrackedBuffer& buffer, Access access) { buffers.push_back({&buffer, access}); }
};

class Pass {
public:
    virtual ~Pass() = default;
    virtual const char* name() const = 0;
    virtual void declare(PassIo& io) = 0;
    virtual void record(VkCommandBuffer cmd, FrameContext& frame) = 0;
};

} // namespace wisp
