// renderer/graphics/oit.h: order-independent transparency for the hair with per-pixel linked lists
// (TressFX's PPLL). Per frame:
//   oit.clear    every pixel's head pointer to nil, the pool counter to zero
//   hair         (hair_oit.frag) each fragment takes a node from the pool and links it in
//   oit.resolve    a compute pass sorts each pixel's nearest k and blends its list into one colour
//                  (compute runs on every unit of the GPU; an H100 runs graphics on few of them)
//   oit.composite  a full-screen pass lays that colour over the target (renderer/composite_pass.h)
//   oit.stats      copies the counters to the host: fragments stored and those the full pool dropped
// The pool holds nodesPerPixel x the target's pixels (automatic: 24 per pixel, at least 8M nodes); it is sized up front
// and checked against the device's limits, so a too-large request is a clear error, and an overflowing frame loses
// fragments (counted) but never writes out of bounds or loops.
#pragma once

#include "gpu/compute_stage.h"
#include "gpu/handle.h"
#include "gpu/pass.h"
#include "gpu/resources.h"
#include "renderer/oit_stats.h"
#include "shaders/shared/shadows.h"

#include <string>
#include <vector>

namespace wisp {

namespace vk {
class Context;
}
class RenderTarget;

class Oit {
public:
    // Nodes per pixel when the setting is 0 (automatic) and the device has room.
    static constexpr uint32_t kAutoNodesPerPixel = 24;
    static constexpr uint64_t kAutoMinNodes = 8u << 20;
    static constexpr VkFormat kColorFormat = kOitColorFormat; // the resolved lists (oitDeviceBytes: their memory)

    // nodesPerPixel 0: automatic (kAutoNodesPerPixel, at least kAutoMinNodes, as the device allows;
    // `autoNodes` > 0 starts it at that many nodes instead, for tests).
    Oit(const vk::Context& ctx, VkExtent2D extent, uint32_t nodesPerPixel, uint32_t framesInFlight,
        uint64_t autoNodes = 0);
    // Re-sizes the lists and the pool; the device must be idle. Throws UserError when the pool
    // would pass the device's storage-buffer range or half its memory.
    void resize(VkExtent2D extent, uint32_t nodesPerPixel);
    // An automatic pool that a frame overflowed grows to hold its fragments with a quarter to
    // spare (at least half as large again), within the device's limit; the device must be idle.
    // False when the pool is the user's (oit_nodes_per_pixel > 0) or already at the limit. A
    // re-sized picture keeps the grown pool.
    bool grow(const OitStats& overflowed);
    // The most nodes this device allows the pool.
    uint64_t limitNodes() const;

    TrackedBuffer& heads() { return headsTrack_; }
    TrackedBuffer& nodes() { return nodesTrack_; }
    TrackedBuffer& counters() { return countersTrack_; }
    TrackedImage& color() { return colorTrack_; } // the resolved hair, premultiplied RGBA16F
    const vk::Image& colorImage() const { return color_; }
    VkBuffer headsBuffer() const { return heads_; }
    VkBuffer nodesBuffer() const { return nodes_; }
    VkBuffer countersBuffer() const { return counters_; }
    uint32_t capacity() const { return capacity_; }
    VkExtent2D extent() const { return extent_; }

    // The counters copied back by the last completed frame that used `slot`.
    OitStats stats(uint32_t slot) const;
    void recordClear(VkCommandBuffer cmd) const;
    void recordStatsCopy(VkCommandBuffer cmd, uint32_t slot) const;

private:
    const vk::Context& ctx_;
    VkExtent2D extent_{};
    uint32_t capacity_ = 0;
    bool automatic_ = true;
    uint64_t autoNodes_ = 0;  // the automatic pool's start (0: kAutoNodesPerPixel, at least kAutoMinNodes)
    uint64_t grownNodes_ = 0; // what an overflowing frame grew the automatic pool to
    void allocate(VkExtent2D extent, uint64_t nodes, uint32_t nodesPerPixel);
    vk::Buffer heads_, nodes_, counters_;
    vk::Image color_;
    TrackedImage colorTrack_;
    std::vector<vk::Buffer> readback_; // one per frame in flight
    TrackedBuffer headsTrack_, nodesTrack_, countersTrack_;
};

class OitClearPass : public Pass {
public:
    explicit OitClearPass(Oit& oit) : oit_(oit) {}
    const char* name() const override { return "oit.clear"; }
    void declare(PassIo& io) override;
    void record(VkCommandBuffer cmd, FrameContext& frame) override;

private:
    Oit& oit_;
};

// A compute stage (gpu/compute_stage.h): its one list of what it touches gives its declarations
// and its descriptors.
class OitResolvePass : public Pass {
public:
    OitResolvePass(const vk::Context& ctx, Oit& oit);
    const char* name() const override { return "oit.resolve"; }
    void declare(PassIo& io) override { stage().declare(io); }
    void record(VkCommandBuffer cmd, FrameContext& frame) override;
    // oit_k, a specialization constant of the resolve (its lists stay in registers): a new value
    // builds the pipeline again, the old one retired to `frame`.
    void setK(uint32_t k, FrameContext& frame);

    // The lists' heads, nodes and counters read, the resolved colour written, and the dispatch.
    ComputeStage stage();
    const StageLayout& layout() const { return layout_; }

private:
    const vk::Context& ctx_;
    Oit& oit_;
    StageLayout layout_;
    vk::ComputeKernel kernel_;
    uint32_t k_ = 8;
};

class OitStatsPass : public Pass {
public:
    explicit OitStatsPass(Oit& oit) : oit_(oit) {}
    const char* name() const override { return "oit.stats"; }
    void declare(PassIo& io) override { io.use(oit_.counters(), Access::TransferSrc); }
    void record(VkCommandBuffer cmd, FrameContext& frame) override;

private:
    Oit& oit_;
};

} // namespace wisp
