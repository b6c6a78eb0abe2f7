// renderer/compute/strand_raster.cpp: the compute path's buffers, pipelines and passes (what each stage
// declares and records; the kernels are shaders/strands_*.comp).
#include "renderer/compute/strand_raster.h"

#include "gpu/check.h"
#include "gpu/context.h"
#include "gpu/frame.h"
#include "gpu/pipeline.h"
#include "physics/gpu_solver.h"
#include "renderer/frame_uniforms.h"
#include "renderer/light_maps.h"
#include "renderer/render_target.h"

#include <algorithm>
#include <cstring>

namespace wisp {

static_assert(sizeof(gpu::StrandRasterPush) == 80, "StrandRasterPush must fit the 128 bytes of push constants");
static_assert(sizeof(gpu::RasterCounters) == 32);
static_assert(sizeof(gpu::RasterPiece) == 48 && offsetof(gpu::RasterPiece, walkGroups) == 16 &&
                  offsetof(gpu::RasterPiece, resolveGroups) == 32,
              "RasterPiece must match its std430 layout (its dispatches are read at these offsets)");

namespace {

const char* stageName(StrandRaster::Stage stage)
{
    switch (stage) {
    case StrandRaster::Stage::Clear:
        return "strands.clear";
    case StrandRaster::Stage::Curves:
        return "strands.curves";
    case StrandRaster::Stage::LightGenerate:
        return "strands.light";
    case StrandRaster::Stage::LightDepth:
        return "light.depth";
    case StrandRaster::Stage::LightOpacity:
        return "light.opacity";
    case StrandRaster::Stage::LightResolve:
        return "light.resolve";
    case StrandRaster::Stage::LightCopy:
        return "light.copy";
    case StrandRaster::Stage::Generate:
        return "strands.generate";
    case StrandRaster::Stage::Depth:
        return "strands.depth";
    case StrandRaster::Stage::Count:
        return "strands.count";
    case StrandRaster::Stage::ScanBlocks:
        return "strands.scan.blocks";
    case StrandRaster::Stage::ScanTotals:
        return "strands.scan.totals";
    case StrandRaster::Stage::ScanOffsets:
        return "strands.scan.offsets";
    case StrandRaster::Stage::Pieces:
        return "strands.pieces";
    case StrandRaster::Stage::Write:
        return "strands.write";
    case StrandRaster::Stage::Resolve:
        return "strands.resolve";
    case StrandRaster::Stage::Stats:
        return "strands.stats";
    }
    return "strands";
}

constexpr uint32_t kScanBlockThreads = 256; // strands_scan.comp's blocks: 4 counts a thread
constexpr VkBufferUsageFlags kIndirect = VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT;

// strands.write or strands.resolve of one recorded piece.
class PiecePass : public Pass {
public:
    PiecePass(StrandRaster& owner, StrandRaster::Stage stage, uint32_t piece)
        : owner_(owner), stage_(stage), piece_(piece),
          name_(std::string(stageName(stage)) + (piece > 0 ? " " + std::to_string(piece) : ""))
    {
    }
    const char* name() const override { return name_.c_str(); }
    void declare(PassIo& io) override { owner_.declare(stage_, io); }
    void record(VkCommandBuffer cmd, FrameContext& frame) override { owner_.record(stage_, cmd, frame, piece_); }

private:
    StrandRaster& owner_;
    StrandRaster::Stage stage_;
    uint32_t piece_;
    std::string name_;
};

} // namespace

std::string describeRasterStats(const RasterStats& s)
{
    std::string text = "compute raster: " + std::to_string(s.segments) + " segments on screen (" +
                       std::to_string(s.hidden) + " behind the meshes), " + std::to_string(s.fragments) +
                       " hair fragments (at most " + std::to_string(s.maxPixel) + " in a pixel), buffer of " +
                       std::to_string(s.capacity);
    if (s.pieces > 1)
        text += ", drawn in " + std::to_string(s.pieces) + " pieces";
    if (s.overflow > 0)
        text += ", " + std::to_string(s.overflow) + " not drawn (more pieces are recorded for the next frame)";
    return text;
}

StrandRaster::StrandRaster(const vk::Context& ctx, RenderTarget& target, FrameUniforms& uniforms, LightMaps& maps,
                           GpuSolver& solver, const std::vector<glm::uvec4>& triangles, uint32_t framesInFlight)
    : ctx_(ctx), target_(target), uniforms_(uniforms), maps_(maps), solver_(solver)
{
    constexpr VkShaderStageFlags kCompute = VK_SHADER_STAGE_COMPUTE_BIT;
    constexpr VkDescriptorType kStorage = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    constexpr VkDescriptorType kSampler = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
    constexpr VkDescriptorType kImage = VK_DESCRIPTOR_TYPE_STORAGE_IMAGE;
    vk::PipelineLayoutBundle layout = vk::createPipelineLayout(
        ctx, {.bindings = {{gpu::kRasterBindingFrame, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, kCompute},
                           {gpu::kRasterBindingSim, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, kCompute},
                           {gpu::kRasterBindingPositions, kStorage, kCompute},
                           {gpu::kRasterBindingTriangles, kStorage, kCompute},
                           {gpu::kBindingShadowHead, kSampler, kCompute},
                           {gpu::kBindingShadowHair, kSampler, kCompute},
                           {gpu::kBindingHairDepth, kSampler, kCompute},
                           {gpu::kBindingOpacity, kSampler, kCompute},
                           {gpu::kRasterBindingLut, kSampler, kCompute},
                           {gpu::kRasterBindingVertices, kStorage, kCompute},
                           {gpu::kRasterBindingColors, kStorage, kCompute},
                           {gpu::kRasterBindingCounts, kStorage, kCompute},
                           {gpu::kRasterBindingOffsets, kStorage, kCompute},
                           {gpu::kRasterBindingFragments, kStorage, kCompute},
                           {gpu::kRasterBindingCounters, kStorage, kCompute},
                           {gpu::kRasterBindingMeshDepth, kSampler, kCompute},
                           {gpu::kRasterBindingHairColor, kImage, kCompute},
                           {gpu::kRasterBindingLightDepth, kStorage, kCompute},
                           {gpu::kRasterBindingLightOpacity, kStorage, kCompute},
                           {gpu::kRasterBindingOpacityImage, kImage, kCompute},
                           {gpu::kRasterBindingDepthRange, kStorage, kCompute},
                           {gpu::kRasterBindingBlockSums, kStorage, kCompute},
                           {gpu::kRasterBindingMeshSamples, kStorage, kCompute},
                           {gpu::kRasterBindingLightDepthImage, kImage, kCompute},
                           {gpu::kRasterBindingTileDepth, kStorage, kCompute},
                           {gpu::kRasterBindingCurves, kStorage, kCompute},
                           {gpu::kRasterBindingPieces, kStorage, kCompute}},
              .pushConstantBytes = sizeof(gpu::StrandRasterPush),
              .pushConstantStages = kCompute,
              .name = "strands.layout"});
    setLayout_ = std::move(layout.setLayout);
    layout_ = std::move(layout.layout);
    curvesPipeline_ = vk::createComputePipeline(ctx, layout_, "strands_curves.comp", "strands.curves.pipeline");
    generatePipeline_ = vk::createComputePipeline(ctx, layout_, "strands_generate.comp", "strands.generate.pipeline");
    generateLightPipeline_ =
        vk::createComputePipeline(ctx, layout_, "strands_generate_light.comp", "strands.light.pipeline");
    const char* single = target.multisampled() ? "" : "_single";
    depthPipeline_ = vk::createComputePipeline(ctx, layout_, std::string("strands_depth") + single + ".comp",
                                               "strands.depth.pipeline");
    depthBufferPipeline_ =
        vk::createComputePipeline(ctx, layout_, "strands_depth_buffer.comp", "strands.depth.pipeline");
    countPipeline_ = vk::createComputePipeline(ctx, layout_, "strands_fragments.comp", "strands.count.pipeline");
    writePipeline_ = vk::createComputePipeline(ctx, layout_, "strands_fragments_write.comp", "strands.write.pipeline");
    scanBlocksPipeline_ = vk::createComputePipeline(ctx, layout_, "strands_scan.comp", "strands.scan.blocks.pipeline",
                                                    {/*kPhase=*/0, kScanBlockThreads});
    scanTotalsPipeline_ = vk::createComputePipeline(ctx, layout_, "strands_scan.comp", "strands.scan.totals.pipeline",
                                                    {/*kPhase=*/1, gpu::kRasterScanGroupSize});
    scanOffsetsPipeline_ = vk::createComputePipeline(ctx, layout_, "strands_scan.comp", "strands.scan.offsets.pipeline",
                                                     {/*kPhase=*/2, kScanBlockThreads});
    piecesPipeline_ = vk::createComputePipeline(ctx, layout_, "strands_pieces.comp", "strands.pieces.pipeline");
    lightDepthPipeline_ =
        vk::createComputePipeline(ctx, layout_, "strands_light.comp", "light.depth.pipeline", {/*kOpacity=*/0});
    lightOpacityPipeline_ =
        vk::createComputePipeline(ctx, layout_, "strands_light.comp", "light.opacity.pipeline", {/*kOpacity=*/1});
    lightResolvePipeline_ =
        vk::createComputePipeline(ctx, layout_, "strands_light_resolve.comp", "light.resolve.pipeline");
    depthSampler_ = vk::createSampler(ctx, VK_FILTER_NEAREST, false, "strands.depth.sampler");

    triangles_ = ctx.createBufferWithData(
        {.size = triangles.size() * sizeof(glm::uvec4), .usage = vk::kStorage, .name = "strands.triangles"},
        triangles.data(), triangles.size() * sizeof(glm::uvec4));
    allocate(counters_, sizeof(gpu::RasterCounters), vk::kStorage | vk::kTransferDst | vk::kTransferSrc,
             "strands.counters", nullptr);
    allocate(pieces_, gpu::kRasterMaxPieces * kPieceBytes, vk::kStorage | kIndirect | vk::kTransferSrc,
             "strands.pieces", nullptr);
    for (uint32_t i = 0; i < framesInFlight; ++i) {
        readback_.push_back(ctx.createBuffer({.size = sizeof(gpu::RasterCounters),
                                              .usage = vk::kTransferDst,
                                              .memory = vk::Memory::Readback,
                                              .name = "strands.counters.readback"}));
        std::memset(readback_.back().mapped(), 0, sizeof(gpu::RasterCounters));
    }
    for (int s = 0; s <= int(Stage::Stats); ++s)
        passes_.push_back(std::make_unique<StagePass<StrandRaster, Stage>>(*this, Stage(s), stageName(Stage(s))));
    for (uint32_t piece = 0; piece < gpu::kRasterMaxPieces; ++piece) {
        piecePasses_.push_back(std::make_unique<PiecePass>(*this, Stage::Write, piece));
        piecePasses_.push_back(std::make_unique<PiecePass>(*this, Stage::Resolve, piece));
    }
    resize();
}

StrandRaster::~StrandRaster() = default;

void StrandRaster::allocate(Storage& storage, uint64_t bytes, VkBufferUsageFlags usage, const char* name,
                            FrameContext* frame)
{
    if (frame && storage.buffer)
        frame->retire(std::move(storage.buffer));
    storage.buffer = ctx_.createBuffer({.size = bufferBytes(bytes), .usage = usage, .name = name});
    storage.track = {.buffer = storage.buffer};
}

void StrandRaster::resize()
{
    VkExtent2D e = target_.extent();
    uint64_t pixels = uint64_t(e.width) * e.height;
    uint64_t blocks = (pixels + 1 + gpu::kRasterScanBlock - 1) / gpu::kRasterScanBlock;
    allocate(counts_, (pixels + 1) * sizeof(uint32_t), vk::kStorage | vk::kTransferDst, "strands.counts", nullptr);
    allocate(offsets_, (pixels + 1) * sizeof(uint32_t), vk::kStorage | vk::kTransferSrc, "strands.offsets", nullptr);
    allocate(depthRange_, pixels * 2 * sizeof(float), vk::kStorage, "strands.depth_range", nullptr);
    allocate(tileDepth_, depthTiles(e) * sizeof(float), vk::kStorage, "strands.tile_depth", nullptr);
    allocate(blockSums_, blocks * sizeof(uint32_t), vk::kStorage, "strands.block_sums", nullptr);
    allocate(meshSamples_, pixels * uint32_t(target_.samples()) * sizeof(uint32_t), vk::kStorage,
             "strands.mesh_samples", nullptr);
    // The count past the last pixel is always 0 (its offset is the total): zeroed once.
    ctx_.submitAndWait([&](VkCommandBuffer cmd) { vkCmdFillBuffer(cmd, counts_.buffer, 0, VK_WHOLE_SIZE, 0); });
    color_ = ctx_.createImage(
        {.format = kColorFormat,
         .extent = e,
         .usage = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT,
         .name = "strands.color"});
    colorTrack_ = {.image = color_.get()};
}

void StrandRaster::setFragmentCapacity(uint64_t fragments)
{
    forcedCapacity_ = fragments;
    fragmentCapacity_ = 0;
    fragments_.buffer.reset();
    for (vk::Buffer& b : readback_) // what earlier frames needed is forgotten
        std::memset(b.mapped(), 0, sizeof(gpu::RasterCounters));
}

StrandRaster::Storage& StrandRaster::storage(Buffer which)
{
    switch (which) {
    case Buffer::Curves:
        return curves_;
    case Buffer::Vertices:
        return vertices_;
    case Buffer::Colors:
        return colors_;
    case Buffer::LightVertices:
        return lightVertices_;
    case Buffer::LightColors:
        return lightColors_;
    case Buffer::Offsets:
        return offsets_;
    case Buffer::Fragments:
        return fragments_;
    case Buffer::Counters:
        return counters_;
    case Buffer::LightDepth:
        return lightDepth_;
    case Buffer::LightOpacity:
        return lightOpacity_;
    case Buffer::Pieces:
        return pieces_;
    }
    return counters_;
}

uint64_t StrandRaster::allocatedBytes() const
{
    uint64_t bytes =
        triangles_.size() + uint64_t(color_.extent().width) * color_.extent().height * vk::formatBytes(color_.format());
    for (const Storage* s :
         {&curves_, &vertices_, &colors_, &lightVertices_, &lightColors_, &counts_, &offsets_, &fragments_, &counters_,
          &depthRange_, &tileDepth_, &blockSums_, &lightDepth_, &lightOpacity_, &meshSamples_, &pieces_})
        bytes += s->buffer ? s->buffer.size() : 0;
    return bytes;
}

Pass* StrandRaster::pass(Stage stage)
{
    return passes_[size_t(stage)].get();
}

Pass* StrandRaster::piecePass(Stage stage, uint32_t piece)
{
    return piecePasses_.at(2 * size_t(piece) + (stage == Stage::Resolve ? 1 : 0)).get();
}

RasterStats StrandRaster::stats(uint32_t slot) const
{
    gpu::RasterCounters c{};
    std::memcpy(&c, readback_.at(slot).mapped(), sizeof(c));
    return {.segments = c.segments,
            .hidden = c.hidden,
            .fragments = c.fragments,
            .capacity = c.capacity,
            .overflow = c.overflow,
            .maxPixel = c.maxPixel,
            .pieces = std::max(c.pieces, 1u)};
}

void StrandRaster::prepare(FrameContext& frame, const StrandDraw& cameraDraw, const StrandDraw& lightDraw,
                           const FrameOptions& options)
{
    lut_ = options.lut;
    auto push = [&](const StrandDraw& d) {
        gpu::StrandRasterPush r{};
        r.guideCount = d.guides;
        r.verticesPerStrand = d.verticesPerStrand;
        r.strandsPerGuide = d.strandsPerGuide;
        r.drawnPerGuide = drawnStrandsPerGuide(d.strandsPerGuide, d.lodStrands);
        r.divisions = d.divisions;
        r.interpolation = d.interpolation;
        r.clumpRadius = d.clumpRadius;
        r.deviation = d.deviation;
        r.width = d.width * d.lodWidthScale;
        r.lodStrands = d.lodStrands;
        r.oitK = options.oitK;
        r.domLayers = options.domLayers;
        return r;
    };
    gpu::StrandRasterPush camera = push(cameraDraw);
    gpu::StrandRasterPush light = push(lightDraw);
    if (!options.shadows)
        light.drawnPerGuide = 0; // the maps are only cleared
    VkExtent2D e = target_.extent();
    uint64_t cameraVertices = uint64_t(camera.guideCount) * camera.drawnPerGuide * (camera.divisions + 1);
    uint64_t lightVertices = uint64_t(light.guideCount) * light.drawnPerGuide * (light.divisions + 1);
    uint64_t curvePoints = uint64_t(camera.guideCount) * (camera.divisions + 1); // (the light's D is the same)
    if (!curves_.buffer || curves_.buffer.size() < curvePoints * kCurvePointBytes)
        allocate(curves_, curvePoints * kCurvePointBytes, vk::kStorage | vk::kTransferSrc, "strands.curves", &frame);
    if (!vertices_.buffer || vertices_.buffer.size() < cameraVertices * kVertexBytes) {
        allocate(vertices_, cameraVertices * kVertexBytes, vk::kStorage | vk::kTransferSrc, "strands.vertices", &frame);
        allocate(colors_, cameraVertices * kColorBytes, vk::kStorage | vk::kTransferSrc, "strands.colors", &frame);
    }
    if (!lightVertices_.buffer || lightVertices_.buffer.size() < lightVertices * kVertexBytes) {
        allocate(lightVertices_, lightVertices * kVertexBytes, vk::kStorage | vk::kTransferSrc,
                 "strands.light_vertices", &frame);
        allocate(lightColors_, lightVertices * kColorBytes, vk::kStorage | vk::kTransferSrc, "strands.light_colors",
                 &frame);
    }
    if (lightSize_ != maps_.size()) {
        lightSize_ = maps_.size();
        uint64_t texels = uint64_t(lightSize_) * lightSize_;
        allocate(lightDepth_, texels * kLightDepthBytes, vk::kStorage | vk::kTransferDst | vk::kTransferSrc,
                 "strands.light_depth", &frame);
        allocate(lightOpacity_, texels * kLightOpacityBytes, vk::kStorage | vk::kTransferDst | vk::kTransferSrc,
                 "strands.light_opacity", &frame);
    }
    // The fragments: room for what this slot's last frame needed (it has completed), with some to
    // spare, up to the budget; at first a few per segment. Past the budget, pieces: as many as the
    // last frame took, and a quarter more (at least one) to spare.
    uint64_t segments = uint64_t(camera.guideCount) * camera.drawnPerGuide * camera.divisions;
    const vk::DeviceReport& device = ctx_.report();
    budget_ = forcedCapacity_ > 0
                  ? forcedCapacity_
                  : fragmentBudget(options.fragmentBudgetBytes, device.deviceLocalBytes, device.maxStorageBufferRange);
    uint64_t wanted = forcedCapacity_ > 0 ? forcedCapacity_ : initialFragments(segments, budget_);
    RasterStats last = stats(frame.slot);
    if (last.fragments > fragmentCapacity_)
        wanted = std::max(wanted, last.fragments + last.fragments / 4);
    wanted = std::min(wanted, budget_);
    if (wanted > fragmentCapacity_ || fragmentCapacity_ > budget_ || !fragments_.buffer) {
        fragmentCapacity_ = fragmentCapacity_ > budget_ ? wanted : std::max(wanted, fragmentCapacity_);
        allocate(fragments_, fragmentCapacity_ * kFragmentBytes, vk::kStorage | vk::kTransferSrc, "strands.fragments",
                 &frame);
    }
    uint64_t neededPieces = last.fragments > fragmentCapacity_ ? std::max<uint64_t>(last.pieces, 2) : 1;
    recordedPieces_ =
        uint32_t(std::min<uint64_t>(neededPieces + std::max<uint64_t>(1, neededPieces / 4), gpu::kRasterMaxPieces));
    // oit_k is the resolve's specialization constant.
    uint32_t k = std::clamp(camera.oitK, 1u, gpu::kMaxOitK);
    if (k != pipelineK_) {
        if (resolvePipeline_)
            frame.retire(std::move(resolvePipeline_));
        resolvePipeline_ =
            vk::createComputePipeline(ctx_, layout_, "strands_resolve.comp", "strands.resolve.pipeline", {k});
        pipelineK_ = k;
    }

    uint64_t pixels = uint64_t(e.width) * e.height;
    camera.fromLight = 0;
    camera.segmentCount = uint32_t(segments);
    camera.targetWidth = e.width;
    camera.targetHeight = e.height;
    camera.samples = uint32_t(target_.samples());
    camera.fragmentCapacity = uint32_t(fragmentCapacity_);
    camera.scanBlocks = uint32_t((pixels + 1 + gpu::kRasterScanBlock - 1) / gpu::kRasterScanBlock);
    camera.oitK = k;
    light.fromLight = 1;
    light.segmentCount = uint32_t(uint64_t(light.guideCount) * light.drawnPerGuide * light.divisions);
    light.targetWidth = lightSize_;
    light.targetHeight = lightSize_;
    camera_ = camera;
    light_ = light;
}

void StrandRaster::declare(Stage stage, PassIo& io)
{
    switch (stage) {
    case Stage::Clear:
        io.use(lightDepth_.track, Access::TransferDst);
        io.use(lightOpacity_.track, Access::TransferDst);
        io.use(counters_.track, Access::TransferDst);
        break;
    case Stage::Curves:
        io.use(solver_.positionsTrack(), Access::ComputeRead);
        io.use(curves_.track, Access::ComputeWrite);
        break;
    case Stage::LightGenerate:
        io.use(curves_.track, Access::ComputeRead);
        io.use(lightVertices_.track, Access::ComputeWrite);
        io.use(lightColors_.track, Access::ComputeWrite);
        break;
    case Stage::LightDepth: // (one shader with light.opacity: it binds, never touches, the opacity)
        io.use(lightVertices_.track, Access::ComputeRead);
        io.use(lightColors_.track, Access::ComputeRead);
        io.use(lightDepth_.track, Access::ComputeWrite);
        io.use(lightOpacity_.track, Access::ComputeRead);
        break;
    case Stage::LightOpacity:
        io.use(lightVertices_.track, Access::ComputeRead);
        io.use(lightColors_.track, Access::ComputeRead);
        io.use(lightDepth_.track, Access::ComputeRead);
        io.use(lightOpacity_.track, Access::ComputeWrite);
        break;
    case Stage::LightResolve:
        io.use(lightOpacity_.track, Access::ComputeRead);
        io.use(lightDepth_.track, Access::ComputeRead);
        io.use(maps_.opacity(), Access::ComputeWrite);
        io.use(maps_.hairDepthValues(), Access::ComputeWrite);
        break;
    case Stage::LightCopy:
        io.use(lightDepth_.track, Access::TransferSrc);
        io.use(maps_.hairDepth(), Access::TransferDst);
        break;
    case Stage::Generate:
        io.use(curves_.track, Access::ComputeRead);
        maps_.declareRead(io, Access::ComputeSampled);
        io.use(vertices_.track, Access::ComputeWrite);
        io.use(colors_.track, Access::ComputeWrite);
        break;
    case Stage::Depth:
        if (externalSamples_) {
            io.use(*externalSamples_, Access::ComputeRead);
        } else {
            io.use(target_.depth(), Access::DepthSampled);
            io.use(meshSamples_.track, Access::ComputeWrite);
        }
        io.use(depthRange_.track, Access::ComputeWrite);
        io.use(tileDepth_.track, Access::ComputeWrite);
        io.use(counts_.track, Access::ComputeWrite);
        break;
    case Stage::Count: // (the walk of strands.write: it binds, never touches, the fragments)
    case Stage::Write:
        io.use(vertices_.track, Access::ComputeRead);
        io.use(colors_.track, Access::ComputeRead);
        io.use(depthRange_.track, Access::ComputeRead);
        io.use(tileDepth_.track, Access::ComputeRead);
        io.use(externalSamples_ ? *externalSamples_ : meshSamples_.track, Access::ComputeRead);
        io.use(counts_.track, Access::ComputeWrite); // counts, then (strands.write) cursors
        io.use(fragments_.track, Access::ComputeWrite);
        io.use(counters_.track, Access::ComputeWrite);
        if (stage == Stage::Write) {
            io.use(offsets_.track, Access::ComputeRead);
            io.use(pieces_.track, Access::ComputeRead);
            io.use(pieces_.track, Access::IndirectRead);
        }
        break;
    case Stage::Pieces:
        io.use(offsets_.track, Access::ComputeRead);
        io.use(counters_.track, Access::ComputeWrite);
        io.use(pieces_.track, Access::ComputeWrite);
        break;
    case Stage::ScanBlocks:
    case Stage::ScanTotals:
    case Stage::ScanOffsets:
        io.use(counts_.track, Access::ComputeWrite);
        io.use(offsets_.track, Access::ComputeWrite);
        io.use(blockSums_.track, Access::ComputeWrite);
        io.use(counters_.track, Access::ComputeWrite);
        break;
    case Stage::Resolve:
        io.use(offsets_.track, Access::ComputeRead);
        io.use(fragments_.track, Access::ComputeRead);
        io.use(counters_.track, Access::ComputeRead);
        io.use(pieces_.track, Access::ComputeRead);
        io.use(pieces_.track, Access::IndirectRead);
        io.use(colorTrack_, Access::ComputeWrite);
        break;
    case Stage::Stats:
        io.use(counters_.track, Access::TransferSrc);
        break;
    }
}

void StrandRaster::dispatch(VkCommandBuffer cmd, VkPipeline pipeline, const gpu::StrandRasterPush& push,
                            const std::vector<VkWriteDescriptorSet>& writes, uint32_t x, uint32_t y)
{
    if (x == 0 || y == 0)
        return;
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline);
    ctx_.pushDescriptorSet(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, layout_, 0, uint32_t(writes.size()), writes.data());
    vkCmdPushConstants(cmd, layout_, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(push), &push);
    vkCmdDispatch(cmd, x, y, 1);
}

void StrandRaster::dispatchIndirect(VkCommandBuffer cmd, VkPipeline pipeline, const gpu::StrandRasterPush& push,
                                    const std::vector<VkWriteDescriptorSet>& writes, VkDeviceSize offset)
{
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline);
    ctx_.pushDescriptorSet(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, layout_, 0, uint32_t(writes.size()), writes.data());
    vkCmdPushConstants(cmd, layout_, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(push), &push);
    vkCmdDispatchIndirect(cmd, pieces_.buffer, offset);
}

void StrandRaster::dispatchLinear(VkCommandBuffer cmd, VkPipeline pipeline, const gpu::StrandRasterPush& push,
                                  const std::vector<VkWriteDescriptorSet>& writes, uint64_t items, uint32_t groupSize)
{
    // Rows of at most 65535 groups; the kernels number their items x + y * (groups per row *
    // group size) and skip those past the end (the same rows strands.pieces dispatches the walk in).
    glm::uvec2 groups = gpu::rasterLinearGroups(uint32_t(items), groupSize);
    dispatch(cmd, pipeline, push, writes, groups.x, groups.y);
}

void StrandRaster::record(Stage stage, VkCommandBuffer cmd, FrameContext& frame, uint32_t piece)
{
    constexpr VkDescriptorType kStorage = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    auto whole = [](const Storage& s) { return VkDescriptorBufferInfo{s.buffer, 0, VK_WHOLE_SIZE}; };
    VkDescriptorBufferInfo frameInfo = uniforms_.descriptor(frame.slot);
    VkDescriptorBufferInfo simInfo{solver_.params(), 0, VK_WHOLE_SIZE};
    VkDescriptorBufferInfo positions{solver_.positions(), 0, VK_WHOLE_SIZE};
    VkDescriptorBufferInfo triangles{triangles_, 0, VK_WHOLE_SIZE};
    VkDescriptorBufferInfo curves = whole(curves_), vertices = whole(vertices_), colors = whole(colors_);
    VkDescriptorBufferInfo lightVertices = whole(lightVertices_), lightColors = whole(lightColors_);
    VkDescriptorBufferInfo counts = whole(counts_), offsets = whole(offsets_), fragments = whole(fragments_);
    VkDescriptorBufferInfo counters = whole(counters_), depthRange = whole(depthRange_), blockSums = whole(blockSums_);
    VkDescriptorBufferInfo tileDepth = whole(tileDepth_), pieces = whole(pieces_);
    VkDescriptorBufferInfo lightDepth = whole(lightDepth_), lightOpacity = whole(lightOpacity_);
    VkDescriptorImageInfo meshDepth{depthSampler_, target_.depthImage().view(),
                                    VK_IMAGE_LAYOUT_DEPTH_READ_ONLY_OPTIMAL};
    VkDescriptorBufferInfo meshSamples{externalSamples_ ? externalSamplesBuffer_ : meshSamples_.buffer.get(), 0,
                                       VK_WHOLE_SIZE};
    auto frameWrite = vk::bufferWrite(gpu::kRasterBindingFrame, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, &frameInfo);
    uint64_t cameraVertices = uint64_t(camera_.guideCount) * camera_.drawnPerGuide * (camera_.divisions + 1);
    uint64_t lightVertexCount = uint64_t(light_.guideCount) * light_.drawnPerGuide * (light_.divisions + 1);

    switch (stage) {
    case Stage::Clear: {
        vkCmdFillBuffer(cmd, lightDepth_.buffer, 0, VK_WHOLE_SIZE, 0x3f800000u); // 1.0f: nothing in front
        vkCmdFillBuffer(cmd, lightOpacity_.buffer, 0, VK_WHOLE_SIZE, 0);
        vkCmdFillBuffer(cmd, counters_.buffer, 0, VK_WHOLE_SIZE, 0);
        break;
    }
    case Stage::Curves: {
        std::vector<VkWriteDescriptorSet> writes = {vk::bufferWrite(gpu::kRasterBindingPositions, kStorage, &positions),
                                                    vk::bufferWrite(gpu::kRasterBindingCurves, kStorage, &curves)};
        dispatchLinear(cmd, curvesPipeline_, camera_, writes, uint64_t(camera_.guideCount) * (camera_.divisions + 1),
                       gpu::kRasterGroupSize);
        break;
    }
    case Stage::LightGenerate:
    case Stage::Generate: {
        bool fromLight = stage == Stage::LightGenerate;
        std::vector<VkWriteDescriptorSet> writes = {
            frameWrite,
            vk::bufferWrite(gpu::kRasterBindingSim, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, &simInfo),
            vk::bufferWrite(gpu::kRasterBindingCurves, kStorage, &curves),
            vk::bufferWrite(gpu::kRasterBindingTriangles, kStorage, &triangles),
            vk::bufferWrite(gpu::kRasterBindingVertices, kStorage, fromLight ? &lightVertices : &vertices),
            vk::bufferWrite(gpu::kRasterBindingColors, kStorage, fromLight ? &lightColors : &colors)};
        if (!fromLight) {
            for (const VkWriteDescriptorSet& w : maps_.descriptorWrites())
                writes.push_back(w);
            writes.push_back(vk::imageWrite(gpu::kRasterBindingLut, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, lut_));
        }
        dispatchLinear(cmd, fromLight ? generateLightPipeline_.get() : generatePipeline_.get(),
                       fromLight ? light_ : camera_, writes, fromLight ? lightVertexCount : cameraVertices,
                       gpu::kRasterGroupSize);
        break;
    }
    case Stage::LightDepth:
    case Stage::LightOpacity: {
        std::vector<VkWriteDescriptorSet> writes = {
            frameWrite, vk::bufferWrite(gpu::kRasterBindingVertices, kStorage, &lightVertices),
            vk::bufferWrite(gpu::kRasterBindingColors, kStorage, &lightColors),
            vk::bufferWrite(gpu::kRasterBindingLightDepth, kStorage, &lightDepth),
            vk::bufferWrite(gpu::kRasterBindingLightOpacity, kStorage, &lightOpacity)};
        dispatchLinear(cmd, stage == Stage::LightDepth ? lightDepthPipeline_.get() : lightOpacityPipeline_.get(),
                       light_, writes, light_.segmentCount, gpu::kRasterGroupSize);
        break;
    }
    case Stage::LightResolve: {
        VkDescriptorImageInfo opacityImage{VK_NULL_HANDLE, maps_.opacityImage().view(), VK_IMAGE_LAYOUT_GENERAL};
        VkDescriptorImageInfo depthImage{VK_NULL_HANDLE, maps_.hairDepthValuesImage().view(), VK_IMAGE_LAYOUT_GENERAL};
        std::vector<VkWriteDescriptorSet> writes = {
            vk::bufferWrite(gpu::kRasterBindingLightOpacity, kStorage, &lightOpacity),
            vk::bufferWrite(gpu::kRasterBindingLightDepth, kStorage, &lightDepth),
            vk::imageWrite(gpu::kRasterBindingOpacityImage, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, &opacityImage),
            vk::imageWrite(gpu::kRasterBindingLightDepthImage, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, &depthImage)};
        dispatch(cmd, lightResolvePipeline_, light_, writes, vk::groupCount(lightSize_, 8),
                 vk::groupCount(lightSize_, 8));
        break;
    }
    case Stage::LightCopy: {
        VkBufferImageCopy region{.imageSubresource = {VK_IMAGE_ASPECT_DEPTH_BIT, 0, 0, 1},
                                 .imageExtent = {lightSize_, lightSize_, 1}};
        vkCmdCopyBufferToImage(cmd, lightDepth_.buffer, maps_.hairDepthImage().get(),
                               VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &region);
        break;
    }
    case Stage::Depth: {
        std::vector<VkWriteDescriptorSet> writes = {
            vk::bufferWrite(gpu::kRasterBindingMeshSamples, kStorage, &meshSamples),
            vk::bufferWrite(gpu::kRasterBindingDepthRange, kStorage, &depthRange),
            vk::bufferWrite(gpu::kRasterBindingTileDepth, kStorage, &tileDepth),
            vk::bufferWrite(gpu::kRasterBindingCounts, kStorage, &counts)};
        if (!externalSamples_)
            writes.push_back(
                vk::imageWrite(gpu::kRasterBindingMeshDepth, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, &meshDepth));
        dispatch(cmd, externalSamples_ ? depthBufferPipeline_.get() : depthPipeline_.get(), camera_, writes,
                 vk::groupCount(camera_.targetWidth, 8), vk::groupCount(camera_.targetHeight, 8));
        break;
    }
    case Stage::Count:
    case Stage::Write: {
        std::vector<VkWriteDescriptorSet> writes = {
            vk::bufferWrite(gpu::kRasterBindingVertices, kStorage, &vertices),
            vk::bufferWrite(gpu::kRasterBindingColors, kStorage, &colors),
            vk::bufferWrite(gpu::kRasterBindingCounts, kStorage, &counts),
            vk::bufferWrite(gpu::kRasterBindingFragments, kStorage, &fragments),
            vk::bufferWrite(gpu::kRasterBindingCounters, kStorage, &counters),
            vk::bufferWrite(gpu::kRasterBindingDepthRange, kStorage, &depthRange),
            vk::bufferWrite(gpu::kRasterBindingTileDepth, kStorage, &tileDepth),
            vk::bufferWrite(gpu::kRasterBindingMeshSamples, kStorage, &meshSamples)};
        if (stage == Stage::Count) {
            dispatchLinear(cmd, countPipeline_, camera_, writes, camera_.segmentCount, gpu::kRasterGroupSize);
        } else {
            writes.push_back(vk::bufferWrite(gpu::kRasterBindingOffsets, kStorage, &offsets));
            writes.push_back(vk::bufferWrite(gpu::kRasterBindingPieces, kStorage, &pieces));
            gpu::StrandRasterPush push = camera_;
            push.piece = piece;
            dispatchIndirect(cmd, writePipeline_, push, writes,
                             piece * kPieceBytes + offsetof(gpu::RasterPiece, walkGroups));
        }
        break;
    }
    case Stage::Pieces: {
        std::vector<VkWriteDescriptorSet> writes = {vk::bufferWrite(gpu::kRasterBindingOffsets, kStorage, &offsets),
                                                    vk::bufferWrite(gpu::kRasterBindingCounters, kStorage, &counters),
                                                    vk::bufferWrite(gpu::kRasterBindingPieces, kStorage, &pieces)};
        gpu::StrandRasterPush push = camera_;
        push.piece = recordedPieces_;
        dispatch(cmd, piecesPipeline_, push, writes, 1);
        break;
    }
    case Stage::ScanBlocks:
    case Stage::ScanTotals:
    case Stage::ScanOffsets: {
        std::vector<VkWriteDescriptorSet> writes = {vk::bufferWrite(gpu::kRasterBindingCounts, kStorage, &counts),
                                                    vk::bufferWrite(gpu::kRasterBindingOffsets, kStorage, &offsets),
                                                    vk::bufferWrite(gpu::kRasterBindingBlockSums, kStorage, &blockSums),
                                                    vk::bufferWrite(gpu::kRasterBindingCounters, kStorage, &counters)};
        if (stage == Stage::ScanTotals)
            dispatch(cmd, scanTotalsPipeline_, camera_, writes, 1);
        else
            dispatchLinear(cmd, stage == Stage::ScanBlocks ? scanBlocksPipeline_.get() : scanOffsetsPipeline_.get(),
                           camera_, writes, camera_.scanBlocks, 1);
        break;
    }
    case Stage::Resolve: {
        VkDescriptorImageInfo color{VK_NULL_HANDLE, color_.view(), VK_IMAGE_LAYOUT_GENERAL};
        std::vector<VkWriteDescriptorSet> writes = {
            vk::bufferWrite(gpu::kRasterBindingOffsets, kStorage, &offsets),
            vk::bufferWrite(gpu::kRasterBindingFragments, kStorage, &fragments),
            vk::bufferWrite(gpu::kRasterBindingCounters, kStorage, &counters),
            vk::bufferWrite(gpu::kRasterBindingPieces, kStorage, &pieces),
            vk::imageWrite(gpu::kRasterBindingHairColor, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, &color)};
        gpu::StrandRasterPush push = camera_;
        push.piece = piece;
        dispatchIndirect(cmd, resolvePipeline_, push, writes,
                         piece * kPieceBytes + offsetof(gpu::RasterPiece, resolveGroups));
        break;
    }
    case Stage::Stats: {
        VkBufferCopy region{0, 0, sizeof(gpu::RasterCounters)};
        vkCmdCopyBuffer(cmd, counters_.buffer, readback_.at(frame.slot), 1, &region);
        vk::transferToHostBarrier(cmd);
        break;
    }
    }
}

} // namespace wisp
