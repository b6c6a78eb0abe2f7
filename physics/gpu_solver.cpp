// physics/gpu_solver.cpp: buffer creation, pipelines and the recorded dispatch sequence.
#include "physics/gpu_solver.h"

#include "core/error.h"
#include "gpu/check.h"
#include "gpu/context.h"
#include "gpu/pipeline.h"
#include "physics/cpu_solver.h"

#include <algorithm>
#include <array>
#include <cstring>

namespace wisp {

namespace {

uint64_t mebibytes(uint64_t bytes)
{
    return (bytes + (uint64_t(1) << 20) - 1) >> 20;
}

// Strand-major (the CPU's order) to the GPU's interleaved slots (gpu::vertexSlot), and back.
template <typename T> std::vector<T> toSlots(const std::vector<T>& strandMajor, uint32_t strands, uint32_t V, T padding)
{
    std::vector<T> out(size_t(gpu::paddedStrandCount(strands)) * V, padding);
    for (uint32_t s = 0; s < strands; ++s)
        for (uint32_t i = 0; i < V; ++i)
            out[gpu::vertexSlot(s, i, V)] = strandMajor[size_t(s) * V + i];
    return out;
}

template <typename T> std::vector<T> fromSlots(const std::vector<T>& slots, uint32_t strands, uint32_t V)
{
    std::vector<T> out(size_t(strands) * V);
    for (uint32_t s = 0; s < strands; ++s)
        for (uint32_t i = 0; i < V; ++i)
            out[size_t(s) * V + i] = slots[gpu::vertexSlot(s, i, V)];
    return out;
}

} // namespace

GpuSolver::GpuSolver(const vk::Context& ctx, const StrandSet& strands, const SimSetup& setup,
                     const glm::mat4& headTransform)
    : ctx_(ctx), setup_(setup), model_(strands), vertexCount_(uint32_t(strands.vertexCount()))
{
    // The grid's sums: fixed point where asked for and possible, else float atomics (and back).
    bool wantFixed = setup.params.gridFixedScale > 0.0f;
    fixedGrid_ = wantFixed ? ctx.report().int64Atomics : !ctx.report().floatAtomicAdd;
    if (fixedGrid_ && !ctx.report().int64Atomics)
        throw UserError("the Vulkan device '" + ctx.report().name +
                        "' has neither float nor 64-bit integer buffer atomics, which the hair-hair grid needs");
    if (fixedGrid_ && setup_.params.gridFixedScale <= 0.0f)
        setup_.params.gridFixedScale = gridFixedScale(strands.vertexCount(), setup_.params.gridMaxSplatSpeed);
    if (!fixedGrid_)
        setup_.params.gridFixedScale = 0.0f;
    // Refused before anything is allocated, here or on the device.
    deviceBytes_ =
        solverDeviceBytes(strands.strandCount(), strands.verticesPerStrand, setup.params.gridNodeCount, fixedGrid_);
    if (deviceBytes_ > ctx.report().deviceLocalBytes)
        throw UserError("the simulation needs " + std::to_string(mebibytes(deviceBytes_)) + " MiB of GPU memory (" +
                        std::to_string(strands.strandCount()) + " strands x " +
                        std::to_string(strands.verticesPerStrand) + " vertices, " +
                        std::to_string(setup.params.gridNodeCount) + " grid nodes), but '" + ctx.report().name +
                        "' has " + std::to_string(mebibytes(ctx.report().deviceLocalBytes)) + " MiB");
    uint32_t count = uint32_t(strands.strandCount());
    uint32_t V = strands.verticesPerStrand;
    SimState strandMajor = initialState(strands, headTransform);
    SimState initial; // in slots; padding slots are pinned (w = 0) and never touched
    initial.positions = toSlots(strandMajor.positions, count, V, glm::vec4(0.0f));
    initial.velocities = toSlots(strandMajor.velocities, count, V, glm::vec4(0.0f));
    initial.tangents = toSlots(strandMajor.tangents, count, V, glm::vec4(0.0f));
    std::vector<gpu::RestVertex> rest =
        toSlots(restVertices(strands), count, V, gpu::RestVertex{glm::vec3(0.0f), 1.0f});
    slotCount_ = uint32_t(initial.positions.size());
    size_t vec4Bytes = size_t(slotCount_) * sizeof(glm::vec4);
    size_t gridBytes = size_t(setup.params.gridNodeCount) *
                       (fixedGrid_ ? gpu::kGridFixedWordsPerNode * sizeof(int64_t) : sizeof(gpu::GridNode));

    constexpr VkBufferUsageFlags kStorageCopy = vk::kStorage | vk::kTransferSrc | vk::kTransferDst;
    params_ = ctx.createBufferWithData({.size = sizeof(gpu::SimParams), .usage = vk::kUniform, .name = "sim.params"},
                                       &setup_.params, sizeof(gpu::SimParams));
    positions_ =
        ctx.createBufferWithData({.size = vec4Bytes, .usage = kStorageCopy | vk::kVertex, .name = "guide.positions"},
                                 initial.positions.data(), vec4Bytes);
    velocities_ = ctx.createBufferWithData({.size = vec4Bytes, .usage = kStorageCopy, .name = "guide.velocities"},
                                           initial.velocities.data(), vec4Bytes);
    tangents_ =
        ctx.createBufferWithData({.size = vec4Bytes, .usage = kStorageCopy | vk::kVertex, .name = "guide.tangents"},
                                 initial.tangents.data(), vec4Bytes);
    rest_ = ctx.createBufferWithData(
        {.size = rest.size() * sizeof(gpu::RestVertex), .usage = kStorageCopy, .name = "guide.rest"}, rest.data(),
        rest.size() * sizeof(gpu::RestVertex));
    strands_ = ctx.createBufferWithData(
        {.size = strands.strands.size() * sizeof(gpu::StrandInfo), .usage = kStorageCopy, .name = "guide.strands"},
        strands.strands.data(), strands.strands.size() * sizeof(gpu::StrandInfo));
    // Both sets of sums start at zero: the first step splats into one, its gather zeroes the other.
    std::vector<uint8_t> zeroGrid(gridBytes, 0);
    for (size_t i = 0; i < grids_.size(); ++i)
        grids_[i] = ctx.createBufferWithData(
            {.size = gridBytes, .usage = kStorageCopy, .name = i == 0 ? "grid.sums.0" : "grid.sums.1"}, zeroGrid.data(),
            gridBytes);
    // The head mesh's field, built here by its own kernels when the setup asks for one.
    if (setup.sdf)
        sdf_ = std::make_unique<GpuMeshSdf>(ctx, *setup.sdf);
    float none = 0.0f;
    sdfNone_ = ctx.createBufferWithData({.size = sizeof(float), .usage = vk::kStorage, .name = "sim.sdf.none"}, &none,
                                        sizeof(float));
    gpu::SimCounters zero{};
    counters_ = ctx.createBufferWithData(
        {.size = sizeof(gpu::SimCounters), .usage = kStorageCopy, .name = "sim.counters"}, &zero, sizeof(zero));
    positionsTrack_ = {.buffer = positions_.get()};
    velocitiesTrack_ = {.buffer = velocities_.get()};
    tangentsTrack_ = {.buffer = tangents_.get()};
    countersTrack_ = {.buffer = counters_.get()};
    for (size_t i = 0; i < grids_.size(); ++i)
        gridTracks_[i] = {.buffer = grids_[i].get()};

    // The layout holds every binding the stages list.
    std::vector<ComputeStage> stages;
    for (Stage s : kStages)
        stages.push_back(stage(s, {}, 0));
    layout_ = StageLayout(ctx, stages, sizeof(gpu::SimStep), "sim.layout");
    createPipelines();
}

void GpuSolver::createPipelines()
{
    const vk::Context& ctx = ctx_;
    // The fixed-point grid's kernels are separate SPIR-V (they need 64-bit integer atomics, the
    // float ones need float atomics).
    std::string variant = fixedGrid_ ? "_fixed" : "";
    integrate_ = vk::createComputeKernel(ctx, layout_.layout(), "sim_integrate" + variant + ".comp", "sim.integrate");
    gather_ = vk::createComputeKernel(ctx, layout_.layout(), "grid_gather" + variant + ".comp", "grid.gather");
}

void GpuSolver::reloadPipelines()
{
    createPipelines();
}

void GpuSolver::reset(const glm::mat4& headTransform)
{
    uint32_t count = uint32_t(model_.strandCount());
    uint32_t V = model_.verticesPerStrand;
    SimState strandMajor = initialState(model_, headTransform);
    std::vector<glm::vec4> positions = toSlots(strandMajor.positions, count, V, glm::vec4(0.0f));
    std::vector<glm::vec4> velocities = toSlots(strandMajor.velocities, count, V, glm::vec4(0.0f));
    std::vector<glm::vec4> tangents = toSlots(strandMajor.tangents, count, V, glm::vec4(0.0f));
    size_t bytes = positions.size() * sizeof(glm::vec4);
    vk::Buffer staging = ctx_.createBuffer(
        {.size = 3 * bytes, .usage = vk::kTransferSrc, .memory = vk::Memory::Upload, .name = "guide.reset.staging"});
    char* mapped = static_cast<char*>(staging.mapped());
    std::memcpy(mapped, positions.data(), bytes);
    std::memcpy(mapped + bytes, velocities.data(), bytes);
    std::memcpy(mapped + 2 * bytes, tangents.data(), bytes);
    ctx_.submitAndWait([&](VkCommandBuffer cmd) {
        VkBufferCopy region{0, 0, bytes};
        vkCmdCopyBuffer(cmd, staging, positions_, 1, &region);
        region.srcOffset = bytes;
        vkCmdCopyBuffer(cmd, staging, velocities_, 1, &region);
        region.srcOffset = 2 * bytes;
        vkCmdCopyBuffer(cmd, staging, tangents_, 1, &region);
        for (const vk::Buffer& grid : grids_) // the turns start again from zeroed sums
            vkCmdFillBuffer(cmd, grid, 0, VK_WHOLE_SIZE, 0);
    });
    turn_ = 0;
}

ComputeStage GpuSolver::stage(Stage stage, const gpu::SimStep& step, uint32_t turn)
{
    using enum Access;
    using namespace gpu; // the bindings: shaders/shared/sim.h
    // Both kernels bind every buffer but the mesh's field (shaders/sim_common.glsl, grid_storage.glsl);
    // the ones a kernel leaves alone are listed as read, the least access.
    bool integrate = stage == Stage::Integrate;
    Access writtenByIntegrate = integrate ? ComputeWrite : ComputeRead;
    TrackedBuffer& sums = gridTracks_[turn];
    TrackedBuffer& next = gridTracks_[1 - turn];
    const SimParams& p = setup_.params;
    // The integrate's threads take a strand each; the gather's a vertex slot and a node of the next sums.
    uint32_t groups = integrate ? vk::groupCount(p.strandCount, kSimGroupSize)
                                : vk::groupCount(std::max(slotCount_, p.gridNodeCount), kSimGroupSize);
    ComputeStage out{
        .uses = {uniformBlock(kSimBindingParams, params_.get()),
                 storageBuffer(kSimBindingPositions, positionsTrack_, writtenByIntegrate),
                 storageBuffer(kSimBindingVelocities, velocitiesTrack_, ComputeWrite),
                 constantBuffer(kSimBindingRest, rest_.get()), constantBuffer(kSimBindingStrands, strands_.get()),
                 storageBuffer(kSimBindingTangents, tangentsTrack_, writtenByIntegrate),
                 storageBuffer(kSimBindingGrid, sums, writtenByIntegrate), // splatted, then gathered
                 storageBuffer(kSimBindingGridNext, next, integrate ? ComputeRead : ComputeWrite), // zeroed
                 storageBuffer(kSimBindingCounters, countersTrack_, writtenByIntegrate)},
        .record = [this, integrate, step, groups](StageCommands& c) {
            c.dispatch(integrate ? integrate_ : gather_, step, groups);
        }};
    // The head mesh's field (or a stand-in when there is none): only the integrate reads it.
    if (integrate)
        out.uses.push_back(constantBuffer(kSimBindingSdf, sdf_ ? sdf_->field() : sdfNone_.get()));
    return out;
}

void GpuSolver::declare(PassIo& io)
{
    for (Stage s : kStages)
        stage(s, {}, turn_).declare(io);
}

uint32_t GpuSolver::takeTurn()
{
    uint32_t turn = turn_;
    turn_ = 1 - turn_;
    return turn;
}

void GpuSolver::recordStep(VkCommandBuffer cmd, const gpu::SimStep& step, vk::GpuTimer* timer)
{
    // This step splats into grids_[turn_]; its gather reads them and zeroes the other set.
    uint32_t turn = takeTurn();
    for (Stage s : kStages) {
        const char* scope = scopeName(s);
        if (timer)
            timer->begin(cmd, scope);
        layout_.record(stage(s, step, turn), cmd, 0, scope);
        vk::computeToComputeBarrier(cmd); // the gather reads the splat; the next integrate, the gather
        if (timer)
            timer->end(cmd);
    }
}

std::vector<uint8_t> GpuSolver::download(const vk::Buffer& buffer) const
{
    // One host buffer, kept across readbacks (samples read up to 3 x 51 MB at 3.2 M vertices).
    if (readback_.size() < buffer.size())
        readback_ = ctx_.createBuffer(
            {.size = buffer.size(), .usage = vk::kTransferDst, .memory = vk::Memory::Readback, .name = "sim.readback"});
    const vk::Buffer& host = readback_;
    ctx_.submitAndWait([&](VkCommandBuffer cmd) {
        vk::memoryBarrier(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, VK_ACCESS_2_MEMORY_WRITE_BIT,
                          VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_READ_BIT);
        VkBufferCopy region{.size = buffer.size()};
        vkCmdCopyBuffer(cmd, buffer, host.get(), 1, &region);
        vk::transferToHostBarrier(cmd);
    });
    std::vector<uint8_t> bytes(size_t(buffer.size()));
    std::memcpy(bytes.data(), host.mapped(), bytes.size());
    return bytes;
}

SimState GpuSolver::readState() const
{
    SimState s;
    auto asVec4 = [](const std::vector<uint8_t>& bytes) {
        std::vector<glm::vec4> out(bytes.size() / sizeof(glm::vec4));
        std::memcpy(out.data(), bytes.data(), out.size() * sizeof(glm::vec4));
        return out;
    };
    uint32_t strands = setup_.params.strandCount, V = setup_.params.verticesPerStrand;
    s.positions = fromSlots(asVec4(download(positions_)), strands, V);
    s.velocities = fromSlots(asVec4(download(velocities_)), strands, V);
    s.tangents = fromSlots(asVec4(download(tangents_)), strands, V);
    std::vector<uint8_t> counters = download(counters_);
    gpu::SimCounters c{};
    std::memcpy(&c, counters.data(), sizeof(c));
    s.nonfiniteResets = c.nonfiniteResets;
    return s;
}

std::vector<gpu::GridNode> GpuSolver::readGrid() const
{
    std::vector<uint8_t> bytes = download(grids_[1 - turn_]); // the last recorded step's
    std::vector<gpu::GridNode> out(setup_.params.gridNodeCount);
    if (!fixedGrid_) {
        std::memcpy(out.data(), bytes.data(), out.size() * sizeof(gpu::GridNode));
        return out;
    }
    std::vector<int64_t> words(bytes.size() / sizeof(int64_t));
    std::memcpy(words.data(), bytes.data(), words.size() * sizeof(int64_t));
    double inv = 1.0 / double(setup_.params.gridFixedScale);
    uint32_t count = setup_.params.gridNodeCount;
    for (uint32_t n = 0; n < count; ++n) {
        auto word = [&](uint32_t w) { return double(words[gpu::gridFixedWord(n, w, count)]) * inv; };
        out[n].density = float(word(0));
        out[n].momentum = glm::vec3(float(word(1)), float(word(2)), float(word(3)));
    }
    return out;
}

} // namespace wisp
