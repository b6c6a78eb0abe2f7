// renderer/strand_raster.h: the hair drawn entirely in compute (hair_raster=compute), beside the
// tessellation path (hair_pass.h), from the same guides and the same strand functions. It owns the
// strand vertices, the screen tiles' bins, the light's accumulation buffers and the hair image, and
// runs as a list of passes (each declares what it touches, so the frame derives every barrier):
//   strands.clear      transfer: the light's depth to 1 and opacity to 0, the tile counts, counters
//   strands.light      the light's strands (fewer, wider: shadow_strands), projected into its map
//   light.depth        the hair's first depth from the light (atomicMin per texel)
//   light.opacity      the deep opacity layers (fixed-point atomicAdd per texel and layer)
//   light.resolve      the layers into the opacity image
//   light.copy         the depth copied into the hair depth map
//     (then the meshes, which read those maps)
//   strands.generate   the camera's strands: placed, projected, shaded per vertex
//   strands.count      segments per screen tile
//   strands.scan       each tile's first bin slot (prefix sum), the total against the capacity
//   strands.bin        each segment's index into its tiles' bins
//   strands.raster     per chunk of a tile's bin and pixel: analytic coverage, the meshes' depth,
//                      the nearest k sorted and the rest blended (the lists' semantics)
//   strands.merge      the lists of tiles shared among several chunks merged; empty tiles cleared
//   hair.composite     the hair image over the target
//   strands.stats      the counters to the host
// The kernels are shaders/strands_*.comp over shaders/shared/strand_raster.h; their C++ twin is
// renderer/strand_raster_reference.h. The bins grow when a frame needs more (the overflowing
// frame's pairs are counted, never written out of bounds); headless pictures render again.
#pragma once

#include "gpu/handle.h"
#include "gpu/pass.h"
#include "gpu/resources.h"
#include "physics/strands.h"
#include "shaders/shared/strand_raster.h"

#include <array>
#include <memory>
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

// One frame's counts (zeros until a frame has completed).
struct RasterStats {
    uint64_t segments = 0;   // segments on screen, binned
    uint64_t pairs = 0;      // (segment, tile) pairs the bins needed
    uint64_t capacity = 0;   // pairs the bins held
    uint64_t overflow = 0;   // pairs that did not fit: dropped that frame, the bins grow for the next
    uint64_t fragments = 0;  // (segment, pixel) overlaps that reached a pixel
    uint64_t chunks = 0;     // raster workgroups (chunks of the tiles' bins)
    uint64_t maxTile = 0;    // the most segments one tile's bin held
};

class StrandRaster {
public:
    enum class Stage {
        Clear, LightGenerate, LightDepth, LightOpacity, LightResolve, LightCopy,
        Generate, Count, Scan, Bin, Raster, Merge, Stats
    };
    static constexpr std::array<Stage, 6> kLightStages = {Stage::Clear,        Stage::LightGenerate, Stage::LightDepth,
                                                          Stage::LightOpacity, Stage::LightResolve,  Stage::LightCopy};
    static constexpr std::array<Stage, 6> kCameraStages = {Stage::Generate, Stage::Count, Stage::Scan, Stage::Bin,
                                                           Stage::Raster, Stage::Merge};
    // Bins hold at least this many (segment, tile) pairs, and start at kInitialPairsPerSegment
    // per segment drawn.
    static constexpr uint64_t kMinBinPairs = 1u << 16;
    static constexpr uint64_t kInitialPairsPerSegment = 4;

    // `triangles`: each guide and its two neighbours (guideTriangles), for multi-strand interpolation.
    StrandRaster(const vk::Context& ctx, RenderTarget& target, FrameUniforms& uniforms, LightMaps& maps,
                 GpuSolver& solver, const std::vector<glm::uvec4>& triangles, uint32_t framesInFlight);
    ~StrandRaster();

    // This frame's strands for the camera and for the light (kernel parameters; the tile counts
    // and sizes are filled in here), the lookup tables' descriptor (owned by the hair pass) and
    // oit_k. Buffers that are too small for them are replaced (the old ones retired to `frame`),
    // and the bins grow to what this slot's last frame needed.
    void prepare(FrameContext& frame, gpu::StrandRasterPush camera, gpu::StrandRasterPush light,
                 const VkDescriptorImageInfo* lut);
    // Recreates what depends on the target's size; the device must be idle.
    void resize();

    Pass* pass(Stage stage);
    TrackedImage& color() { return colorTrack_; }  // the hair, premultiplied RGBA16F
    const vk::Image& colorImage() const { return color_; }
    RasterStats stats(uint32_t slot) const;
    uint64_t binCapacity() const { return binCapacity_; }

    // The buffers, for tests that read them back (tests/test_strand_raster.cpp).
    enum class Buffer { Vertices, Colors, LightVertices, LightColors, TileOffsets, Bins, Counters, LightDepth, LightOpacity,
                        ChunkOffsets, PartialOffsets, ChunkTiles, Dispatch, Partials };
    TrackedBuffer& track(Buffer which) { return storage(which).track; }
    const vk::Buffer& buffer(Buffer which) { return storage(which).buffer; }
    const gpu::StrandRasterPush& cameraPush() const { return camera_; }
    const gpu::StrandRasterPush& lightPush() const { return light_; }
    // Test hook: the bins are remade this small, and grow from there only as overflow makes them.
    // The device must be idle.
    void setBinCapacity(uint64_t pairs);
    // Test hook: how many segments of a tile's bin one raster workgroup takes (kRasterChunkSegments).
    void setChunkSegments(uint32_t segments) { chunkSegments_ = segments; }

    void declare(Stage stage, PassIo& io);
    void record(Stage stage, VkCommandBuffer cmd, FrameContext& frame);

private:
    struct Storage {
        vk::Buffer buffer;
        TrackedBuffer track;
    };
    Storage& storage(Buffer which);
    void allocate(Storage& storage, uint64_t bytes, VkBufferUsageFlags usage, const char* name, FrameContext* frame);
    void dispatch(VkCommandBuffer cmd, VkPipeline pipeline, const gpu::StrandRasterPush& push,
                  const std::vector<VkWriteDescriptorSet>& writes, uint32_t x, uint32_t y = 1);
    void dispatchLinear(VkCommandBuffer cmd, VkPipeline pipeline, const gpu::StrandRasterPush& push,
                        const std::vector<VkWriteDescriptorSet>& writes, uint64_t threads);

    const vk::Context& ctx_;
    RenderTarget& target_;
    FrameUniforms& uniforms_;
    LightMaps& maps_;
    GpuSolver& solver_;
    vk::DescriptorSetLayout setLayout_;
    vk::PipelineLayout layout_;
    vk::Pipeline generatePipeline_, generateLightPipeline_, countPipeline_, binPipeline_, scanPipeline_, rasterPipeline_;
    vk::Pipeline lightDepthPipeline_, lightOpacityPipeline_, lightResolvePipeline_, mergePipeline_;
    uint32_t pipelineK_ = 0;  // the oit_k the raster and merge pipelines were built for
    vk::Sampler depthSampler_;  // the meshes' depth, fetched by texel
    vk::Buffer triangles_;
    Storage vertices_, colors_;            // the camera's strand vertices
    Storage lightVertices_, lightColors_;  // the light's
    Storage tileCounts_, tileOffsets_, bins_, counters_;
    Storage chunkOffsets_, partialOffsets_, chunkTiles_, dispatch_, partials_;
    Storage lightDepth_, lightOpacity_;
    std::vector<vk::Buffer> readback_;  // counters, one per frame in flight
    vk::Image color_;
    TrackedImage colorTrack_;
    uint64_t binCapacity_ = 0;
    uint64_t partialCapacity_ = 0;
    uint64_t forcedCapacity_ = 0;
    uint32_t chunkSegments_ = gpu::kRasterChunkSegments;
    uint32_t lightSize_ = 0;
    gpu::StrandRasterPush camera_{};
    gpu::StrandRasterPush light_{};
    const VkDescriptorImageInfo* lut_ = nullptr;
    std::vector<std::unique_ptr<Pass>> passes_;  // one per Stage
};

}  // namespace wisp
