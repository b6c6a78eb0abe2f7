// gpu/frame.h: the frame loop's per-slot state (command buffer, fence, deletion list, GPU
// timer) and the pass runner. Frame::run calls each pass's declare(), emits one pipeline barrier
// for the hazards those declarations imply, then brackets the pass's record() with timestamps.
#pragma once

#include "gpu/handle.h"
#include "gpu/pass.h"
#include "gpu/resources.h"
#include "gpu/timestamps.h"

#include <cstdint>
#include <span>
#include <variant>
#include <vector>

namespace wisp {

namespace vk {
class Context;
}

// Owners that must outlive the GPU's use of them: freed when their frame's fence has signalled.
using Retired = std::variant<vk::Buffer, vk::Image, vk::Pipeline, vk::PipelineLayout, vk::DescriptorSetLayout,
                             vk::ImageView, vk::Sampler>;

struct FrameContext {
    VkCommandBuffer cmd = VK_NULL_HANDLE;
    uint32_t slot = 0;        // which in-flight slot, for per-slot buffers
    uint64_t frameNumber = 0; // frames begun since the start
    std::vector<Retired> retired;
    template <typename T> void retire(T&& owner) { retired.emplace_back(std::forward<T>(owner)); }
};

class Frame {
public:
    // Timed scopes a frame holds at most: every pass is one (the compute path records up to 64
    // pieces of two passes each).
    static constexpr uint32_t kMaxScopes = 192;

    Frame(const vk::Context& ctx, uint32_t framesInFlight);
    ~Frame();
    Frame(const Frame&) = delete;
    Frame& operator=(const Frame&) = delete;

    uint32_t framesInFlight() const { return static_cast<uint32_t>(slots_.size()); }

    // Waits for the slot's previous use, frees what it retired, and begins its command buffer.
    // `transientImages` start the frame undefined (so the first pass writing them clears them).
    FrameContext& begin(std::span<TrackedImage* const> transientImages);
    void run(FrameContext& frame, std::span<Pass* const> passes);
    // A barrier outside any pass, e.g. a swapchain image to Present.
    void transition(FrameContext& frame, TrackedImage& image, Access access);
    void submit(FrameContext& frame, VkSemaphore wait = VK_NULL_HANDLE,
                VkPipelineStageFlags2 waitStage = VK_PIPELINE_STAGE_2_NONE, VkSemaphore signal = VK_NULL_HANDLE);
    void waitIdle();
    // Per-pass GPU times of the most recently completed frame (after begin() or waitIdle()).
    const std::vector<vk::ScopeTime>& timings() const { return timings_; }

private:
    struct Slot {
        vk::CommandPool pool;
        vk::Fence fence;
        vk::GpuTimer timer;
        FrameContext context;
        bool submitted = false;
    };
    void retireSlot(Slot& slot);
    void barrier(VkCommandBuffer cmd, const PassIo& io);

    const vk::Context& ctx_;
    std::vector<Slot> slots_;
    uint64_t frameNumber_ = 0;
    std::vector<vk::ScopeTime> timings_;
};

} // namespace wisp
