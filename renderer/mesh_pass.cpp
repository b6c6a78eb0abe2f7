// renderer/mesh_pass.cpp: mesh upload, the mesh pipeline, and its draw.
#include "renderer/mesh_pass.h"

#include "gpu/frame.h"
#include "renderer/frame_uniforms.h"
#include "renderer/light_maps.h"
#include "renderer/render_target.h"
#include "gpu/context.h"
#include "gpu/pipeline.h"
#include "shaders/shared/mesh_params.h"
#include "shaders/shared/shadows.h"

#include <array>
#include <string>
#include <vector>

#include <cstring>

namespace wisp {

static_assert(sizeof(gpu::MeshPush) == 80, "MeshPush: mat4 + vec3 + float");

namespace {

struct MeshVertex {
    glm::vec3 position;
    glm::vec3 normal;
};
static_assert(sizeof(MeshVertex) == 24);

}  // namespace

MeshPass::MeshPass(const vk::Context& ctx, RenderTarget& target, FrameUniforms& uniforms)
    : ctx_(ctx), target_(target), uniforms_(uniforms)
{
    vk::PipelineLayoutBundle layout = vk::createPipelineLayout(
        ctx, {.bindings = {{.binding = gpu::kFrameParamsBinding,
                            .type = VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER,
                            .stages = VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT},
                           {gpu::kBindingShadowHead, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, VK_SHADER_STAGE_FRAGMENT_BIT},
                           {gpu::kBindingShadowHair, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, VK_SHADER_STAGE_FRAGMENT_BIT},
                           {gpu::kBindingHairDepth, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, VK_SHADER_STAGE_FRAGMENT_BIT},
                           {gpu::kBindingOpacity, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, VK_SHADER_STAGE_FRAGMENT_BIT}},
              .pushConstantBytes = sizeof(gpu::MeshPush),
              .pushConstantStages = VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT,
              .name = "mesh.layout"});
    setLayout_ = std::move(layout.setLayout);
    layout_ = std::move(layout.layout);
    pipeline_ = vk::createGraphicsPipeline(
        ctx, {.layout = layout_,
              .shaders = {"mesh.vert", "mesh.frag"},
              .vertexStride = sizeof(MeshVertex),
              .attributes = {{.location = gpu::kMeshLocationPosition, .format = VK_FORMAT_R32G32B32_SFLOAT,
                              .offset = offsetof(MeshVertex, position)},
                             {.location = gpu::kMeshLocationNormal, .format = VK_FORMAT_R32G32B32_SFLOAT,
                              .offset = offsetof(MeshVertex, normal)}},
              .cullMode = VK_CULL_MODE_NONE,  // meshes from the wild are not always closed or consistently wound
              .colorFormat = RenderTarget::kColorFormat,
              .depthFormat = RenderTarget::kDepthFormat,
              .samples = target.samples(),
              .name = "mesh.pipeline"});
    lightPipeline_ = vk::createGraphicsPipeline(
        ctx, {.layout = layout_,
              .shaders = {"mesh_light.vert"},
              .vertexStride = sizeof(MeshVertex),
              .attributes = {{.location = gpu::kMeshLocationPosition, .format = VK_FORMAT_R32G32B32_SFLOAT,
                              .offset = offsetof(MeshVertex, position)},
                             {.location = gpu::kMeshLocationNormal, .format = VK_FORMAT_R32G32B32_SFLOAT,
                              .offset = offsetof(MeshVertex, normal)}},
              .cullMode = VK_CULL_MODE_NONE,
              .depthBiasConstant = 2.0f,  // keeps lit surfaces from shadowing themselves (acne)
              .depthBiasSlope = 2.0f,
              .depthFormat = LightMaps::kDepthFormat,
              .name = "mesh.light_depth.pipeline"});
}

MeshPass::GpuMesh MeshPass::upload(const Mesh& mesh, const char* name) const
{
    std::vector<MeshVertex> vertices(mesh.positions.size());
    for (size_t i = 0; i < vertices.size(); ++i)
        vertices[i] = {mesh.positions[i], mesh.normals[i]};
    std::string base = name;
    GpuMesh out;
    out.vertices = ctx_.createBufferWithData(
        {.size = vertices.size() * sizeof(MeshVertex), .usage = vk::kVertex, .name = (base + ".vertices").c_str()},
        vertices.data(), vertices.size() * sizeof(MeshVertex));
    out.indices = ctx_.createBufferWithData(
        {.size = mesh.indices.size() * sizeof(uint32_t), .usage = vk::kIndex, .name = (base + ".indices").c_str()},
        mesh.indices.data(), mesh.indices.size() * sizeof(uint32_t));
    out.indexCount = static_cast<uint32_t>(mesh.indices.size());
    return out;
}

void MeshPass::setMesh(const Mesh& mesh)
{
    head_ = upload(mesh, "mesh.head");
    if (sphereMesh_.indexCount == 0)
        sphereMesh_ = upload(makeSphereMesh(), "mesh.sphere");
}

void MeshPass::setSurface(const glm::mat4& model, const glm::vec3& albedo, float roughness)
{
    model_ = model;
    albedo_ = albedo;
    roughness_ = roughness;
}

void MeshPass::declare(PassIo& io)
{
    lightMaps_->declareRead(io);
    target_.declareDraw(io);
}

void MeshPass::draw(VkCommandBuffer cmd, const GpuMesh& mesh, const glm::mat4& model, const glm::vec3& albedo,
                    float roughness)
{
    if (mesh.indexCount == 0)
        return;
    gpu::MeshPush push{.model = model, .albedo = albedo, .roughness = roughness};
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

constexpr glm::vec3 kSphereAlbedo{0.35f, 0.45f, 0.6f};  // a blue-grey ball, apart from skin and hair
constexpr glm::vec3 kMarkerAlbedo{1.0f, 0.85f, 0.3f};

}  // namespace

void MeshPass::recordFromLight(VkCommandBuffer cmd, FrameContext& frame)
{
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, lightPipeline_);
    uniforms_.push(ctx_, cmd, layout_, frame.slot);
    draw(cmd, head_, headTransform_ * model_, albedo_, roughness_);
    if (sphere_.w > 0.0f)
        draw(cmd, sphereMesh_, placeSphere(sphere_), kSphereAlbedo, 0.4f);
}

void MeshPass::record(VkCommandBuffer cmd, FrameContext& frame)
{
    target_.beginRendering(cmd, clearColor_);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline_);
    uniforms_.push(ctx_, cmd, layout_, frame.slot);
    std::array<VkWriteDescriptorSet, 4> maps = lightMaps_->descriptorWrites();
    ctx_.pushDescriptorSet(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, layout_, 0, uint32_t(maps.size()), maps.data());
    draw(cmd, head_, headTransform_ * model_, albedo_, roughness_);
    if (sphere_.w > 0.0f)
        draw(cmd, sphereMesh_, placeSphere(sphere_), kSphereAlbedo, 0.4f);
    if (marker_.w > 0.0f)
        draw(cmd, sphereMesh_, placeSphere(marker_), kMarkerAlbedo, 0.2f);
    target_.endRendering(cmd);
}

}  // namespace wisp
