// renderer/mesh_pass.cpp: mesh upload, the mesh pipeline, and its draw.
#include "renderer/mesh_pass.h"

#include "gpu/context.h"
#include "gpu/frame.h"
#include "gpu/pipeline.h"
#include "renderer/frame_uniforms.h"
#include "renderer/light_maps.h"
#include "renderer/render_target.h"
#include "shaders/shared/mesh_params.h"
#include "shaders/shared/mesh_raster.h"
#include "shaders/shared/shadows.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <vector>

#include <cstring>

namespace wisp {

namespace {

struct MeshVertex {
    glm::vec3 position;
    glm::vec3 normal;
    float scalp; // 0..1, kMeshLocationScalp
};
static_assert(sizeof(MeshVertex) == 28);

// The depth pass before the shading (MeshPass::depthPass).
class MeshDepthPass : public Pass {
public:
    explicit MeshDepthPass(MeshPass& meshes) : meshes_(meshes) {}
    const char* name() const override { return "meshes.depth"; }
    void declare(PassIo& io) override { meshes_.declareDepth(io); }
    void record(VkCommandBuffer cmd, FrameContext& frame) override { meshes_.recordDepth(cmd, frame); }

private:
    MeshPass& meshes_;
};

} // namespace

std::vector<float> scalpCoverage(const Mesh& head, const StrandSet& strands)
{
    if (strands.scalpPaint.size() == head.positions.size())
        return strands.scalpPaint; // grown hair: the field its roots were grown at
    std::vector<float> out(head.positions.size(), 0.0f);
    size_t n = strands.strandCount();
    if (n == 0)
        return out;
    uint32_t V = strands.verticesPerStrand;
    std::vector<glm::vec3> roots(n);
    Bounds b{strands.rest[0], strands.rest[0]};
    for (size_t s = 0; s < n; ++s) {
        roots[s] = strands.rest[s * V];
        b.min = glm::min(b.min, roots[s]);
        b.max = glm::max(b.max, roots[s]);
    }
    // A hash grid of the roots, cells of about two roots each.
    glm::vec3 size = glm::max(b.size(), glm::vec3(1e-6f * std::max(b.diagonal(), 1e-6f)));
    float cell = std::max(std::sqrt((size.x * size.y + size.y * size.z + size.z * size.x) * 2.0f / float(n)),
                          1e-4f * b.diagonal());
    glm::ivec3 dims = glm::min(glm::ivec3(size / cell) + 1, glm::ivec3(256));
    glm::vec3 step = size / glm::vec3(dims) + glm::vec3(1e-12f);
    auto cellOf = [&](glm::vec3 p) {
        return glm::clamp(glm::ivec3(glm::floor((p - b.min) / step)), glm::ivec3(0), dims - 1);
    };
    std::vector<std::vector<uint32_t>> grid(size_t(dims.x) * dims.y * dims.z);
    auto key = [&](glm::ivec3 c) { return (size_t(c.z) * dims.y + c.y) * dims.x + c.x; };
    for (uint32_t s = 0; s < n; ++s)
        grid[key(cellOf(roots[s]))].push_back(s);
    auto nearest = [&](glm::vec3 p, uint32_t skip, float within) {
        float best = within;
        glm::ivec3 lo = cellOf(p - glm::vec3(within)), hi = cellOf(p + glm::vec3(within));
        for (int z = lo.z; z <= hi.z; ++z)
            for (int y = lo.y; y <= hi.y; ++y)
                for (int x = lo.x; x <= hi.x; ++x)
                    for (uint32_t o : grid[key({x, y, z})])
                        if (o != skip)
                            best = std::min(best, glm::length(roots[o] - p));
        return best;
    };
    // The roots' typical spacing: the median distance to the nearest other root (of up to 2,000).
    std::vector<float> spacing;
    for (size_t s = 0; s < n; s += std::max<size_t>(1, n / 2000))
        spacing.push_back(nearest(roots[s], uint32_t(s), 4.0f * cell));
    std::nth_element(spacing.begin(), spacing.begin() + std::ptrdiff_t(spacing.size() / 2), spacing.end());
    float typical = std::max(spacing[spacing.size() / 2], 1e-6f * b.diagonal());
    if (n == 1)
        typical = 0.01f * std::max(head.bounds().diagonal(), 1e-6f);
    float inner = 1.0f * typical, outer = 2.5f * typical;
    for (size_t v = 0; v < out.size(); ++v) {
        float d = nearest(head.positions[v], UINT32_MAX, outer);
        float t = std::clamp((d - inner) / (outer - inner), 0.0f, 1.0f);
        out[v] = 1.0f - t * t * (3.0f - 2.0f * t);
    }
    return out;
}

MeshPass::MeshPass(const vk::Context& ctx, RenderTarget& target, FrameUniforms& uniforms, LightMaps& maps)
    : ctx_(ctx), target_(target), uniforms_(uniforms), maps_(maps)
{
    vk::PipelineLayoutBundle layout = vk::createPipelineLayout(
        ctx,
        {.bindings =
             {{.binding = gpu::kFrameParamsBinding,
               .type = VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER,
               .stages = VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT},
              {gpu::kBindingShadowHead, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, VK_SHADER_STAGE_FRAGMENT_BIT},
              {gpu::kBindingShadowHair, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, VK_SHADER_STAGE_FRAGMENT_BIT},
              {gpu::kBindingHairDepth, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, VK_SHADER_STAGE_FRAGMENT_BIT},
              {gpu::kBindingOpacity, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, VK_SHADER_STAGE_FRAGMENT_BIT},
              {gpu::kMeshBindingShadowMask, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, VK_SHADER_STAGE_FRAGMENT_BIT}},
         .pushConstantBytes = sizeof(gpu::MeshPush),
         .pushConstantStages = VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT,
         .name = "mesh.layout"});
    // (The light's maps are read by mesh_shadow.comp; the shading reads the mask at binding 8.)
    setLayout_ = std::move(layout.setLayout);
    layout_ = std::move(layout.layout);
    vk::GraphicsPipelineDesc shade{
        .layout = layout_,
        .shaders = {"mesh.vert", "mesh.frag"},
        .vertexStride = sizeof(MeshVertex),
        .attributes = {{.location = gpu::kMeshLocationPosition,
                        .format = VK_FORMAT_R32G32B32_SFLOAT,
                        .offset = offsetof(MeshVertex, position)},
                       {.location = gpu::kMeshLocationNormal,
                        .format = VK_FORMAT_R32G32B32_SFLOAT,
                        .offset = offsetof(MeshVertex, normal)},
                       {.location = gpu::kMeshLocationScalp,
                        .format = VK_FORMAT_R32_SFLOAT,
                        .offset = offsetof(MeshVertex, scalp)}},
        .cullMode = VK_CULL_MODE_NONE, // meshes from the wild are not always closed or consistently wound
        .depthWrite = false,           // the depth pass has written it; the same surfaces pass LESS_OR_EQUAL
        .colorFormat = RenderTarget::kColorFormat,
        .depthFormat = RenderTarget::kDepthFormat,
        .samples = target.samples(),
        .name = "mesh.pipeline"};
    pipeline_ = vk::createGraphicsPipeline(ctx, shade);
    backgroundPipeline_ = vk::createGraphicsPipeline(ctx, {.layout = layout_,
                                                           .shaders = {"fullscreen.vert", "background.frag"},
                                                           .cullMode = VK_CULL_MODE_NONE,
                                                           .depthTest = false,
                                                           .depthWrite = false,
                                                           .colorFormat = RenderTarget::kColorFormat,
                                                           .depthFormat = RenderTarget::kDepthFormat,
                                                           .samples = target.samples(),
                                                           .name = "mesh.background.pipeline"});
    vk::GraphicsPipelineDesc depth = shade;
    depth.shaders = {"mesh.vert"};
    depth.depthWrite = true;
    depth.colorFormat = VK_FORMAT_UNDEFINED; // depth alone
    depth.name = "mesh.depth.pipeline";
    depthPipeline_ = vk::createGraphicsPipeline(ctx, depth);

    nearest_ = vk::createSampler(ctx, VK_FILTER_NEAREST, false, "mesh.nearest.sampler");
    ComputeStage shadow = shadowMaskStage(); // (the layout holds the bindings it lists)
    shadowLayout_ = StageLayout(ctx, std::span(&shadow, 1), sizeof(gpu::MeshShadowPush), "mesh.shadow.layout");
    shadowKernel_ = vk::createComputeKernel(ctx, shadowLayout_.layout(),
                                            target.multisampled() ? "mesh_shadow.comp" : "mesh_shadow_single.comp",
                                            "mesh.shadow.pipeline");
    depthPass_ = std::make_unique<MeshDepthPass>(*this);
    shadowMaskPass_ =
        std::make_unique<ComputeStagePass>("meshes.shadow", shadowLayout_, [this] { return shadowMaskStage(); });
    resize();
    lightPipeline_ = vk::createGraphicsPipeline(
        ctx, {.layout = layout_,
              .shaders = {"mesh_light.vert"},
              .vertexStride = sizeof(MeshVertex),
              .attributes = {{.location = gpu::kMeshLocationPosition,
                              .format = VK_FORMAT_R32G32B32_SFLOAT,
                              .offset = offsetof(MeshVertex, position)},
                             {.location = gpu::kMeshLocationNormal,
                              .format = VK_FORMAT_R32G32B32_SFLOAT,
                              .offset = offsetof(MeshVertex, normal)},
                             {.location = gpu::kMeshLocationScalp,
                              .format = VK_FORMAT_R32_SFLOAT,
                              .offset = offsetof(MeshVertex, scalp)}},
              .cullMode = VK_CULL_MODE_NONE,
              .depthBiasConstant = 2.0f, // keeps lit surfaces from shadowing themselves (acne)
              .depthBiasSlope = 2.0f,
              .depthFormat = LightMaps::kDepthFormat,
              .name = "mesh.light_depth.pipeline"});
}

MeshPass::~MeshPass() = default;

void MeshPass::resize()
{
    shadowMask_ = ctx_.createImage({.format = VK_FORMAT_R8G8B8A8_UNORM,
                                    .extent = target_.extent(),
                                    .usage = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT,
                                    .name = "mesh.shadow_mask"});
    shadowMaskTrack_ = {.image = shadowMask_.get()};
}

MeshPass::GpuMesh MeshPass::upload(const Mesh& mesh, const char* name, const std::vector<float>& scalp) const
{
    std::vector<MeshVertex> vertices(mesh.positions.size());
    for (size_t i = 0; i < vertices.size(); ++i)
        vertices[i] = {mesh.positions[i], mesh.normals[i], i < scalp.size() ? scalp[i] : 0.0f};
    std::string base = name;
    GpuMesh out;
    out.vertices = ctx_.createBufferWithData({.size = vertices.size() * sizeof(MeshVertex),
                                              .usage = vk::kVertex | vk::kStorage,
                                              .name = (base + ".vertices").c_str()},
                                             vertices.data(), vertices.size() * sizeof(MeshVertex));
    out.indices = ctx_.createBufferWithData({.size = mesh.indices.size() * sizeof(uint32_t),
                                             .usage = vk::kIndex | vk::kStorage,
                                             .name = (base + ".indices").c_str()},
                                            mesh.indices.data(), mesh.indices.size() * sizeof(uint32_t));
    out.indexCount = static_cast<uint32_t>(mesh.indices.size());
    return out;
}

void MeshPass::setMesh(const Mesh& mesh, const std::vector<float>& scalp)
{
    head_ = upload(mesh, "mesh.head", scalp);
    ++meshVersion_;
    if (sphereMesh_.indexCount == 0)
        sphereMesh_ = upload(makeSphereMesh(), "mesh.sphere", {});
}

void MeshPass::setSurface(const glm::vec3& albedo, float roughness)
{
    albedo_ = albedo;
    roughness_ = roughness;
}

void MeshPass::declare(PassIo& io)
{
    io.use(shadowMaskTrack_, Access::FragmentSampled);
    target_.declareDraw(io, RenderTarget::DepthUse::TestOnly); // the depth pass wrote it
}

void MeshPass::declareDepth(PassIo& io)
{
    target_.declareDepth(io);
}

void MeshPass::draw(VkCommandBuffer cmd, const GpuMesh& mesh, const glm::mat4& model, const glm::vec3& albedo,
                    float roughness)
{
    if (mesh.indexCount == 0)
        return;
    gpu::MeshPush push{.model = model,
                       .albedo = albedo,
                       .roughness = roughness,
                       .scalpAlbedo = scalpAlbedo_,
                       .scalpStrength = scalpStrength_};
    vkCmdPushConstants(cmd, layout_, VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0, sizeof(push), &push);
    VkDeviceSize offset = 0;
    VkBuffer vb = mesh.vertices;
    vkCmdBindVertexBuffers(cmd, 0, 1, &vb, &offset);
    vkCmdBindIndexBuffer(cmd, mesh.indices, 0, VK_INDEX_TYPE_UINT32);
    vkCmdDrawIndexed(cmd, mesh.indexCount, 1, 0, 0, 0);
}

namespace {

glm::mat4 placeSphere(const glm::vec4& sphere)
{
    glm::mat4 m(sphere.w);
    m[3] = glm::vec4(glm::vec3(sphere), 1.0f);
    return m;
}

using gpu::kMarkerAlbedo;
using gpu::kMarkerRoughness;
using gpu::kSphereAlbedo;
using gpu::kSphereRoughness;

} // namespace

void MeshPass::recordFromLight(VkCommandBuffer cmd, FrameContext& frame)
{
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, lightPipeline_);
    uniforms_.push(ctx_, cmd, layout_, frame.slot);
    draw(cmd, head_, headTransform_, albedo_, roughness_);
    if (sphere_.w > 0.0f)
        draw(cmd, sphereMesh_, placeSphere(sphere_), kSphereAlbedo, kSphereRoughness);
}

void MeshPass::recordDepth(VkCommandBuffer cmd, FrameContext& frame)
{
    target_.beginDepthRendering(cmd);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, depthPipeline_);
    uniforms_.push(ctx_, cmd, layout_, frame.slot);
    draw(cmd, head_, headTransform_, albedo_, roughness_);
    if (sphere_.w > 0.0f)
        draw(cmd, sphereMesh_, placeSphere(sphere_), kSphereAlbedo, kSphereRoughness);
    if (marker_.w > 0.0f)
        draw(cmd, sphereMesh_, placeSphere(marker_), kMarkerAlbedo, kMarkerRoughness);
    target_.endRendering(cmd);
}

ComputeStage MeshPass::shadowMaskStage()
{
    using enum Access;
    using namespace gpu; // the bindings: shaders/shared/mesh_params.h, shadows.h
    ComputeStage s{.uses = {uniformBlock(kMeshBindingFrame, uniforms_.descriptors())}};
    for (const StageUse& u : maps_.computeReads())
        s.uses.push_back(u);
    s.uses.push_back(
        sampledImage(kMeshBindingDepth, target_.depth(), target_.depthImage().view(), nearest_, DepthSampled));
    s.uses.push_back(storageImage(kMeshBindingShadowMask, shadowMaskTrack_, shadowMask_.view(), ComputeWrite));
    s.record = [this](StageCommands& c) {
        VkExtent2D e = target_.extent();
        MeshShadowPush push{.inverseViewProjection = inverseViewProjection_,
                            .width = e.width,
                            .height = e.height,
                            .samples = uint32_t(target_.samples()),
                            .pad = 0};
        c.dispatch(shadowKernel_, push, vk::groupCount(e.width, 8), vk::groupCount(e.height, 8));
    };
    return s;
}

void MeshPass::record(VkCommandBuffer cmd, FrameContext& frame)
{
    // The backdrop first, over every sample (the clear is overdrawn), then the meshes over it.
    target_.beginRendering(cmd, glm::vec3(0.0f), RenderTarget::DepthUse::TestOnly);
    uniforms_.push(ctx_, cmd, layout_, frame.slot);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, backgroundPipeline_);
    vkCmdDraw(cmd, 3, 1, 0, 0);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline_);
    VkDescriptorImageInfo mask{nearest_, shadowMask_.view(), VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
    VkWriteDescriptorSet maskWrite =
        vk::imageWrite(gpu::kMeshBindingShadowMask, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, &mask);
    ctx_.pushDescriptorSet(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, layout_, 0, 1, &maskWrite);
    draw(cmd, head_, headTransform_, albedo_, roughness_);
    if (sphere_.w > 0.0f)
        draw(cmd, sphereMesh_, placeSphere(sphere_), kSphereAlbedo, kSphereRoughness);
    if (marker_.w > 0.0f)
        draw(cmd, sphereMesh_, placeSphere(marker_), kMarkerAlbedo, kMarkerRoughness);
    target_.endRendering(cmd);
}

} // namespace wisp
