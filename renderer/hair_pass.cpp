// renderer/hair_pass.cpp: the hair pipeline (vertex, tessellation, geometry, fragment) and its
// draw: guides x length chunks patches of one control point, one instance per chunk of 64 strands.
#include "renderer/hair_pass.h"

#include "physics/gpu_solver.h"
#include "renderer/frame.h"
#include "renderer/frame_uniforms.h"
#include "renderer/render_target.h"
#include "renderer/vk/check.h"
#include "renderer/vk/context.h"
#include "renderer/vk/pipeline.h"

#include <algorithm>
#include <array>

namespace wisp {

namespace {
// Results come back in the order of the bits: GS invocations, GS primitives, TES invocations.
constexpr VkQueryPipelineStatisticFlags kStatistics = VK_QUERY_PIPELINE_STATISTIC_GEOMETRY_SHADER_INVOCATIONS_BIT |
                                                      VK_QUERY_PIPELINE_STATISTIC_GEOMETRY_SHADER_PRIMITIVES_BIT |
                                                      VK_QUERY_PIPELINE_STATISTIC_TESSELLATION_EVALUATION_SHADER_INVOCATIONS_BIT;
}  // namespace

static_assert(sizeof(gpu::HairPush) == 96, "HairPush must fit the 128 bytes of push constants every device has");

HairDrawCounts hairDrawCounts(uint32_t guides, const StrandSettings& s)
{
    HairDrawCounts c;
    c.guides = guides;
    c.strandsPerGuide = s.strandsPerGuide;
    c.divisions = s.divisions;
    c.lengthChunks = (s.divisions + gpu::kMaxTessLevel - 1) / gpu::kMaxTessLevel;
    uint32_t divisionsPerPatch = (s.divisions + c.lengthChunks - 1) / c.lengthChunks;
    c.strandsPerPatch = std::clamp(s.maxPatchVertices / (divisionsPerPatch + 1), 1u, gpu::kMaxTessLevel);
    c.strandChunks = (s.strandsPerGuide + c.strandsPerPatch - 1) / c.strandsPerPatch;
    return c;
}

HairPass::HairPass(const vk::Context& ctx, RenderTarget& target, FrameUniforms& uniforms, GpuSolver& solver,
                   const StrandSet& strands)
    : ctx_(ctx), target_(target), uniforms_(uniforms), solver_(solver)
{
    if (ctx.report().pipelineStatisticsQuery) {
        VkQueryPoolCreateInfo info{.sType = VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO,
                                   .queryType = VK_QUERY_TYPE_PIPELINE_STATISTICS,
                                   .queryCount = 1,
                                   .pipelineStatistics = kStatistics};
        VkQueryPool pool = VK_NULL_HANDLE;
        VK_CHECK(vkCreateQueryPool(ctx.device(), &info, nullptr, &pool));
        ctx.setName(pool, VK_OBJECT_TYPE_QUERY_POOL, "hair.statistics");
        statistics_ = vk::QueryPool(ctx.device(), pool);
    }
    std::vector<glm::uvec4> triangles = guideTriangles(strands);
    triangles_ = ctx.createBufferWithData({.size = triangles.size() * sizeof(glm::uvec4), .usage = vk::kStorage,
                                           .name = "hair.triangles"},
                                          triangles.data(), triangles.size() * sizeof(glm::uvec4));
    constexpr VkShaderStageFlags kTessellation =
        VK_SHADER_STAGE_TESSELLATION_CONTROL_BIT | VK_SHADER_STAGE_TESSELLATION_EVALUATION_BIT;
    constexpr VkShaderStageFlags kAll = kTessellation | VK_SHADER_STAGE_GEOMETRY_BIT | VK_SHADER_STAGE_FRAGMENT_BIT;
    vk::PipelineLayoutBundle layout = vk::createPipelineLayout(
        ctx, {.bindings = {{gpu::kHairBindingFrame, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, kAll},
                           {gpu::kHairBindingSim, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, kTessellation},
                           {gpu::kHairBindingPositions, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, kTessellation},
                           {gpu::kHairBindingTriangles, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, kTessellation}},
              .pushConstantBytes = sizeof(gpu::HairPush),
              .pushConstantStages = kAll,
              .name = "hair.layout"});
    setLayout_ = std::move(layout.setLayout);
    layout_ = std::move(layout.layout);
    pipeline_ = vk::createGraphicsPipeline(
        ctx, {.layout = layout_,
              .shaders = {"hair.vert", "hair.tesc", "hair.tese", "hair.geom", "hair.frag"},
              .topology = VK_PRIMITIVE_TOPOLOGY_PATCH_LIST,
              .patchControlPoints = 1,
              .cullMode = VK_CULL_MODE_NONE,
              .colorFormat = RenderTarget::kColorFormat,
              .depthFormat = RenderTarget::kDepthFormat,
              .samples = target.samples(),  // coverage is the fragment's sample mask (hair.frag)
              .name = "hair.pipeline"});
}

void HairPass::declare(PassIo& io)
{
    io.use(solver_.positionsTrack(), Access::VertexShaderRead);  // tessellation reads the guides
    target_.declareDraw(io);
}

HairPass::Statistics HairPass::statistics() const
{
    Statistics out;
    if (!statistics_)
        return out;
    uint64_t values[3] = {0, 0, 0};
    VK_CHECK(vkGetQueryPoolResults(ctx_.device(), statistics_, 0, 1, sizeof(values), values, sizeof(values),
                                   VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT));
    out.geometryInvocations = values[0];
    out.geometryPrimitives = values[1];
    out.tessEvaluations = values[2];
    return out;
}

void HairPass::record(VkCommandBuffer cmd, FrameContext& frame)
{
    if (statistics_)
        vkCmdResetQueryPool(cmd, statistics_, 0, 1);
    target_.beginRendering(cmd, glm::vec3(0.0f));
    if (statistics_)
        vkCmdBeginQuery(cmd, statistics_, 0, 0);
    if (counts_.guides > 0 && counts_.strandsPerGuide > 0 && counts_.divisions > 0) {
        vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline_);
        VkDescriptorBufferInfo frameInfo = uniforms_.descriptor(frame.slot);
        VkDescriptorBufferInfo simInfo{solver_.params(), 0, VK_WHOLE_SIZE};
        VkDescriptorBufferInfo positionsInfo{solver_.positions(), 0, VK_WHOLE_SIZE};
        VkDescriptorBufferInfo trianglesInfo{triangles_, 0, VK_WHOLE_SIZE};
        auto write = [](uint32_t binding, VkDescriptorType type, const VkDescriptorBufferInfo* info) {
            return VkWriteDescriptorSet{.sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET,
                                        .dstBinding = binding,
                                        .descriptorCount = 1,
                                        .descriptorType = type,
                                        .pBufferInfo = info};
        };
        std::array<VkWriteDescriptorSet, 4> writes = {
            write(gpu::kHairBindingFrame, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, &frameInfo),
            write(gpu::kHairBindingSim, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, &simInfo),
            write(gpu::kHairBindingPositions, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, &positionsInfo),
            write(gpu::kHairBindingTriangles, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, &trianglesInfo)};
        ctx_.pushDescriptorSet(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, layout_, 0, uint32_t(writes.size()), writes.data());
        push_.samples = uint32_t(target_.samples());
        vkCmdPushConstants(cmd, layout_,
                           VK_SHADER_STAGE_TESSELLATION_CONTROL_BIT | VK_SHADER_STAGE_TESSELLATION_EVALUATION_BIT |
                               VK_SHADER_STAGE_GEOMETRY_BIT | VK_SHADER_STAGE_FRAGMENT_BIT,
                           0, sizeof(push_), &push_);
        vkCmdDraw(cmd, counts_.guides * counts_.lengthChunks, counts_.strandChunks, 0, 0);
    }
    if (statistics_)
        vkCmdEndQuery(cmd, statistics_, 0);
    target_.endRendering(cmd);
}

}  // namespace wisp
