// renderer/graphics/oit.cpp: the linked lists' buffers, their sizing and limits, and the clear, resolve
// and statistics passes.
#include "renderer/graphics/oit.h"

#include "core/error.h"
#include "gpu/check.h"
#include "gpu/context.h"
#include "gpu/frame.h"
#include "gpu/pipeline.h"
#include "renderer/render_target.h"

#include <algorithm>
#include <array>
#include <cstring>
#include <string>

namespace wisp {

namespace {

struct ResolvePush {
    uint32_t width;
    uint32_t height;
    uint32_t k;
    uint32_t maxWalk;
};

std::string mib(uint64_t bytes)
{
    return std::to_string((bytes + (1u << 20) - 1) >> 20) + " MiB";
}

} // namespace

std::string oitOverflowAdvice(const OitStats& s, uint32_t width, uint32_t height)
{
    uint64_t pixels = std::max<uint64_t>(uint64_t(width) * height, 1);
    std::string what = "the OIT pool was full: " + std::to_string(s.overflow) + " of " + std::to_string(s.fragments) +
                       " hair fragments were dropped; ";
    uint64_t needed = s.fragments + s.fragments / 8; // the fragments with some to spare
    if (!s.automatic && needed <= s.limit)
        return what + "raise oit_nodes_per_pixel to " + std::to_string((needed + pixels - 1) / pixels) +
               " (--set oit_nodes_per_pixel=N, or 0: automatic, grown as frames need)";
    return what + "the device allows a pool of at most " + std::to_string(s.limit) + " nodes (" +
           std::to_string(s.limit / pixels) +
           " per pixel here), fewer than this frame needs; use --set transparency=msaa "
           "(no pool) or a smaller picture";
}

Oit::Oit(const vk::Context& ctx, VkExtent2D extent, uint32_t nodesPerPixel, uint32_t framesInFlight, uint64_t autoNodes)
    : ctx_(ctx), autoNodes_(autoNodes)
{
    for (uint32_t i = 0; i < framesInFlight; ++i)
        readback_.push_back(ctx.createBuffer({.size = sizeof(gpu::OitCounters),
                                              .usage = vk::kTransferDst,
                                              .memory = vk::Memory::Readback,
                                              .name = "oit.counters.readback"}));
    for (vk::Buffer& b : readback_)
        std::memset(b.mapped(), 0, sizeof(gpu::OitCounters));
    resize(extent, nodesPerPixel);
}

uint64_t Oit::limitNodes() const
{
    const vk::DeviceReport& device = ctx_.report();
    // What one buffer may hold on this device, and at most half of its memory.
    uint64_t limit = device.maxStorageBufferRange;
    if (device.deviceLocalBytes > 0)
        limit = std::min<uint64_t>(limit, device.deviceLocalBytes / 2);
    return std::min<uint64_t>(limit / sizeof(gpu::OitNode), gpu::kOitNil - 1);
}

void Oit::resize(VkExtent2D extent, uint32_t requestedNodesPerPixel)
{
    uint64_t pixels = uint64_t(extent.width) * extent.height;
    const vk::DeviceReport& device = ctx_.report();
    uint64_t limitBytes = limitNodes() * sizeof(gpu::OitNode);
    uint32_t nodesPerPixel = requestedNodesPerPixel;
    uint64_t nodes = pixels * nodesPerPixel;
    automatic_ = nodesPerPixel == 0;
    if (automatic_) {
        // Automatic: kAutoNodesPerPixel per pixel but never fewer than kAutoMinNodes (small
        // pictures of a full head hold many fragments per pixel), or what a frame needed, within
        // what the device allows.
        uint64_t wanted = autoNodes_ > 0 ? autoNodes_ : std::max<uint64_t>(pixels * kAutoNodesPerPixel, kAutoMinNodes);
        wanted = std::max(wanted, grownNodes_);
        nodes = std::max<uint64_t>(std::min<uint64_t>(wanted, limitNodes()), pixels);
        nodesPerPixel = uint32_t((nodes + pixels - 1) / pixels);
    }
    uint64_t bytes = nodes * sizeof(gpu::OitNode);
    if (nodes >= gpu::kOitNil || bytes > limitBytes)
        throw UserError("the OIT fragment pool (" + std::to_string(extent.width) + " x " +
                        std::to_string(extent.height) + " pixels x " + std::to_string(std::max(nodesPerPixel, 1u)) +
                        " nodes of " + std::to_string(sizeof(gpu::OitNode)) + " bytes = " + mib(bytes) +
                        ") is larger than '" + device.name + "' allows (" + mib(limitBytes) +
                        ": one storage buffer, at most half the device memory); lower oit_nodes_per_pixel or the "
                        "resolution, or use transparency=msaa");
    allocate(extent, nodes, nodesPerPixel);
}

bool Oit::grow(const OitStats& overflowed)
{
    if (!automatic_ || overflowed.overflow == 0)
        return false;
    uint64_t wanted = std::max(overflowed.fragments + overflowed.fragments / 4, uint64_t(capacity_) + capacity_ / 2);
    uint64_t nodes = std::min(wanted, limitNodes());
    if (nodes <= capacity_)
        return false;
    grownNodes_ = nodes;
    uint64_t pixels = uint64_t(extent_.width) * extent_.height;
    allocate(extent_, nodes, uint32_t((nodes + pixels - 1) / pixels));
    return true;
}

void Oit::allocate(VkExtent2D extent, uint64_t nodes, uint32_t)
{
    uint64_t pixels = uint64_t(extent.width) * extent.height;
    uint64_t bytes = nodes * sizeof(gpu::OitNode);
    extent_ = extent;
    capacity_ = uint32_t(nodes);
    heads_ = ctx_.createBuffer(
        {.size = pixels * sizeof(uint32_t), .usage = vk::kStorage | vk::kTransferDst, .name = "oit.heads"});
    nodes_ = ctx_.createBuffer({.size = bytes, .usage = vk::kStorage, .name = "oit.nodes"});
    counters_ = ctx_.createBuffer({.size = sizeof(gpu::OitCounters),
                                   .usage = vk::kStorage | vk::kTransferDst | vk::kTransferSrc,
                                   .name = "oit.counters"});
    color_ = ctx_.createImage({.format = kColorFormat,
                               .extent = extent,
                               .usage = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT,
                               .name = "oit.color"});
    colorTrack_ = {.image = color_.get()};
    headsTrack_ = {.buffer = heads_};
    nodesTrack_ = {.buffer = nodes_};
    countersTrack_ = {.buffer = counters_};
}

OitStats Oit::stats(uint32_t slot) const
{
    gpu::OitCounters c{};
    std::memcpy(&c, readback_.at(slot).mapped(), sizeof(c));
    return {.fragments = c.allocated,
            .overflow = c.overflow,
            .capacity = capacity_,
            .limit = limitNodes(),
            .automatic = automatic_};
}

void Oit::recordClear(VkCommandBuffer cmd) const
{
    vkCmdFillBuffer(cmd, heads_, 0, VK_WHOLE_SIZE, gpu::kOitNil);
    gpu::OitCounters c{.allocated = 0, .overflow = 0, .capacity = capacity_, .pad = 0};
    vkCmdUpdateBuffer(cmd, counters_, 0, sizeof(c), &c);
}

void Oit::recordStatsCopy(VkCommandBuffer cmd, uint32_t slot) const
{
    VkBufferCopy region{0, 0, sizeof(gpu::OitCounters)};
    vkCmdCopyBuffer(cmd, counters_, readback_.at(slot), 1, &region);
    vk::transferToHostBarrier(cmd);
}

void OitClearPass::declare(PassIo& io)
{
    io.use(oit_.heads(), Access::TransferDst);
    io.use(oit_.counters(), Access::TransferDst);
}

void OitClearPass::record(VkCommandBuffer cmd, FrameContext&)
{
    oit_.recordClear(cmd);
}

void OitStatsPass::record(VkCommandBuffer cmd, FrameContext& frame)
{
    oit_.recordStatsCopy(cmd, frame.slot);
}

OitResolvePass::OitResolvePass(const vk::Context& ctx, Oit& oit) : ctx_(ctx), oit_(oit)
{
    ComputeStage resolve = stage(); // (the layout holds the bindings it lists)
    layout_ = StageLayout(ctx, std::span(&resolve, 1), sizeof(ResolvePush), "oit.resolve.layout");
    kernel_ = vk::createComputeKernel(ctx, layout_.layout(), "oit_resolve.comp", "oit.resolve.pipeline", {k_});
}

void OitResolvePass::setK(uint32_t k, FrameContext& frame)
{
    k = std::clamp(k, 1u, gpu::kMaxOitK);
    if (k == k_)
        return;
    k_ = k;
    frame.retire(std::move(kernel_.pipeline));
    kernel_ = vk::createComputeKernel(ctx_, layout_.layout(), "oit_resolve.comp", "oit.resolve.pipeline", {k_});
}

ComputeStage OitResolvePass::stage()
{
    using enum Access;
    using namespace gpu; // the bindings: shaders/shared/shadows.h
    return {.uses = {storageBuffer(kOitResolveBindingHeads, oit_.heads(), ComputeRead),
                     storageBuffer(kOitResolveBindingNodes, oit_.nodes(), ComputeRead),
                     storageBuffer(kOitResolveBindingCounters, oit_.counters(), ComputeRead),
                     storageImage(kOitResolveBindingColor, oit_.color(), oit_.colorImage().view(), ComputeWrite)},
            .record = [this](StageCommands& c) {
                // A list can never hold more nodes than the pool; the bound also keeps a corrupted list finite.
                VkExtent2D e = oit_.extent();
                ResolvePush push{.width = e.width, .height = e.height, .k = k_, .maxWalk = oit_.capacity()};
                c.dispatch(kernel_, push, vk::groupCount(e.width, 8), vk::groupCount(e.height, 8));
            }};
}

void OitResolvePass::record(VkCommandBuffer cmd, FrameContext& frame)
{
    layout_.record(stage(), cmd, frame.slot, name());
}

} // namespace wisp
