// renderer/guide_pass.cpp: a line list over every strand's segments.
#include "renderer/guide_pass.h"

#include "gpu/context.h"
#include "gpu/frame.h"
#include "gpu/pipeline.h"
#include "physics/gpu_solver.h"
#include "renderer/frame_uniforms.h"
#include "renderer/render_target.h"
#include "shaders/shared/guide_params.h"
#include "shaders/shared/sim.h"

namespace wisp {

GuidePass::GuidePass(const vk::Context& ctx, RenderTarget& target, FrameUniforms& uniforms, GpuSolver& solver,
                     uint32_t strandCount, uint32_t verticesPerStrand)
    : ctx_(ctx), target_(target), uniforms_(uniforms), solver_(solver), verticesPerStrand_(verticesPerStrand)
{
    std::vector<uint32_t> indices;
    indices.reserve(size_t(strandCount) * (verticesPerStrand - 1) * 2);
    for (uint32_t s = 0; s < strandCount; ++s)
        for (uint32_t i = 1; i < verticesPerStrand; ++i) {
            indices.push_back(gpu::vertexSlot(s, i - 1, verticesPerStrand)); // the solver's interleaved layout
            indices.push_back(gpu::vertexSlot(s, i, verticesPerStrand));
        }
    indexCount_ = uint32_t(indices.size());
    indices_ = ctx.createBufferWithData(
        {.size = indices.size() * sizeof(uint32_t), .usage = vk::kIndex, .name = "guides.indices"}, indices.data(),
        indices.size() * sizeof(uint32_t));
    vk::PipelineLayoutBundle layout =
        vk::createPipelineLayout(ctx, {.bindings = {{.binding = gpu::kFrameParamsBinding,
                                                     .type = VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER,
                                                     .stages = VK_SHADER_STAGE_VERTEX_BIT}},
                                       .pushConstantBytes = sizeof(gpu::GuidePush),
                                       .pushConstantStages = VK_SHADER_STAGE_VERTEX_BIT,
                                       .name = "guides.layout"});
    setLayout_ = std::move(layout.setLayout);
    layout_ = std::move(layout.layout);
    pipeline_ = vk::createGraphicsPipeline(ctx, {.layout = layout_,
                                                 .shaders = {"guide.vert", "guide.frag"},
                                                 .vertexStride = sizeof(glm::vec4),
                                                 .attributes = {{.location = gpu::kGuideLocationPosition,
                                                                 .format = VK_FORMAT_R32G32B32A32_SFLOAT,
                                                                 .offset = 0}},
                                                 .topology = VK_PRIMITIVE_TOPOLOGY_LINE_LIST,
                                                 .cullMode = VK_CULL_MODE_NONE,
                                                 .colorFormat = RenderTarget::kColorFormat,
                                                 .depthFormat = RenderTarget::kDepthFormat,
                                                 .samples = target.samples(),
                                                 .name = "guides.pipeline"});
}

void GuidePass::declare(PassIo& io)
{
    io.use(solver_.positionsTrack(), Access::VertexInput);
    target_.declareDraw(io);
}

void GuidePass::record(VkCommandBuffer cmd, FrameContext& frame)
{
    target_.beginRendering(cmd, glm::vec3(0.0f));
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline_);
    uniforms_.push(ctx_, cmd, layout_, frame.slot);
    gpu::GuidePush push{.rootColor = glm::vec3(0.08f, 0.03f, 0.01f),
                        .verticesPerStrand = verticesPerStrand_,
                        .tipColor = glm::vec3(0.75f, 0.42f, 0.16f),
                        .pad = 0.0f};
    vkCmdPushConstants(cmd, layout_, VK_SHADER_STAGE_VERTEX_BIT, 0, sizeof(push), &push);
    VkDeviceSize offset = 0;
    VkBuffer vb = solver_.positions();
    vkCmdBindVertexBuffers(cmd, 0, 1, &vb, &offset);
    vkCmdBindIndexBuffer(cmd, indices_, 0, VK_INDEX_TYPE_UINT32);
    vkCmdDrawIndexed(cmd, indexCount_, 1, 0, 0, 0);
    target_.endRendering(cmd);
}

} // namespace wisp
