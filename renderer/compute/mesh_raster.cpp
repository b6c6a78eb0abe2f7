// renderer/compute/mesh_raster.cpp: the compute meshes' buffers, pipelines and stages (each one list of
// what it touches, and its commands; the kernels are shaders/mesh_raster.comp, mesh_shade.comp and
// hair_compose.comp).
#include "renderer/compute/mesh_raster.h"

#include "gpu/context.h"
#include "gpu/frame.h"
#include "gpu/pipeline.h"
#include "renderer/frame_uniforms.h"
#include "renderer/light_maps.h"
#include "renderer/mesh_pass.h"
#include "renderer/render_target.h"
#include "shaders/shared/shadows.h"

#include <algorithm>
#include <stdexcept>

namespace wisp {

namespace {

constexpr uint32_t kMaxGroupsPerDimension = 65535;

const char* stageName(MeshRaster::Stage stage)
{
    switch (stage) {
    case MeshRaster::Stage::Clear:
        return "meshes.clear";
    case MeshRaster::Stage::Raster:
        return "meshes.raster";
    case MeshRaster::Stage::Ids:
        return "meshes.ids";
    case MeshRaster::Stage::Shade:
        return "meshes.shade";
    case MeshRaster::Stage::Compose:
        return "hair.composite";
    case MeshRaster::Stage::Copy:
        return "frame.copy";
    }
    return "meshes";
}

} // namespace

MeshRaster::MeshRaster(const vk::Context& ctx, RenderTarget& target, FrameUniforms& uniforms, LightMaps& maps,
                       MeshPass& meshes)
    : ctx_(ctx), target_(target), uniforms_(uniforms), maps_(maps), meshes_(meshes)
{
    // The layout holds every binding any stage lists (the lists only name the resources here).
    std::vector<ComputeStage> stages;
    for (int s = 0; s <= int(Stage::Copy); ++s)
        stages.push_back(stage(Stage(s)));
    layout_ = StageLayout(ctx, stages, sizeof(gpu::MeshRasterPush), "meshes.compute.layout");
    VkPipelineLayout layout = layout_.layout();
    depthKernel_ = vk::createComputeKernel(ctx, layout, "mesh_raster.comp", "meshes.raster.pipeline", {/*kPhase=*/0});
    idKernel_ = vk::createComputeKernel(ctx, layout, "mesh_raster.comp", "meshes.ids.pipeline", {/*kPhase=*/1});
    shadeKernel_ = vk::createComputeKernel(ctx, layout, "mesh_shade.comp", "meshes.shade.pipeline");
    composeKernel_ = vk::createComputeKernel(ctx, layout, "hair_compose.comp", "hair.composite.pipeline");
    for (int s = 0; s <= int(Stage::Copy); ++s)
        passes_.push_back(
            std::make_unique<ComputeStagePass>(stageName(Stage(s)), layout_, [this, s] { return stage(Stage(s)); }));
    resize();
}

MeshRaster::~MeshRaster() = default;

void MeshRaster::resize()
{
    VkExtent2D e = target_.extent();
    uint64_t samples = uint64_t(e.width) * e.height * uint32_t(target_.samples());
    depth_ = ctx_.createBuffer({.size = samples * 4,
                                .usage = vk::kStorage | vk::kTransferDst | vk::kTransferSrc,
                                .name = "meshes.depth_samples"});
    ids_ = ctx_.createBuffer({.size = samples * 4,
                              .usage = vk::kStorage | vk::kTransferDst | vk::kTransferSrc,
                              .name = "meshes.id_samples"});
    depthTrack_ = {.buffer = depth_};
    idTrack_ = {.buffer = ids_};
    color_ = ctx_.createImage({.format = VK_FORMAT_R16G16B16A16_SFLOAT,
                               .extent = e,
                               .usage = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT,
                               .name = "meshes.color"});
    frame_ = ctx_.createImage({.format = VK_FORMAT_R8G8B8A8_UNORM,
                               .extent = e,
                               .usage = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT,
                               .name = "meshes.frame"});
    colorTrack_ = {.image = color_.get()};
    frameTrack_ = {.image = frame_.get()};
    drawnKey_ = MeshVisibilityKey{}; // new buffers: nothing drawn in them yet
}

void MeshRaster::setVisibility(const glm::mat4& viewProjection, const glm::mat4& headTransform)
{
    VkExtent2D e = target_.extent();
    key_ = MeshVisibilityKey{.viewProjection = viewProjection,
                             .headTransform = headTransform,
                             .sphere = meshes_.sphere(),
                             .marker = meshes_.marker(),
                             .meshVersion = meshes_.meshVersion(),
                             .width = e.width,
                             .height = e.height,
                             .samples = uint32_t(target_.samples()),
                             .pad = 0};
}

uint64_t MeshRaster::allocatedBytes() const
{
    uint64_t pixels = uint64_t(color_.extent().width) * color_.extent().height;
    return depth_.size() + ids_.size() + pixels * (vk::formatBytes(color_.format()) + vk::formatBytes(frame_.format()));
}

gpu::MeshRasterPush MeshRaster::push() const
{
    VkExtent2D e = target_.extent();
    return {.sphere = meshes_.sphere(),
            .marker = meshes_.marker(),
            .headAlbedo = meshes_.albedo(),
            .headRoughness = meshes_.roughness(),
            .scalpAlbedo = meshes_.scalpAlbedo(),
            .scalpStrength = meshes_.scalpStrength(),
            .samples = uint32_t(target_.samples()),
            .width = e.width,
            .height = e.height,
            .object = 0,
            .triangles = 0,
            .pad0 = 0,
            .pad1 = 0,
            .pad2 = 0};
}

ComputeStage MeshRaster::stage(Stage stage)
{
    using enum Access;
    using namespace gpu; // the bindings: shaders/shared/mesh_raster.h, shadows.h
    MeshPass::Buffers head = meshes_.headBuffers(), sphere = meshes_.sphereBuffers();
    StageUse frame = uniformBlock(kMeshRasterBindingFrame, uniforms_.descriptors());
    VkExtent2D e = target_.extent();

    switch (stage) {
    case Stage::Clear:
        return {.uses = {commandUse(depthTrack_, TransferDst), commandUse(idTrack_, TransferDst)},
                .record = [this](StageCommands& c) {
                    c.fill(depthTrack_, kMeshDepthClear);
                    c.fill(idTrack_, kNoMesh);
                }};
    case Stage::Raster: // (one shader with meshes.ids: meshes.raster binds, never touches, the triangles)
    case Stage::Ids: {
        bool ids = stage == Stage::Ids;
        return {.uses = {frame, constantBuffer(kMeshRasterBindingVertices, head.vertices),
                         constantBuffer(kMeshRasterBindingIndices, head.indices),
                         storageBuffer(kMeshRasterBindingDepth, depthTrack_, ids ? ComputeRead : ComputeWrite),
                         storageBuffer(kMeshRasterBindingIds, idTrack_, ids ? ComputeWrite : ComputeRead)},
                .record = [this, ids](StageCommands& c) {
                    rasterize(c, ids ? idKernel_ : depthKernel_);
                    if (ids)
                        drawnKey_ = key_; // the samples now hold this frame's key
                }};
    }
    case Stage::Shade: {
        ComputeStage s{.uses = {frame, constantBuffer(kMeshRasterBindingVertices, head.vertices),
                                constantBuffer(kMeshRasterBindingIndices, head.indices),
                                constantBuffer(kMeshRasterBindingSphereVertices, sphere.vertices),
                                constantBuffer(kMeshRasterBindingSphereIndices, sphere.indices),
                                storageBuffer(kMeshRasterBindingDepth, depthTrack_, ComputeRead),
                                storageBuffer(kMeshRasterBindingIds, idTrack_, ComputeRead),
                                storageImage(kMeshRasterBindingColor, colorTrack_, color_.view(), ComputeWrite)},
                       .record = [this, e](StageCommands& c) {
                           c.dispatch(shadeKernel_, push(), vk::groupCount(e.width, 8), vk::groupCount(e.height, 8));
                       }};
        for (const StageUse& u : maps_.computeReads())
            s.uses.push_back(u);
        return s;
    }
    case Stage::Compose: // (no hair: the meshes' colour is bound in its place, not read)
        return {.uses = {storageImage(kMeshRasterBindingColor, colorTrack_, color_.view(), ComputeRead),
                         storageImage(kMeshRasterBindingHair, hairTrack_ ? *hairTrack_ : colorTrack_,
                                      hairImage_ ? hairImage_->view() : color_.view(), ComputeRead),
                         storageImage(kMeshRasterBindingOut, frameTrack_, frame_.view(), ComputeWrite)},
                .record = [this, e](StageCommands& c) {
                    MeshRasterPush p = push();
                    p.object = hairTrack_ ? 1u : 0u;
                    c.dispatch(composeKernel_, p, vk::groupCount(e.width, 8), vk::groupCount(e.height, 8));
                }};
    case Stage::Copy:
        return {.uses = {commandUse(frameTrack_, TransferSrc), commandUse(target_.result(), TransferDst)},
                .record = [this, e](StageCommands& c) {
                    VkImageCopy region{.srcSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1},
                                       .dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1},
                                       .extent = {e.width, e.height, 1}};
                    c.copyImage(frameTrack_, target_.result(), region);
                }};
    }
    throw std::logic_error("no such meshes stage");
}

void MeshRaster::rasterize(StageCommands& c, const vk::ComputeKernel& kernel)
{
    gpu::MeshRasterPush p = push();
    MeshPass::Buffers head = meshes_.headBuffers(), sphere = meshes_.sphereBuffers();
    struct Draw {
        uint32_t object;
        MeshPass::Buffers buffers;
        bool shown;
    };
    const Draw draws[] = {{gpu::kMeshObjectHead, head, head.triangles > 0},
                          {gpu::kMeshObjectSphere, sphere, p.sphere.w > 0.0f},
                          {gpu::kMeshObjectMarker, sphere, p.marker.w > 0.0f}};
    for (const Draw& d : draws) {
        if (!d.shown || d.buffers.triangles == 0)
            continue;
        c.setConstantBuffer(gpu::kMeshRasterBindingVertices, d.buffers.vertices);
        c.setConstantBuffer(gpu::kMeshRasterBindingIndices, d.buffers.indices);
        gpu::MeshRasterPush drawPush = p;
        drawPush.object = d.object;
        drawPush.triangles = d.buffers.triangles;
        // One workgroup per triangle, in rows of at most 65535.
        uint32_t x = std::min(d.buffers.triangles, kMaxGroupsPerDimension);
        c.dispatch(kernel, drawPush, x, (d.buffers.triangles + x - 1) / x);
    }
}

} // namespace wisp
