// renderer/compute/strand_raster.cpp: the compute path's buffers, pipelines and stages (StrandRaster::stage:
// each stage one list of what it touches, and its commands; the kernels are shaders/strands_*.comp).
#include "renderer/compute/strand_raster.h"

#include "gpu/check.h"
#include "gpu/compute_stage.h"
#include "gpu/context.h"
#include "gpu/frame.h"
#include "gpu/pipeline.h"
#include "physics/gpu_solver.h"
#include "renderer/frame_uniforms.h"
#include "renderer/light_maps.h"
#include "renderer/render_target.h"

#include <algorithm>
#include <cstring>
#include <stdexcept>

namespace wisp {

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
    case StrandRaster::Stage::CountFragments:
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
    case StrandRaster::Stage::Reserve:
        return "strands.reserve";
    case StrandRaster::Stage::Stats:
        return "strands.stats";
    }
    return "strands";
}

constexpr uint32_t kScanBlockThreads = 256; // strands_scan.comp's blocks: 4 counts a thread
constexpr VkBufferUsageFlags kIndirect = VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT;

} // namespace

std::string describeRasterStats(const RasterStats& s)
{
    std::string text = "compute raster: " + std::to_string(s.segments) + " segments on screen (" +
                       std::to_string(s.hidden) + " skipped whole: behind the meshes in every " +
                       std::to_string(gpu::kRasterDepthTile) + " x " + std::to_string(gpu::kRasterDepthTile) +
                       " tile they cross), " + std::to_string(s.fragments) + " hair fragments (at most " +
                       std::to_string(s.maxPixel) + " in a pixel), buffer of " + std::to_string(s.capacity);
    if (s.pieces > 1)
        text += ", drawn in " + std::to_string(s.pieces) + " pieces";
    if (s.oneWalk())
        text += ", one walk";
    else if (s.reserved)
        text += ", " + std::to_string(s.spilled) + " spilled from their reserved room";
    if (s.overflow > 0)
        text += ", " + std::to_string(s.overflow) + " not drawn (more pieces are recorded for the next frame)";
    return text;
}

StrandRaster::StrandRaster(const vk::Context& ctx, RenderTarget& target, FrameUniforms& uniforms, LightMaps& maps,
                           GpuSolver& solver, const std::vector<glm::uvec4>& triangles, uint32_t framesInFlight)
    : ctx_(ctx), target_(target), uniforms_(uniforms), maps_(maps), solver_(solver)
{
    // The layout holds every binding any stage lists (the lists only name the resources here).
    std::vector<ComputeStage> stages;
    for (int s = 0; s <= int(Stage::Stats); ++s)
        stages.push_back(stage(Stage(s)));
    layout_ = StageLayout(ctx, stages, sizeof(gpu::StrandRasterPush), "strands.layout");
    VkPipelineLayout layout = layout_.layout();
    curvesKernel_ = vk::createComputeKernel(ctx, layout, "strands_curves.comp", "strands.curves.pipeline");
    generateKernel_ = vk::createComputeKernel(ctx, layout, "strands_generate.comp", "strands.generate.pipeline");
    generateLightKernel_ =
        vk::createComputeKernel(ctx, layout, "strands_generate_light.comp", "strands.light.pipeline");
    const char* single = target.multisampled() ? "" : "_single";
    depthKernel_ =
        vk::createComputeKernel(ctx, layout, std::string("strands_depth") + single + ".comp", "strands.depth.pipeline");
    depthBufferKernel_ = vk::createComputeKernel(ctx, layout, "strands_depth_buffer.comp", "strands.depth.pipeline");
    countKernel_ = vk::createComputeKernel(ctx, layout, "strands_fragments.comp", "strands.count.pipeline");
    writeKernel_ = vk::createComputeKernel(ctx, layout, "strands_fragments_write.comp", "strands.write.pipeline");
    scanBlocksKernel_ = vk::createComputeKernel(ctx, layout, "strands_scan.comp", "strands.scan.blocks.pipeline",
                                                {/*kPhase=*/0, kScanBlockThreads});
    scanTotalsKernel_ = vk::createComputeKernel(ctx, layout, "strands_scan.comp", "strands.scan.totals.pipeline",
                                                {/*kPhase=*/1, gpu::kRasterScanGroupSize});
    scanOffsetsKernel_ = vk::createComputeKernel(ctx, layout, "strands_scan.comp", "strands.scan.offsets.pipeline",
                                                 {/*kPhase=*/2, kScanBlockThreads});
    piecesKernel_ = vk::createComputeKernel(ctx, layout, "strands_pieces.comp", "strands.pieces.pipeline");
    reserveKernel_ = vk::createComputeKernel(ctx, layout, "strands_reserve.comp", "strands.reserve.pipeline");
    lightDepthKernel_ =
        vk::createComputeKernel(ctx, layout, "strands_light.comp", "light.depth.pipeline", {/*kOpacity=*/0});
    lightOpacityKernel_ =
        vk::createComputeKernel(ctx, layout, "strands_light.comp", "light.opacity.pipeline", {/*kOpacity=*/1});
    lightResolveKernel_ = vk::createComputeKernel(ctx, layout, "strands_light_resolve.comp", "light.resolve.pipeline");
    depthSampler_ = vk::createSampler(ctx, VK_FILTER_NEAREST, false, "strands.depth.sampler");

    triangles_ = ctx.createBufferWithData(
        {.size = triangles.size() * sizeof(glm::uvec4), .usage = vk::kStorage, .name = "strands.triangles"},
        triangles.data(), triangles.size() * sizeof(glm::uvec4));
    allocate(counters_, sizeof(gpu::RasterCounters), vk::kStorage | vk::kTransferDst | vk::kTransferSrc,
             "strands.counters", nullptr);
    allocate(pieces_, gpu::kRasterMaxPieces * kPieceBytes, vk::kStorage | kIndirect | vk::kTransferSrc,
             "strands.pieces", nullptr);
    allocate(spillList_, gpu::kRasterSpillList * sizeof(glm::uvec4), vk::kStorage, "strands.spill_list", nullptr);
    for (uint32_t i = 0; i < framesInFlight; ++i) {
        readback_.push_back(ctx.createBuffer({.size = sizeof(gpu::RasterCounters),
                                              .usage = vk::kTransferDst,
                                              .memory = vk::Memory::Readback,
                                              .name = "strands.counters.readback"}));
        std::memset(readback_.back().mapped(), 0, sizeof(gpu::RasterCounters));
    }
    for (int s = 0; s <= int(Stage::Stats); ++s)
        passes_.push_back(
            std::make_unique<ComputeStagePass>(stageName(Stage(s)), layout_, [this, s] { return stage(Stage(s)); }));
    for (uint32_t piece = 0; piece < gpu::kRasterMaxPieces; ++piece) // strands.write N, strands.resolve N
        for (Stage s : {Stage::Write, Stage::Resolve})
            piecePasses_.push_back(std::make_unique<ComputeStagePass>(
                std::string(stageName(s)) + (piece > 0 ? " " + std::to_string(piece) : ""), layout_,
                [this, s, piece] { return stage(s, piece); }));
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
    allocate(reserved_, (pixels + 1) * sizeof(uint32_t), vk::kStorage | vk::kTransferDst | vk::kTransferSrc,
             "strands.reserved", nullptr);
    allocate(depthRange_, pixels * 2 * sizeof(float), vk::kStorage, "strands.depth_range", nullptr);
    allocate(tileDepth_, depthTiles(e) * sizeof(float), vk::kStorage, "strands.tile_depth", nullptr);
    allocate(blockSums_, blocks * sizeof(uint32_t), vk::kStorage, "strands.block_sums", nullptr);
    allocate(meshSamples_, pixels * uint32_t(target_.samples()) * sizeof(uint32_t), vk::kStorage,
             "strands.mesh_samples", nullptr);
    // The count past the last pixel is always 0 (its offset is the total): zeroed once. No pixel has
    // reserved room before a frame has laid it out.
    ctx_.submitAndWait([&](VkCommandBuffer cmd) {
        vkCmdFillBuffer(cmd, counts_.buffer, 0, VK_WHOLE_SIZE, 0);
        vkCmdFillBuffer(cmd, reserved_.buffer, 0, VK_WHOLE_SIZE, 0);
    });
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
    case Buffer::Reserved:
        return reserved_;
    }
    return counters_;
}

uint64_t StrandRaster::allocatedBytes() const
{
    uint64_t bytes =
        triangles_.size() + uint64_t(color_.extent().width) * color_.extent().height * vk::formatBytes(color_.format());
    for (const Storage* s : {&curves_, &vertices_, &colors_, &lightVertices_, &lightColors_, &counts_, &offsets_,
                             &fragments_, &counters_, &depthRange_, &tileDepth_, &blockSums_, &lightDepth_,
                             &lightOpacity_, &meshSamples_, &pieces_, &reserved_, &spillList_})
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
            .pieces = std::max(c.pieces, 1u),
            .reserved = c.reservedEnd != gpu::kRasterNotReserved,
            .spilled = c.spilled};
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
        r.coilRadius = d.coilRadius;
        r.coilFrequency = d.coilFrequency;
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
    // Room for the reserved layout (an eighth more than the last frame's fragments, and
    // kRasterReservedPerPixel a pixel) and the exact one after it, a sixteenth to spare, where the
    // budget allows: the frame is then written in one walk (shaders/shared/strand_raster.h "One walk").
    uint64_t reservedLayout = last.fragments * 35 / 16 + gpu::kRasterReservedPerPixel * (uint64_t(e.width) * e.height);
    if (last.fragments > 0 && reservedLayout <= budget_)
        wanted = std::max(wanted, reservedLayout);
    wanted = std::min(wanted, budget_);
    if (wanted > fragmentCapacity_ || fragmentCapacity_ > budget_ || !fragments_.buffer) {
        fragmentCapacity_ = fragmentCapacity_ > budget_ ? wanted : std::max(wanted, fragmentCapacity_);
        allocate(fragments_, fragmentCapacity_ * kFragmentBytes, vk::kStorage | vk::kTransferSrc, "strands.fragments",
                 &frame);
    }
    // strands.count writes into the reserved layout only where the buffer holds it (else its stores
    // would go to waste: the scan would lay the frame out exactly).
    bool reserving = last.fragments > 0 && fragmentCapacity_ >= reservedLayout;
    uint64_t neededPieces = last.fragments > fragmentCapacity_ ? std::max<uint64_t>(last.pieces, 2) : 1;
    recordedPieces_ =
        uint32_t(std::min<uint64_t>(neededPieces + std::max<uint64_t>(1, neededPieces / 4), gpu::kRasterMaxPieces));
    // oit_k is the resolve's specialization constant.
    uint32_t k = std::clamp(camera.oitK, 1u, gpu::kMaxOitK);
    if (k != pipelineK_) {
        if (resolveKernel_)
            frame.retire(std::move(resolveKernel_.pipeline));
        resolveKernel_ =
            vk::createComputeKernel(ctx_, layout_.layout(), "strands_resolve.comp", "strands.resolve.pipeline", {k});
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
    camera.reserving = reserving ? 1u : 0u;
    camera.spillCapacity = spillCapacity_;
    light.fromLight = 1;
    light.segmentCount = uint32_t(uint64_t(light.guideCount) * light.drawnPerGuide * light.divisions);
    light.targetWidth = lightSize_;
    light.targetHeight = lightSize_;
    camera_ = camera;
    light_ = light;
}

namespace {

// Groups of `groupSize` for `items` items, in rows of at most 65535 workgroups; the kernels number
// their items x + y * (groups per row * group size) and skip those past the end (the same rows
// strands.pieces dispatches the walk in).
void dispatchLinear(StageCommands& c, const vk::ComputeKernel& kernel, const gpu::StrandRasterPush& push,
                    uint64_t items, uint32_t groupSize)
{
    glm::uvec2 groups = gpu::rasterLinearGroups(uint32_t(items), groupSize);
    c.dispatch(kernel, push, groups.x, groups.y);
}

} // namespace

ComputeStage StrandRaster::stage(Stage stage, uint32_t piece)
{
    using enum Access;
    using namespace gpu; // the bindings: shaders/shared/strand_raster.h, shadows.h
    StageUse frame = uniformBlock(kRasterBindingFrame, uniforms_.descriptors());
    // The meshes' depth samples: the compute meshes' buffer, or the depth image's (strands.depth
    // copies them into a buffer of its own).
    TrackedBuffer& samples = externalSamples_ ? *externalSamples_ : meshSamples_.track;

    switch (stage) {
    case Stage::Clear:
        return {.uses = {commandUse(lightDepth_.track, TransferDst), commandUse(lightOpacity_.track, TransferDst),
                         commandUse(counters_.track, TransferDst)},
                .record = [this](StageCommands& c) {
                    c.fill(lightDepth_.track, 0x3f800000u); // 1.0f: nothing in front
                    c.fill(lightOpacity_.track, 0);
                    c.fill(counters_.track, 0);
                }};
    case Stage::Curves:
        return {.uses = {storageBuffer(kRasterBindingPositions, solver_.positionsTrack(), ComputeRead),
                         storageBuffer(kRasterBindingCurves, curves_.track, ComputeWrite)},
                .record = [this](StageCommands& c) {
                    uint64_t points = uint64_t(camera_.guideCount) * (camera_.divisions + 1);
                    dispatchLinear(c, curvesKernel_, camera_, points, kRasterGroupSize);
                }};
    case Stage::LightGenerate:
    case Stage::Generate: {
        bool fromLight = stage == Stage::LightGenerate;
        ComputeStage s{
            .uses = {frame, uniformBlock(kRasterBindingSim, solver_.params()),
                     storageBuffer(kRasterBindingCurves, curves_.track, ComputeRead),
                     constantBuffer(kRasterBindingTriangles, triangles_),
                     storageBuffer(kRasterBindingVertices, (fromLight ? lightVertices_ : vertices_).track,
                                   ComputeWrite),
                     storageBuffer(kRasterBindingColors, (fromLight ? lightColors_ : colors_).track, ComputeWrite)},
            .record = [this, fromLight](StageCommands& c) {
                const StrandRasterPush& push = fromLight ? light_ : camera_;
                uint64_t vertices = uint64_t(push.guideCount) * push.drawnPerGuide * (push.divisions + 1);
                dispatchLinear(c, fromLight ? generateLightKernel_ : generateKernel_, push, vertices, kRasterGroupSize);
            }};
        if (!fromLight) { // the camera's strands are shaded: the light's maps and the lookup tables
            for (const StageUse& u : maps_.computeReads())
                s.uses.push_back(u);
            s.uses.push_back(
                constantImage(kRasterBindingLut, lut_ ? *lut_ : VkDescriptorImageInfo{}).when(lut_ != nullptr));
        }
        return s;
    }
    case Stage::LightDepth: // (one shader with light.opacity: light.depth binds, never touches, the opacity)
    case Stage::LightOpacity: {
        bool depth = stage == Stage::LightDepth;
        return {.uses = {frame, storageBuffer(kRasterBindingVertices, lightVertices_.track, ComputeRead),
                         storageBuffer(kRasterBindingColors, lightColors_.track, ComputeRead),
                         storageBuffer(kRasterBindingLightDepth, lightDepth_.track, depth ? ComputeWrite : ComputeRead),
                         storageBuffer(kRasterBindingLightOpacity, lightOpacity_.track,
                                       depth ? ComputeRead : ComputeWrite)},
                .record = [this, depth](StageCommands& c) {
                    dispatchLinear(c, depth ? lightDepthKernel_ : lightOpacityKernel_, light_, light_.segmentCount,
                                   kRasterGroupSize);
                }};
    }
    case Stage::LightResolve:
        return {.uses = {storageBuffer(kRasterBindingLightOpacity, lightOpacity_.track, ComputeRead),
                         storageBuffer(kRasterBindingLightDepth, lightDepth_.track, ComputeRead),
                         storageImage(kRasterBindingOpacityImage, maps_.opacity(), maps_.opacityImage().view(),
                                      ComputeWrite),
                         storageImage(kRasterBindingLightDepthImage, maps_.hairDepthValues(),
                                      maps_.hairDepthValuesImage().view(), ComputeWrite)},
                .record = [this](StageCommands& c) {
                    c.dispatch(lightResolveKernel_, light_, vk::groupCount(lightSize_, 8),
                               vk::groupCount(lightSize_, 8));
                }};
    case Stage::LightCopy:
        return {.uses = {commandUse(lightDepth_.track, TransferSrc), commandUse(maps_.hairDepth(), TransferDst)},
                .record = [this](StageCommands& c) {
                    VkBufferImageCopy region{.imageSubresource = {VK_IMAGE_ASPECT_DEPTH_BIT, 0, 0, 1},
                                             .imageExtent = {lightSize_, lightSize_, 1}};
                    c.copyBufferToImage(lightDepth_.track, maps_.hairDepth(), region);
                }};
    case Stage::Depth:
        return {
            .uses = {storageBuffer(kRasterBindingMeshSamples, samples, externalSamples_ ? ComputeRead : ComputeWrite),
                     sampledImage(kRasterBindingMeshDepth, target_.depth(), target_.depthImage().view(), depthSampler_,
                                  DepthSampled)
                         .when(!externalSamples_),
                     storageBuffer(kRasterBindingDepthRange, depthRange_.track, ComputeWrite),
                     storageBuffer(kRasterBindingTileDepth, tileDepth_.track, ComputeWrite),
                     storageBuffer(kRasterBindingCounts, counts_.track, ComputeWrite)},
            .record = [this](StageCommands& c) {
                c.dispatch(externalSamples_ ? depthBufferKernel_ : depthKernel_, camera_,
                           vk::groupCount(camera_.targetWidth, 8), vk::groupCount(camera_.targetHeight, 8));
            }};
    case Stage::CountFragments: // (the walk of strands.write: it binds, never touches, the fragments)
    case Stage::Write: {
        bool write = stage == Stage::Write;
        return {.uses = {storageBuffer(kRasterBindingVertices, vertices_.track, ComputeRead),
                         storageBuffer(kRasterBindingColors, colors_.track, ComputeRead),
                         storageBuffer(kRasterBindingDepthRange, depthRange_.track, ComputeRead),
                         storageBuffer(kRasterBindingTileDepth, tileDepth_.track, ComputeRead),
                         storageBuffer(kRasterBindingMeshSamples, samples, ComputeRead),
                         storageBuffer(kRasterBindingCounts, counts_.track, ComputeWrite), // counts, then cursors
                         storageBuffer(kRasterBindingFragments, fragments_.track, ComputeWrite),
                         storageBuffer(kRasterBindingCounters, counters_.track, ComputeWrite),
                         storageBuffer(kRasterBindingReserved, reserved_.track, ComputeRead),
                         storageBuffer(kRasterBindingSpillList, spillList_.track, write ? ComputeRead : ComputeWrite),
                         storageBuffer(kRasterBindingOffsets, offsets_.track, ComputeRead).when(write),
                         storageBuffer(kRasterBindingPieces, pieces_.track, ComputeRead).when(write),
                         commandUse(pieces_.track, IndirectRead).when(write)},
                .record = [this, write, piece](StageCommands& c) {
                    if (!write) {
                        dispatchLinear(c, countKernel_, camera_, camera_.segmentCount, kRasterGroupSize);
                        return;
                    }
                    StrandRasterPush push = camera_;
                    push.piece = piece;
                    c.dispatchIndirect(writeKernel_, push, pieces_.track,
                                       piece * kPieceBytes + offsetof(RasterPiece, walkGroups));
                }};
    }
    case Stage::ScanBlocks:
    case Stage::ScanTotals:
    case Stage::ScanOffsets:
        return {.uses = {storageBuffer(kRasterBindingCounts, counts_.track, ComputeWrite),
                         storageBuffer(kRasterBindingOffsets, offsets_.track, ComputeWrite),
                         storageBuffer(kRasterBindingBlockSums, blockSums_.track, ComputeWrite),
                         storageBuffer(kRasterBindingCounters, counters_.track, ComputeWrite),
                         storageBuffer(kRasterBindingReserved, reserved_.track, ComputeRead)},
                .record = [this, stage](StageCommands& c) {
                    if (stage == Stage::ScanTotals)
                        c.dispatch(scanTotalsKernel_, camera_, 1);
                    else
                        dispatchLinear(c, stage == Stage::ScanBlocks ? scanBlocksKernel_ : scanOffsetsKernel_, camera_,
                                       camera_.scanBlocks, 1);
                }};
    case Stage::Pieces:
        return {.uses = {storageBuffer(kRasterBindingOffsets, offsets_.track, ComputeRead),
                         storageBuffer(kRasterBindingCounters, counters_.track, ComputeWrite),
                         storageBuffer(kRasterBindingPieces, pieces_.track, ComputeWrite)},
                .record = [this](StageCommands& c) {
                    StrandRasterPush push = camera_;
                    push.piece = recordedPieces_;
                    c.dispatch(piecesKernel_, push, 1);
                }};
    case Stage::Resolve:
        return {.uses = {storageBuffer(kRasterBindingOffsets, offsets_.track, ComputeRead),
                         storageBuffer(kRasterBindingFragments, fragments_.track, ComputeRead),
                         storageBuffer(kRasterBindingCounters, counters_.track, ComputeRead),
                         storageBuffer(kRasterBindingPieces, pieces_.track, ComputeRead),
                         storageBuffer(kRasterBindingReserved, reserved_.track, ComputeRead),
                         commandUse(pieces_.track, IndirectRead),
                         storageImage(kRasterBindingHairColor, colorTrack_, color_.view(), ComputeWrite)},
                .record = [this, piece](StageCommands& c) {
                    StrandRasterPush push = camera_;
                    push.piece = piece;
                    c.dispatchIndirect(resolveKernel_, push, pieces_.track,
                                       piece * kPieceBytes + offsetof(RasterPiece, resolveGroups));
                }};
    case Stage::Reserve:
        return {.uses = {storageBuffer(kRasterBindingOffsets, offsets_.track, ComputeRead),
                         storageBuffer(kRasterBindingReserved, reserved_.track, ComputeWrite)},
                .record = [this](StageCommands& c) {
                    uint64_t entries = uint64_t(camera_.targetWidth) * camera_.targetHeight + 1;
                    dispatchLinear(c, reserveKernel_, camera_, entries, kRasterGroupSize);
                }};
    case Stage::Stats:
        return {.uses = {commandUse(counters_.track, TransferSrc)}, .record = [this](StageCommands& c) {
                    c.copyToHost(counters_.track, readback_.at(c.slot()), sizeof(RasterCounters));
                }};
    }
    throw std::logic_error("no such strands stage");
}

} // namespace wisp
