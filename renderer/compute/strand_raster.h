// renderer/compute/strand_raster.h: the hair drawn entirely in compute (hair_raster=compute), beside the
// tessellation path (hair_pass.h), from the same guides and the same strand functions. It owns the
// strand vertices, the pixels' fragment buffer, the light's accumulation buffers and the hair
// image, and runs as a list of passes, one per stage, each stage written once as the list of what
// it touches (binding, resource, access: gpu/compute_stage.h), from which the frame derives its
// barriers and the stage's descriptors are pushed (stage() below):
//   strands.clear         transfer: the light's depth to 1 and opacity to 0, the counters
//   strands.light         the light's strands (fewer, wider: shadow_strands), projected into its map
//   light.depth           the hair's first depth from the light (atomicMin per texel)
//   light.opacity         the deep opacity layers (fixed-point atomicAdd per texel and layer)
//   light.resolve         the layers into the opacity image, the depth into the R32F image the
//                         opacity lookups sample
//   light.copy            the depth copied into the hair depth map (only without opacity layers:
//                         the PCF of the hair's shadow compares against it)
//     (then the meshes, which read those maps)
//   strands.generate      the camera's strands: placed, projected, shaded per vertex
//   strands.depth         each pixel's nearest and farthest mesh depth sample; its count zeroed
//   strands.count         each segment's fragments counted at their pixels, and written into
//                         the room the last frame's layout reserved (shaders/shared/strand_raster.h
//                         "One walk") where it has room
//   strands.scan.blocks   the counts' prefix sum: each block's total,
//   strands.scan.totals   the blocks' offsets and the total against the capacity,
//   strands.scan.offsets  each pixel's first slot
//   strands.pieces        the pieces of the frame that fit the fragment buffer (one where the
//                         frame fits): each piece's pixels and its two indirect dispatches
//   strands.write N       (per piece) each of the piece's fragments written to its pixel's slot;
//                         in the reserved layout only the pixels that had no room, from the
//                         list of the fragments strands.count spilled (no threads when none did)
//   strands.resolve N     (per piece) per pixel: the nearest k sorted and the rest blended (the
//                         lists' semantics), one write
//   strands.reserve       the next frame's reserved layout, from this frame's offsets
//   hair.composite        the hair image over the target
//   strands.stats         the counters to the host
// The kernels are shaders/strands_*.comp over shaders/shared/strand_raster.h; their C++ twin is
// renderer/compute/strand_raster_reference.h. The fragment buffer grows to what a frame needs, up
// to a budget (fragment_budget, or a share of the device's memory within one buffer's range);
// a frame past the budget is drawn in pieces (shaders/shared/strand_raster.h "Pieces"), the same
// picture, never missing hair. The pieces are recorded from what the slot's last frame needed,
// with room to spare; a frame that needs more than were recorded counts what it left out, and
// headless pictures render again.
#pragma once

#include "gpu/compute_stage.h"
#include "gpu/handle.h"
#include "gpu/pass.h"
#include "gpu/resources.h"
#include "renderer/strand_draw.h"
#include "shaders/shared/strand_raster.h"

#include <glm/glm.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

namespace wisp {

namespace vk {
class Context;
}
struct FrameContext;
class RenderTarget;
class FrameUniforms;
class GpuSolver;
class LightMaps;

// The strands the light's maps draw per guide, LOD's `lodStrands` (continuous) drawn for the camera:
// `strandFraction` of them (shadow_strands), wider, at least one.
inline float lightLodStrands(float lodStrands, float strandFraction)
{
    return std::max(1.0f, lodStrands * strandFraction);
}
// The strands a guide's LOD of `lodStrands` (continuous) generates: the last one fading, at most all.
inline uint32_t drawnStrandsPerGuide(uint32_t strandsPerGuide, float lodStrands)
{
    return std::min(strandsPerGuide, uint32_t(std::ceil(lodStrands)));
}

// One frame's counts (zeros until a frame has completed).
struct RasterStats {
    uint64_t segments = 0;  // segments on screen
    uint64_t hidden = 0;    // of those, the ones behind the meshes' coarse depth (not walked)
    uint64_t fragments = 0; // fragments the pixels held (what the buffer needed)
    uint64_t capacity = 0;  // fragments the buffer held
    uint64_t overflow = 0;  // fragments not drawn: pieces past those recorded (more are recorded next frame)
    uint64_t maxPixel = 0;  // the most fragments one pixel held
    uint64_t pieces = 1;    // the pieces the frame took (1: it fit the buffer whole)
    bool reserved = false;  // drawn in the last frame's reserved layout ("One walk")
    uint64_t spilled = 0;   // of its fragments, those without reserved room (strands.write places them)
    // Whether strands.count wrote every fragment (no second walk).
    bool oneWalk() const { return reserved && spilled == 0; }
};
// "compute raster: S segments on screen (H behind the meshes), F hair fragments (at most P in a pixel), buffer of C",
// ", one walk" or ", K spilled from their reserved room" in the reserved layout, and ", K not drawn"
// when some did not fit: the line `wisp render` prints and the window's panel shows.
std::string describeRasterStats(const RasterStats& stats);

class StrandRaster {
public:
    enum class Stage {
        Clear,
        Curves,
        LightGenerate,
        LightDepth,
        LightOpacity,
        LightResolve,
        LightCopy,
        Generate,
        Depth,
        CountFragments,
        ScanBlocks,
        ScanTotals,
        ScanOffsets,
        Pieces,
        Write,
        Resolve,
        Reserve,
        Stats
    };
    // (Curves, the guides' points both generates read, runs with the light's stages: before them.)
    static constexpr std::array<Stage, 7> kLightStages = {Stage::Clear,      Stage::Curves,       Stage::LightGenerate,
                                                          Stage::LightDepth, Stage::LightOpacity, Stage::LightResolve,
                                                          Stage::LightCopy};
    // (Then strands.write and strands.resolve for each recorded piece, piecePass, and strands.reserve.)
    static constexpr std::array<Stage, 7> kCameraStages = {Stage::Generate,   Stage::Depth,      Stage::CountFragments,
                                                           Stage::ScanBlocks, Stage::ScanTotals, Stage::ScanOffsets,
                                                           Stage::Pieces};
    // The fragment buffer holds at least this many fragments, and starts at
    // kInitialFragmentsPerSegment per segment drawn.
    static constexpr uint64_t kMinFragments = 1u << 18;
    // The automatic budget: this share of the device-local memory (and at most one buffer's range);
    // any budget holds at least kMinBudget fragments (1 MiB).
    static constexpr uint64_t kBudgetShareOfMemory = 8;
    static constexpr uint64_t kMinBudget = 1u << 17;
    static constexpr uint64_t kInitialFragmentsPerSegment = 8;
    // What each buffer holds per item (shaders/shared/strand_raster.h's bindings).
    static constexpr uint64_t kCurvePointBytes = 2 * sizeof(glm::vec4);     // a guide's curve point: position, tangent
    static constexpr uint64_t kVertexBytes = sizeof(glm::vec4);             // a strand vertex, projected
    static constexpr uint64_t kColorBytes = sizeof(uint32_t);               // its packed colour and opacity
    static constexpr uint64_t kFragmentBytes = 2 * sizeof(uint32_t);        // depth bits, packed colour and opacity
    static constexpr uint64_t kLightDepthBytes = sizeof(float);             // a light texel's first hair depth
    static constexpr uint64_t kLightOpacityBytes = 4 * sizeof(uint32_t);    // its opacity layers, fixed point
    static constexpr uint64_t kPieceBytes = sizeof(gpu::RasterPiece);       // a recorded piece
    static constexpr VkFormat kColorFormat = VK_FORMAT_R16G16B16A16_SFLOAT; // the hair image, premultiplied

    // A buffer's size as allocated: never empty.
    static constexpr uint64_t bufferBytes(uint64_t bytes) { return bytes > 16 ? bytes : 16; }
    // The most fragments one buffer may hold on a device of this storage-buffer range.
    static constexpr uint64_t fragmentLimit(uint64_t maxStorageBufferRange)
    {
        return (maxStorageBufferRange < 0xffffffffull ? maxStorageBufferRange : 0xffffffffull) / kFragmentBytes;
    }
    // The fragments the buffer may grow to: `budgetBytes` (fragment_budget; 0: automatic, a share
    // of the device-local memory), within one buffer's range, at least kMinBudget.
    static constexpr uint64_t fragmentBudget(uint64_t budgetBytes, uint64_t deviceLocalBytes,
                                             uint64_t maxStorageBufferRange)
    {
        uint64_t bytes = budgetBytes > 0 ? budgetBytes : deviceLocalBytes / kBudgetShareOfMemory;
        uint64_t fragments = bytes / kFragmentBytes > kMinBudget ? bytes / kFragmentBytes : kMinBudget;
        uint64_t limit = fragmentLimit(maxStorageBufferRange);
        return fragments < limit ? fragments : limit;
    }
    // The coarse depth's tiles over a target (kRasterDepthTile pixels a side, partial ones included).
    static constexpr uint64_t depthTiles(VkExtent2D extent)
    {
        return uint64_t((extent.width + gpu::kRasterDepthTile - 1) / gpu::kRasterDepthTile) *
               ((extent.height + gpu::kRasterDepthTile - 1) / gpu::kRasterDepthTile);
    }
    // The fragment buffer a first frame of `segments` segments gets, within the budget.
    static constexpr uint64_t initialFragments(uint64_t segments, uint64_t budget)
    {
        uint64_t wanted = segments * kInitialFragmentsPerSegment > kMinFragments
                              ? segments * kInitialFragmentsPerSegment
                              : kMinFragments;
        return wanted < budget ? wanted : budget;
    }

    // What the compute path allocates on the device for a first frame (the fragment buffer grows
    // past it when a frame needs more): allocatedBytes() sums the same buffers as they are made.
    struct DeviceSizes {
        VkExtent2D extent{};
        uint64_t guides = 0;
        uint32_t strandsPerGuide = 0;      // drawn for the camera (all of them at full detail)
        uint32_t lightStrandsPerGuide = 0; // drawn into the light's maps (0: shadows off)
        uint32_t divisions = 0;
        uint32_t lightMapSize = 0;               // shadow_size: texels per side
        uint32_t samples = 1;                    // the target's MSAA samples (the meshes' depth samples)
        uint64_t fragmentBudget = kMinFragments; // fragmentBudget(...) on the device
    };
    static constexpr uint64_t deviceBytes(const DeviceSizes& s)
    {
        uint64_t pixels = uint64_t(s.extent.width) * s.extent.height;
        uint64_t blocks = (pixels + 1 + gpu::kRasterScanBlock - 1) / gpu::kRasterScanBlock;
        uint64_t texels = uint64_t(s.lightMapSize) * s.lightMapSize;
        uint64_t cameraVertices = s.guides * s.strandsPerGuide * (s.divisions + 1);
        uint64_t lightVertices = s.guides * s.lightStrandsPerGuide * (s.divisions + 1);
        uint64_t segments = s.guides * s.strandsPerGuide * s.divisions;
        return s.guides * sizeof(glm::uvec4) + // each guide's triangle of guides
               bufferBytes(s.guides * (s.divisions + 1) * kCurvePointBytes) + bufferBytes(sizeof(gpu::RasterCounters)) +
               bufferBytes(cameraVertices * kVertexBytes) + bufferBytes(cameraVertices * kColorBytes) +
               bufferBytes(lightVertices * kVertexBytes) + bufferBytes(lightVertices * kColorBytes) +
               3 * bufferBytes((pixels + 1) * sizeof(uint32_t)) +  // counts, offsets, reserved (and one past the last)
               bufferBytes(pixels * 2 * sizeof(float)) +           // each pixel's mesh depth range
               bufferBytes(depthTiles(s.extent) * sizeof(float)) + // each tile's farthest mesh sample
               bufferBytes(blocks * sizeof(uint32_t)) +            // the scan's block sums
               bufferBytes(pixels * (s.samples > 1 ? s.samples : 1) * sizeof(uint32_t)) + // the meshes' depth samples
               bufferBytes(texels * kLightDepthBytes) + bufferBytes(texels * kLightOpacityBytes) +
               bufferBytes(initialFragments(segments, s.fragmentBudget) * kFragmentBytes) +
               gpu::kRasterMaxPieces * kPieceBytes + gpu::kRasterSpillList * sizeof(glm::uvec4) +
               pixels * vk::formatBytes(kColorFormat);
    }

    // The storage buffers whose size grows with the workload, each of which must fit one buffer's
    // range (maxStorageBufferRange): the strand vertices and their colours, the guides' curve
    // points, the light's strand vertices, the per-pixel and per-sample buffers.
    struct SizedBuffer {
        const char* name;
        uint64_t bytes;
    };
    static std::vector<SizedBuffer> growingBuffers(const DeviceSizes& s)
    {
        uint64_t pixels = uint64_t(s.extent.width) * s.extent.height;
        uint64_t cameraVertices = s.guides * s.strandsPerGuide * (s.divisions + 1);
        uint64_t lightVertices = s.guides * s.lightStrandsPerGuide * (s.divisions + 1);
        return {{"strands.vertices", cameraVertices * kVertexBytes},
                {"strands.colors", cameraVertices * kColorBytes},
                {"strands.light_vertices", lightVertices * kVertexBytes},
                {"strands.curves", s.guides * (s.divisions + 1) * kCurvePointBytes},
                {"strands.depth_range", pixels * 2 * sizeof(float)},
                {"strands.mesh_samples", pixels * (s.samples > 1 ? s.samples : 1) * sizeof(uint32_t)},
                {"strands.light_opacity", uint64_t(s.lightMapSize) * s.lightMapSize * kLightOpacityBytes}};
    }

    // `triangles`: each guide and its two neighbours (guideTriangles), for multi-strand interpolation.
    StrandRaster(const vk::Context& ctx, RenderTarget& target, FrameUniforms& uniforms, LightMaps& maps,
                 GpuSolver& solver, const std::vector<glm::uvec4>& triangles, uint32_t framesInFlight);
    ~StrandRaster();

    // What a frame draws besides its strands.
    struct FrameOptions {
        bool shadows = true;                        // false: the light's maps are only cleared
        uint32_t oitK = 8;                          // the nearest fragments kept sorted per pixel
        uint32_t domLayers = 0;                     // deep opacity layers
        const VkDescriptorImageInfo* lut = nullptr; // the lookup mode's tables (renderer/hair_lut_image.h)
        uint64_t fragmentBudgetBytes = 0;           // fragment_budget (0: automatic)
    };
    // This frame's strands for the camera and for the light. Buffers too small for them are
    // replaced (the old ones retired to `frame`), and the fragment buffer grows to what this
    // slot's last frame needed.
    void prepare(FrameContext& frame, const StrandDraw& camera, const StrandDraw& light, const FrameOptions& options);
    // Recreates what depends on the target's size; the device must be idle.
    void resize();

    // Where the meshes' depth samples come from: the target's depth image (null: the graphics meshes;
    // strands.depth copies it into a buffer of its own), or the compute meshes' buffer (float bits,
    // pixel * samples + s). Set before each frame it changes.
    void setMeshSamples(TrackedBuffer* samples) { externalSamples_ = samples; }

    Pass* pass(Stage stage);
    // strands.write or strands.resolve of recorded piece `piece` (< recordedPieces()).
    Pass* piecePass(Stage stage, uint32_t piece);
    // The pieces this frame records (prepare chose them from the slot's last frame).
    uint32_t recordedPieces() const { return recordedPieces_; }
    // The fragments the buffer may grow to on this device with this frame's budget.
    uint64_t fragmentBudget() const { return budget_; }
    TrackedImage& color() { return colorTrack_; } // the hair, premultiplied RGBA16F
    const vk::Image& colorImage() const { return color_; }
    RasterStats stats(uint32_t slot) const;
    uint64_t fragmentCapacity() const { return fragmentCapacity_; }
    // The bytes of the device-local buffers and the image it holds now (what deviceBytes
    // estimates; the host-visible counters' readback is not counted).
    uint64_t allocatedBytes() const;

    // The buffers, for tests that read them back (tests/test_strand_raster.cpp).
    enum class Buffer {
        Curves,
        Vertices,
        Colors,
        LightVertices,
        LightColors,
        Offsets,
        Fragments,
        Counters,
        LightDepth,
        LightOpacity,
        Pieces,
        Reserved
    };
    TrackedBuffer& track(Buffer which) { return storage(which).track; }
    const vk::Buffer& buffer(Buffer which) { return storage(which).buffer; }
    const gpu::StrandRasterPush& cameraPush() const { return camera_; }
    const gpu::StrandRasterPush& lightPush() const { return light_; }
    // Test hook: the budget is this many fragments, the buffer remade that size, and what earlier
    // frames needed forgotten (so the next frame records one piece and one to spare). The device
    // must be idle.
    void setFragmentCapacity(uint64_t fragments);
    // Test hook: the spill list holds this many fragments (at most kRasterSpillList); past them
    // strands.write walks every segment again.
    void setSpillCapacity(uint32_t fragments) { spillCapacity_ = std::min(fragments, gpu::kRasterSpillList); }

    // Each stage as the one list of what it touches (binding, resource, access) and its commands
    // (`piece`: which recorded piece strands.write or strands.resolve draws): its pass declares
    // and records from it, and the layout holds every binding the stages list.
    ComputeStage stage(Stage stage, uint32_t piece = 0);
    const StageLayout& layout() const { return layout_; }

private:
    struct Storage {
        vk::Buffer buffer;
        TrackedBuffer track;
    };
    Storage& storage(Buffer which);
    void allocate(Storage& storage, uint64_t bytes, VkBufferUsageFlags usage, const char* name, FrameContext* frame);

    const vk::Context& ctx_;
    RenderTarget& target_;
    FrameUniforms& uniforms_;
    LightMaps& maps_;
    GpuSolver& solver_;
    StageLayout layout_;
    vk::ComputeKernel generateKernel_, generateLightKernel_, depthKernel_, depthBufferKernel_, countKernel_,
        writeKernel_;
    vk::ComputeKernel scanBlocksKernel_, scanTotalsKernel_, scanOffsetsKernel_, piecesKernel_, resolveKernel_,
        reserveKernel_;
    vk::ComputeKernel lightDepthKernel_, lightOpacityKernel_, lightResolveKernel_, curvesKernel_;
    uint32_t pipelineK_ = 0;   // the oit_k the resolve pipeline was built for
    vk::Sampler depthSampler_; // the meshes' depth, fetched by texel
    vk::Buffer triangles_;
    Storage curves_;                      // the guides' curve points (strands.curves)
    Storage vertices_, colors_;           // the camera's strand vertices
    Storage lightVertices_, lightColors_; // the light's
    Storage counts_, offsets_, fragments_, counters_, depthRange_, tileDepth_, blockSums_, pieces_;
    Storage reserved_;  // each pixel's reserved first slot (strands.reserve; zeros: no room)
    Storage spillList_; // the fragments strands.count spilled (strands.write places them)
    uint32_t spillCapacity_ = gpu::kRasterSpillList;
    Storage meshSamples_; // the depth image's samples, when the meshes are drawn by graphics
    TrackedBuffer* externalSamples_ = nullptr;
    Storage lightDepth_, lightOpacity_;
    std::vector<vk::Buffer> readback_; // counters, one per frame in flight
    vk::Image color_;
    TrackedImage colorTrack_;
    uint64_t fragmentCapacity_ = 0;
    uint64_t forcedCapacity_ = 0;
    uint64_t budget_ = kMinFragments;
    uint32_t recordedPieces_ = 1;
    uint32_t lightSize_ = 0;
    gpu::StrandRasterPush camera_{};
    gpu::StrandRasterPush light_{};
    const VkDescriptorImageInfo* lut_ = nullptr;
    std::vector<std::unique_ptr<ComputeStagePass>> passes_;      // one per Stage
    std::vector<std::unique_ptr<ComputeStagePass>> piecePasses_; // strands.write N, strands.resolve N, pair by pair
};

} // namespace wisp
