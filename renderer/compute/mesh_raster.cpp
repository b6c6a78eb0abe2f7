// renderer/compute/mesh_raster.cpp: the compute meshes' buffers, pipelines and passes (what each stage
// declares and records; the kernels are shaders/mesh_raster.comp, mesh_shade.comp and
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

namespace wisp {

static_assert(sizeof(gpu::MeshRasterPush) == 96, "MeshRasterPush must fit the 128 bytes of push constants");

namespace {

constexpr VkDescriptorType kStorage = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
constexpr VkDescriptorType kImage = VK_DESCRIPTOR_TYPE_STORAGE_IMAGE;

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
    constexpr VkShaderStageFlags kCompute = VK_SHADER_STAGE_COMPUTE_BIT;
    constexpr VkDescriptorType kSampler = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
    vk::PipelineLayoutBundle layout = vk::createPipelineLayout(
        ctx, {.bindings = {{gpu::kMeshRasterBindingFrame, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, kCompute},
                           {gpu::kMeshRasterBindingVertices, kStorage, kCompute},
                           {gpu::kMeshRasterBindingIndices, kStorage, kCompute},
                           {gpu::kMeshRasterBindingSphereVertices, kStorage, kCompute},
                           {gpu::kBindingShadowHead, kSampler, kCompute},
                           {gpu::kBindingShadowHair, kSampler, kCompute},
                           {gpu::kBindingHairDepth, kSampler, kCompute},
                           {gpu::kBindingOpacity, kSampler, kCompute},
                           {gpu::kMeshRasterBindingSphereIndices, kStorage, kCompute},
                           {gpu::kMeshRasterBindingDepth, kStorage, kCompute},
                           {gpu::kMeshRasterBindingIds, kStorage, kCompute},
                           {gpu::kMeshRasterBindingColor, kImage, kCompute},
                           {gpu::kMeshRasterBindingHair, kImage, kCompute},
                           {gpu::kMeshRasterBindingOut, kImage, kCompute}},
              .pushConstantBytes = sizeof(gpu::MeshRasterPush),
              .pushConstantStages = kCompute,
              .name = "meshes.compute.layout"});
    setLayout_ = std::move(layout.setLayout);
    layout_ = std::move(layout.layout);
    depthPipeline_ =
        vk::createComputePipeline(ctx, layout_, "mesh_raster.comp", "meshes.raster.pipeline", {/*kPhase=*/0});
    idPipeline_ = vk::createComputePipeline(ctx, layout_, "mesh_raster.comp", "meshes.ids.pipeline", {/*kPhase=*/1});
    shadePipeline_ = vk::createComputePipeline(ctx, layout_, "mesh_shade.comp", "meshes.shade.pipeline");
    composePipeline_ = vk::createComputePipeline(ctx, layout_, "hair_compose.comp", "hair.composite.pipeline");
    for (int s = 0; s <= int(Stage::Copy); ++s)
        passes_.push_back(std::make_unique<StagePass<MeshRaster, Stage>>(*this, Stage(s), stageName(Stage(s))));
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

void MeshRaster::declare(Stage stage, PassIo& io)
{
    switch (stage) {
    case Stage::Clear:
        io.use(depthTrack_, Access::TransferDst);
        io.use(idTrack_, Access::TransferDst);
        break;
    case Stage::Raster:
        io.use(depthTrack_, Access::ComputeWrite);
        io.use(idTrack_, Access::ComputeRead); // (bound, not touched: one shader with meshes.ids)
        break;
    case Stage::Ids:
        io.use(depthTrack_, Access::ComputeRead);
        io.use(idTrack_, Access::ComputeWrite);
        break;
    case Stage::Shade:
        maps_.declareRead(io, Access::ComputeSampled);
        io.use(depthTrack_, Access::ComputeRead);
        io.use(idTrack_, Access::ComputeRead);
        io.use(colorTrack_, Access::ComputeWrite);
        break;
    case Stage::Compose:
        io.use(colorTrack_, Access::ComputeRead);
        if (hairTrack_)
            io.use(*hairTrack_, Access::ComputeRead);
        io.use(frameTrack_, Access::ComputeWrite);
        break;
    case Stage::Copy:
        io.use(frameTrack_, Access::TransferSrc);
        io.use(target_.result(), Access::TransferDst);
        break;
    }
}

void MeshRaster::record(Stage stage, VkCommandBuffer cmd, FrameContext& frame)
{
    VkExtent2D e = target_.extent();
    gpu::MeshRasterPush p = push();
    VkDescriptorBufferInfo frameInfo = uniforms_.descriptor(frame.slot);
    VkDescriptorBufferInfo depth{depth_, 0, VK_WHOLE_SIZE}, ids{ids_, 0, VK_WHOLE_SIZE};
    MeshPass::Buffers head = meshes_.headBuffers(), sphere = meshes_.sphereBuffers();
    VkDescriptorBufferInfo headVertices{head.vertices, 0, VK_WHOLE_SIZE}, headIndices{head.indices, 0, VK_WHOLE_SIZE};
    VkDescriptorBufferInfo sphereVertices{sphere.vertices, 0, VK_WHOLE_SIZE};
    VkDescriptorBufferInfo sphereIndices{sphere.indices, 0, VK_WHOLE_SIZE};
    auto bindAndPush = [&](VkPipeline pipeline, const std::vector<VkWriteDescriptorSet>& writes,
                           const gpu::MeshRasterPush& push) {
        vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline);
        ctx_.pushDescriptorSet(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, layout_, 0, uint32_t(writes.size()), writes.data());
        vkCmdPushConstants(cmd, layout_, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(push), &push);
    };

    switch (stage) {
    case Stage::Clear:
        vkCmdFillBuffer(cmd, depth_, 0, VK_WHOLE_SIZE, gpu::kMeshDepthClear);
        vkCmdFillBuffer(cmd, ids_, 0, VK_WHOLE_SIZE, gpu::kNoMesh);
        break;
    case Stage::Raster:
    case Stage::Ids: {
        VkPipeline pipeline = stage == Stage::Raster ? depthPipeline_.get() : idPipeline_.get();
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
            VkDescriptorBufferInfo vertices{d.buffers.vertices, 0, VK_WHOLE_SIZE};
            VkDescriptorBufferInfo indices{d.buffers.indices, 0, VK_WHOLE_SIZE};
            std::vector<VkWriteDescriptorSet> writes = {
                vk::bufferWrite(gpu::kMeshRasterBindingFrame, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, &frameInfo),
                vk::bufferWrite(gpu::kMeshRasterBindingVertices, kStorage, &vertices),
                vk::bufferWrite(gpu::kMeshRasterBindingIndices, kStorage, &indices),
                vk::bufferWrite(gpu::kMeshRasterBindingDepth, kStorage, &depth),
                vk::bufferWrite(gpu::kMeshRasterBindingIds, kStorage, &ids)};
            gpu::MeshRasterPush drawPush = p;
            drawPush.object = d.object;
            drawPush.triangles = d.buffers.triangles;
            bindAndPush(pipeline, writes, drawPush);
            // One workgroup per triangle, in rows of at most 65535.
            uint32_t x = std::min(d.buffers.triangles, kMaxGroupsPerDimension);
            vkCmdDispatch(cmd, x, (d.buffers.triangles + x - 1) / x, 1);
        }
        break;
    }
    case Stage::Shade: {
        VkDescriptorImageInfo color{VK_NULL_HANDLE, color_.view(), VK_IMAGE_LAYOUT_GENERAL};
        std::vector<VkWriteDescriptorSet> writes = {
            vk::bufferWrite(gpu::kMeshRasterBindingFrame, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, &frameInfo),
            vk::bufferWrite(gpu::kMeshRasterBindingVertices, kStorage, &headVertices),
            vk::bufferWrite(gpu::kMeshRasterBindingIndices, kStorage, &headIndices),
            vk::bufferWrite(gpu::kMeshRasterBindingSphereVertices, kStorage, &sphereVertices),
            vk::bufferWrite(gpu::kMeshRasterBindingSphereIndices, kStorage, &sphereIndices),
            vk::bufferWrite(gpu::kMeshRasterBindingDepth, kStorage, &depth),
            vk::bufferWrite(gpu::kMeshRasterBindingIds, kStorage, &ids),
            vk::imageWrite(gpu::kMeshRasterBindingColor, kImage, &color)};
        for (const VkWriteDescriptorSet& w : maps_.descriptorWrites())
            writes.push_back(w);
        bindAndPush(shadePipeline_, writes, p);
        vkCmdDispatch(cmd, vk::groupCount(e.width, 8), vk::groupCount(e.height, 8), 1);
        break;
    }
    case Stage::Compose: {
        VkDescriptorImageInfo color{VK_NULL_HANDLE, color_.view(), VK_IMAGE_LAYOUT_GENERAL};
        VkDescriptorImageInfo hair{VK_NULL_HANDLE, hairImage_ ? hairImage_->view() : color_.view(),
                                   VK_IMAGE_LAYOUT_GENERAL}; // (no hair: bound, not read)
        VkDescriptorImageInfo out{VK_NULL_HANDLE, frame_.view(), VK_IMAGE_LAYOUT_GENERAL};
        std::vector<VkWriteDescriptorSet> writes = {vk::imageWrite(gpu::kMeshRasterBindingColor, kImage, &color),
                                                    vk::imageWrite(gpu::kMeshRasterBindingHair, kImage, &hair),
                                                    vk::imageWrite(gpu::kMeshRasterBindingOut, kImage, &out)};
        p.object = hairTrack_ ? 1u : 0u;
        bindAndPush(composePipeline_, writes, p);
        vkCmdDispatch(cmd, vk::groupCount(e.width, 8), vk::groupCount(e.height, 8), 1);
        break;
    }
    case Stage::Copy: {
        VkImageCopy region{.srcSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1},
                           .dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1},
                           .extent = {e.width, e.height, 1}};
        vkCmdCopyImage(cmd, frame_.get(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, target_.resultImage().get(),
                       VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &region);
        break;
    }
    }
}

} // namespace wisp
