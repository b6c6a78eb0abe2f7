// gpu/compute_stage.h: a compute stage declared once, as the list of what it touches: each entry a
// (binding, resource, access). From that one list come the frame's declarations (so its barriers),
// the descriptors pushed for its kernels and, over all of an owner's stages, the descriptor set's
// layout; the stage's commands reach resources only through it (Granite's render-graph passes,
// Falcor's reflect()/execute()). Owners of several stages (renderer/compute/) write each as:
//
//   case Stage::Blur:
//       return {.uses = {storageBuffer(kBindingInput, input_, Access::ComputeRead),
//                        storageImage(kBindingOutput, outputTrack_, output_.view(), Access::ComputeWrite)},
//               .record = [this](StageCommands& c) { c.dispatch(blurKernel_, push_, groupsX, groupsY); }};
//
// A dispatch of a kernel whose shader uses a binding its stage does not list (its SPIR-V says which
// it uses: vk::ComputeKernel), and a fill, copy or indirect dispatch of a resource the stage does
// not list with that access, throw (tests/test_compute_stage.cpp shows both).
#pragma once

#include "gpu/handle.h"
#include "gpu/pass.h"
#include "gpu/pipeline.h"

#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <vector>

namespace wisp {

namespace vk {
class Buffer;
class Context;
} // namespace vk

// One entry of a stage's list. Tracked resources (a TrackedBuffer or TrackedImage) are declared to
// the frame, which derives the barriers; untracked ones need none: uniform blocks the host writes
// (one per frame in flight), and buffers and images written outside the frames' passes (by a
// submission of their own) that stages only read. Make entries with the functions below.
struct StageUse {
    static constexpr uint32_t kNoBinding = ~0u;
    uint32_t binding = kNoBinding; // kNoBinding: reached by a command (fill, copy, indirect arguments)
    VkDescriptorType type = VK_DESCRIPTOR_TYPE_MAX_ENUM;
    Access access = Access::ComputeRead;
    TrackedBuffer* buffer = nullptr;
    TrackedImage* image = nullptr;
    VkDescriptorBufferInfo bufferInfo{};             // an untracked buffer
    VkDescriptorImageInfo imageInfo{};               // an image: its view, sampler and layout
    std::span<const VkDescriptorBufferInfo> perSlot; // a uniform block per frame in flight
    bool bound = true; // false: in the layout, but neither declared nor written this time (see when())

    // Listed (its binding is in the layout) and used only while `condition` holds: a stage whose
    // kernel variant reads it in some frames and not in others.
    StageUse when(bool condition) const
    {
        StageUse u = *this;
        u.bound = condition;
        return u;
    }
    bool tracked() const { return buffer || image; }
};

// A storage buffer the stage's kernels read (Access::ComputeRead) or write (ComputeWrite).
StageUse storageBuffer(uint32_t binding, TrackedBuffer& buffer, Access access);
// A storage image read (ComputeRead) or written (ComputeWrite), in the general layout.
StageUse storageImage(uint32_t binding, TrackedImage& image, VkImageView view, Access access);
// A sampled image (ComputeSampled, or DepthSampled for a depth image in its read-only layout).
StageUse sampledImage(uint32_t binding, TrackedImage& image, VkImageView view, VkSampler sampler,
                      Access access = Access::ComputeSampled);
// A uniform block the host writes: one per frame in flight (the frame's slot picks it), or one.
StageUse uniformBlock(uint32_t binding, std::span<const VkDescriptorBufferInfo> perSlot);
StageUse uniformBlock(uint32_t binding, VkBuffer buffer);
// A storage buffer, or a sampled image, written by a submission of its own and only read by
// stages: no barrier (the meshes' vertices, the guides' triangles, the lookup tables).
StageUse constantBuffer(uint32_t binding, VkBuffer buffer);
StageUse constantImage(uint32_t binding, const VkDescriptorImageInfo& info);
// A resource the stage's commands touch outside its descriptors: TransferSrc/TransferDst for fills
// and copies, IndirectRead for a dispatch's arguments.
StageUse commandUse(TrackedBuffer& buffer, Access access);
StageUse commandUse(TrackedImage& image, Access access);

class StageCommands;

// A compute stage: what it touches, and its commands.
struct ComputeStage {
    std::vector<StageUse> uses;
    std::function<void(StageCommands&)> record;

    // Each tracked resource the stage uses, once per access, in the order listed.
    void declare(PassIo& io) const;
};

// The commands a stage may record: each dispatch binds its pipeline and pushes the descriptors of
// the stage's bound entries (those and no others), and every other command checks the resources it
// names against the list, throwing std::logic_error for one not listed with that access.
class StageCommands {
public:
    StageCommands(const vk::Context& ctx, VkPipelineLayout layout, VkCommandBuffer cmd, uint32_t slot,
                  const ComputeStage& stage, std::string name);

    // `push` is the whole push-constant block; x or y of 0 dispatches nothing. Every binding the
    // kernel's shader uses must be one the stage lists (else it would read whatever an earlier
    // stage pushed there, undeclared): one it does not list throws.
    template <typename Push>
    void dispatch(const vk::ComputeKernel& kernel, const Push& push, uint32_t x, uint32_t y = 1)
    {
        if (x == 0 || y == 0)
            return;
        bind(kernel, &push, sizeof(push));
        vkCmdDispatch(cmd_, x, y, 1);
    }
    // The dispatch whose groups `arguments` (listed as IndirectRead) holds at `offset`.
    template <typename Push>
    void dispatchIndirect(const vk::ComputeKernel& kernel, const Push& push, TrackedBuffer& arguments,
                          VkDeviceSize offset)
    {
        require(arguments, Access::IndirectRead, "takes its dispatch from");
        bind(kernel, &push, sizeof(push));
        vkCmdDispatchIndirect(cmd_, arguments.buffer, offset);
    }
    // The whole buffer set to `value` (listed as TransferDst).
    void fill(TrackedBuffer& buffer, uint32_t value);
    void copyBufferToImage(TrackedBuffer& src, TrackedImage& dst, const VkBufferImageCopy& region);
    void copyImage(TrackedImage& src, TrackedImage& dst, const VkImageCopy& region);
    // `bytes` of `src` (TransferSrc) into a host-visible buffer, readable once the frame's fence signals.
    void copyToHost(TrackedBuffer& src, const vk::Buffer& host, VkDeviceSize bytes);
    // The untracked buffer the stage lists at `binding` replaced for the next dispatches (one mesh a draw).
    void setConstantBuffer(uint32_t binding, VkBuffer buffer);

    uint32_t slot() const { return slot_; } // the frame's slot in flight

private:
    void bind(const vk::ComputeKernel& kernel, const void* push, uint32_t bytes);
    void require(const TrackedBuffer& buffer, Access access, const char* verb) const;
    void require(const TrackedImage& image, Access access, const char* verb) const;

    const vk::Context& ctx_;
    VkPipelineLayout layout_;
    VkCommandBuffer cmd_;
    uint32_t slot_;
    const ComputeStage& stage_;
    std::string name_;
    std::vector<VkDescriptorBufferInfo> bufferInfos_; // one per entry (the writes point into them)
    std::vector<VkDescriptorImageInfo> imageInfos_;
    std::vector<VkWriteDescriptorSet> writes_;
};

// The pipeline layout an owner's stages share: one push-descriptor set holding every binding any of
// its stages lists (two stages giving one binding different types is an error), and push constants.
class StageLayout {
public:
    StageLayout() = default;
    StageLayout(const vk::Context& ctx, std::span<const ComputeStage> stages, uint32_t pushConstantBytes,
                const char* name);
    VkPipelineLayout layout() const { return layout_; }
    // The bindings it holds, by number.
    const std::vector<uint32_t>& bindings() const { return bindings_; }
    void record(const ComputeStage& stage, VkCommandBuffer cmd, uint32_t slot, const std::string& name) const;

private:
    const vk::Context* ctx_ = nullptr;
    vk::DescriptorSetLayout setLayout_;
    vk::PipelineLayout layout_;
    std::vector<uint32_t> bindings_;
};

// A stage run as one of the frame's passes: `describe` gives its list each time it is declared and
// recorded (so a resource remade between frames is the one bound).
class ComputeStagePass : public Pass {
public:
    ComputeStagePass(std::string name, const StageLayout& layout, std::function<ComputeStage()> describe)
        : name_(std::move(name)), layout_(layout), describe_(std::move(describe))
    {
    }
    const char* name() const override { return name_.c_str(); }
    void declare(PassIo& io) override { describe_().declare(io); }
    void record(VkCommandBuffer cmd, FrameContext& frame) override;

private:
    std::string name_;
    const StageLayout& layout_;
    std::function<ComputeStage()> describe_;
};

} // namespace wisp
