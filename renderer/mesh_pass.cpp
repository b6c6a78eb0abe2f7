// renderer/mesh_pass.cpp: mesh upload, the mesh pipeline, and its draw.
#include "renderer/mesh_pass.h"

#include "renderer/frame.h"
#include "renderer/frame_uniforms.h"
#include "renderer/light_maps.h"
#include "renderer/render_target.h"
#include "renderer/vk/context.h"
#include "renderer/vk/pipeline.h"
#include "shaders/shared/mesh_params.h"
#include "shaders/shared/shadows.h"

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

void MeshPass::setMesh(const Mesh& mesh)
{
    std::vector<MeshVertex> vertices(mesh.positions.size());
    for (size_t i = 0; i < vertices.size(); ++i)
        vertices[i] = {mesh.positions[i], mesh.normals[i]};
    vertices_ = ctx_.createBufferWithData({.size = vertices.size() * sizeof(MeshVertex), .usage = vk::kVertex, .name = "mesh.vertices"},
                                          vertices.data(), vertices.size() * sizeof(MeshVertex));
    indices_ = ctx_.createBufferWithData({.size = mesh.indices.size() * sizeof(uint32_t), .usage = vk::kIndex, .name = "mesh.indices"},
                                         mesh.indices.data(), mesh.indices.size() * sizeof(uint32_t));
    indexCount_ = static_cast<uint32_t>(mesh.indices.size());
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

void MeshPass::drawMesh(VkCommandBuffer cmd)
{
    gpu::MeshPush push{.model = model_, .albedo = albedo_, .roughness = roughness_};
    vkCmdPushConstants(cmd, layout_, VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0, sizeof(push), &push);
    VkDeviceSize offset = 0;
    VkBuffer vb = vertices_;
    vkCmdBindVertexBuffers(cmd, 0, 1, &vb, &offset);
    vkCmdBindIndexBuffer(cmd, indices_, 0, VK_INDEX_TYPE_UINT32);
    vkCmdDrawIndexed(cmd, indexCount_, 1, 0, 0, 0);
}

void MeshPass::recordFromLight(VkCommandBuffer cmd, FrameContext& frame)
{
    if (indexCount_ == 0)
        return;
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, lightPipeline_);
    uniforms_.push(ctx_, cmd, layout_, frame.slot);
    drawMesh(cmd);
}

void MeshPass::record(VkCommandBuffer cmd, FrameContext& frame)
{
    target_.beginRendering(cmd, clearColor_);
    if (indexCount_ > 0) {
        vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline_);
        uniforms_.push(ctx_, cmd, layout_, frame.slot);
        std::array<VkWriteDescriptorSet, 4> maps = lightMaps_->descriptorWrites();
        ctx_.pushDescriptorSet(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, layout_, 0, uint32_t(maps.size()), maps.data());
        drawMesh(cmd);
    }
    target_.endRendering(cmd);
}

}  // namespace wisp
