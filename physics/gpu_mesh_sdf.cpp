// physics/gpu_mesh_sdf.cpp: the field's build on the device (see the header).
#include "physics/gpu_mesh_sdf.h"

#include "gpu/context.h"
#include "gpu/pipeline.h"

#include <cstring>

namespace wisp {

namespace {

const char* const kStageNames[] = {"sdf.clear", "sdf.splat", "sdf.sign"};

// A storage buffer holding `data` (at least one element's worth: Vulkan has no empty buffers).
template <typename T> vk::Buffer constantStorage(const vk::Context& ctx, const std::vector<T>& data, const char* name)
{
    std::vector<T> padded = data.empty() ? std::vector<T>(1) : data;
    return ctx.createBufferWithData({.size = padded.size() * sizeof(T), .usage = vk::kStorage, .name = name},
                                    padded.data(), padded.size() * sizeof(T));
}

} // namespace

GpuMeshSdf::GpuMeshSdf(const vk::Context& ctx, const SdfPlan& plan)
    : ctx_(ctx), grid_(plan.grid), rows_(uint32_t(plan.rowCount()))
{
    triangles_ = constantStorage(ctx, plan.triangles, "sdf.triangles");
    items_ = constantStorage(ctx, plan.items, "sdf.items");
    VkDeviceSize bytes = VkDeviceSize(plan.nodeCount()) * sizeof(uint32_t);
    keys_ = ctx.createBuffer({.size = bytes, .usage = vk::kStorage | vk::kTransferDst, .name = "sdf.keys"});
    field_ = ctx.createBuffer({.size = bytes, .usage = vk::kStorage | vk::kTransferSrc, .name = "sdf.field"});
    keysTrack_.buffer = keys_;
    fieldTrack_.buffer = field_;

    std::vector<ComputeStage> stages;
    for (int s = 0; s < kStages; ++s)
        stages.push_back(stage(s));
    layout_ = StageLayout(ctx, stages, sizeof(gpu::SdfGrid), "sdf.layout");
    splat_ = vk::createComputeKernel(ctx, layout_.layout(), "mesh_sdf_splat.comp", "sdf.splat.pipeline");
    sign_ = vk::createComputeKernel(ctx, layout_.layout(), "mesh_sdf_sign.comp", "sdf.sign.pipeline");

    std::vector<std::unique_ptr<ComputeStagePass>> passes;
    std::vector<Pass*> list;
    for (int s = 0; s < kStages; ++s) {
        passes.push_back(std::make_unique<ComputeStagePass>(kStageNames[s], layout_, [this, s] { return stage(s); }));
        list.push_back(passes.back().get());
    }
    Frame frame(ctx, 1);
    FrameContext& fc = frame.begin({});
    frame.run(fc, list);
    frame.submit(fc);
    frame.waitIdle();
    for (const vk::ScopeTime& t : frame.timings())
        buildMs_ += t.milliseconds;
}

ComputeStage GpuMeshSdf::stage(int which)
{
    switch (which) {
    case kClear:
        return {.uses = {commandUse(keysTrack_, Access::TransferDst)},
                .record = [this](StageCommands& c) { c.fill(keysTrack_, gpu::kSdfNoKey); }};
    case kSplat:
        return {.uses = {constantBuffer(gpu::kSdfBindingTriangles, triangles_),
                         constantBuffer(gpu::kSdfBindingItems, items_),
                         storageBuffer(gpu::kSdfBindingKeys, keysTrack_, Access::ComputeWrite)},
                .record = [this](StageCommands& c) {
                    c.dispatch(splat_, grid_, vk::groupCount(grid_.counts.x, gpu::kSdfGroupSize));
                }};
    default:
        return {.uses = {constantBuffer(gpu::kSdfBindingTriangles, triangles_),
                         storageBuffer(gpu::kSdfBindingKeys, keysTrack_, Access::ComputeRead),
                         storageBuffer(gpu::kSdfBindingField, fieldTrack_, Access::ComputeWrite)},
                .record = [this](StageCommands& c) {
                    c.dispatch(sign_, grid_, vk::groupCount(rows_, gpu::kSdfGroupSize));
                }};
    }
}

MeshSdf GpuMeshSdf::read() const
{
    MeshSdf out;
    out.grid = grid_;
    size_t nodes = size_t(grid_.dims.x) * grid_.dims.y * grid_.dims.z;
    vk::Buffer host = ctx_.createBuffer({.size = nodes * sizeof(float),
                                         .usage = vk::kTransferDst,
                                         .memory = vk::Memory::Readback,
                                         .name = "sdf.readback"});
    ctx_.submitAndWait([&](VkCommandBuffer cmd) {
        vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, VK_ACCESS_2_MEMORY_WRITE_BIT,
                          VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_READ_BIT);
        VkBufferCopy region{0, 0, nodes * sizeof(float)};
        vkCmdCopyBuffer(cmd, field_.get(), host.get(), 1, &region);
        vk::transferToHostBarrier(cmd);
    });
    out.values.resize(nodes);
    std::memcpy(out.values.data(), host.mapped(), nodes * sizeof(float));
    return out;
}

} // namespace wisp
