// renderer/graphics/hair_pass.cpp: the hair pipeline (vertex, tessellation, geometry, fragment) and its
// draw: guides x length chunks patches of one control point, one instance per chunk of 64 strands.
#include "renderer/graphics/hair_pass.h"

#include "gpu/check.h"
#include "gpu/context.h"
#include "gpu/frame.h"
#include "gpu/pipeline.h"
#include "physics/gpu_solver.h"
#include "renderer/frame_uniforms.h"
#include "renderer/graphics/oit.h"
#include "renderer/hair_lut_image.h"
#include "renderer/light_maps.h"
#include "renderer/render_target.h"

#include <algorithm>
#include <array>
#include <cstring>
#include <string>
#include <vector>

namespace wisp {

namespace {
// Results come back in the order of the bits: GS invocations, GS primitives, TES invocations.
constexpr VkQueryPipelineStatisticFlags kStatistics =
    VK_QUERY_PIPELINE_STATISTIC_GEOMETRY_SHADER_INVOCATIONS_BIT |
    VK_QUERY_PIPELINE_STATISTIC_GEOMETRY_SHADER_PRIMITIVES_BIT |
    VK_QUERY_PIPELINE_STATISTIC_TESSELLATION_EVALUATION_SHADER_INVOCATIONS_BIT;
} // namespace

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
    c.patchesPerDraw = std::max(1u, gpu::kMaxTessVerticesPerDraw / (c.strandsPerPatch * (divisionsPerPatch + 1)));
    return c;
}

std::string describeHairDraw(const HairDrawCounts& c)
{
    return "drawn as " + std::to_string(c.patches() * c.strandChunks) + " patches of up to " +
           std::to_string(c.strandsPerPatch) + " strands x " +
           std::to_string((c.divisions + c.lengthChunks - 1) / c.lengthChunks) + " divisions (" +
           std::to_string(c.strandChunks) + " instances, " + std::to_string(c.draws()) + " draws)";
}

HairPass::HairPass(const vk::Context& ctx, RenderTarget& target, FrameUniforms& uniforms, GpuSolver& solver,
                   const std::vector<glm::uvec4>& triangles)
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
    triangles_ = ctx.createBufferWithData(
        {.size = triangles.size() * sizeof(glm::uvec4), .usage = vk::kStorage, .name = "hair.triangles"},
        triangles.data(), triangles.size() * sizeof(glm::uvec4));
    constexpr VkShaderStageFlags kTessellation =
        VK_SHADER_STAGE_TESSELLATION_CONTROL_BIT | VK_SHADER_STAGE_TESSELLATION_EVALUATION_BIT;
    constexpr VkShaderStageFlags kFragment = VK_SHADER_STAGE_FRAGMENT_BIT;
    constexpr VkShaderStageFlags kEvaluation = VK_SHADER_STAGE_TESSELLATION_EVALUATION_BIT;
    constexpr VkShaderStageFlags kAll =
        VK_SHADER_STAGE_VERTEX_BIT | kTessellation | VK_SHADER_STAGE_GEOMETRY_BIT | kFragment;
    constexpr VkDescriptorType kSampler = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
    constexpr VkDescriptorType kStorage = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    vk::PipelineLayoutBundle layout = vk::createPipelineLayout(
        ctx, {.bindings = {{gpu::kHairBindingFrame, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, kAll},
                           {gpu::kHairBindingSim, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, kTessellation},
                           {gpu::kHairBindingPositions, kStorage, kTessellation},
                           {gpu::kHairBindingTriangles, kStorage, kTessellation},
                           // The camera's hair reads the light's maps per vertex (hair.tese); the
                           // opacity pass reads the hair's first depth per fragment.
                           {gpu::kBindingShadowHead, kSampler, kEvaluation},
                           {gpu::kBindingShadowHair, kSampler, kEvaluation},
                           {gpu::kBindingHairDepth, kSampler, kEvaluation | kFragment},
                           {gpu::kBindingOpacity, kSampler, kEvaluation},
                           {gpu::kHairBindingOitHeads, kStorage, kFragment},
                           {gpu::kHairBindingOitNodes, kStorage, kFragment},
                           {gpu::kHairBindingOitCounters, kStorage, kFragment},
                           {gpu::kHairBindingLut, kSampler, kFragment}},
              .pushConstantBytes = sizeof(gpu::HairPush),
              .pushConstantStages = kAll,
              .name = "hair.layout"});
    setLayout_ = std::move(layout.setLayout);
    layout_ = std::move(layout.layout);

    vk::GraphicsPipelineDesc camera{.layout = layout_,
                                    .shaders = {"hair.vert", "hair.tesc", "hair.tese", "hair.geom", "hair.frag"},
                                    .topology = VK_PRIMITIVE_TOPOLOGY_PATCH_LIST,
                                    .patchControlPoints = 1,
                                    .cullMode = VK_CULL_MODE_NONE,
                                    .colorFormat = RenderTarget::kColorFormat,
                                    .depthFormat = RenderTarget::kDepthFormat,
                                    .samples = target.samples(), // coverage is the fragment's sample mask (hair.frag)
                                    .name = "hair.pipeline"};
    pipeline_ = vk::createGraphicsPipeline(ctx, camera);
    vk::GraphicsPipelineDesc oit = camera;
    oit.shaders.back() = "hair_oit.frag";
    oit.depthWrite = false; // tested against the head, never hiding other hair
    oit.colorWrite = false;
    oit.name = "hair.oit.pipeline";
    oitPipeline_ = vk::createGraphicsPipeline(ctx, oit);
    vk::GraphicsPipelineDesc depth{.layout = layout_,
                                   .shaders = {"hair.vert", "hair.tesc", "hair_light.tese", "hair_light.geom"},
                                   .topology = VK_PRIMITIVE_TOPOLOGY_PATCH_LIST,
                                   .patchControlPoints = 1,
                                   .cullMode = VK_CULL_MODE_NONE,
                                   .depthFormat = LightMaps::kDepthFormat,
                                   .name = "hair.light_depth.pipeline"};
    depthPipeline_ = vk::createGraphicsPipeline(ctx, depth);
    vk::GraphicsPipelineDesc opacity = depth;
    opacity.shaders.push_back("hair_opacity.frag");
    opacity.depthTest = false;
    opacity.depthWrite = false;
    opacity.depthFormat = VK_FORMAT_UNDEFINED;
    opacity.colorFormat = LightMaps::kOpacityFormat;
    opacity.blend = vk::Blend::Additive;
    opacity.name = "hair.light_opacity.pipeline";
    opacityPipeline_ = vk::createGraphicsPipeline(ctx, opacity);
}

void HairPass::setDraw(const StrandDraw& camera, const StrandDraw& light, const HairDrawCounts& counts)
{
    counts_ = counts;
    auto push = [&](const StrandDraw& d) {
        gpu::HairPush p{};
        p.guideCount = d.guides;
        p.verticesPerStrand = d.verticesPerStrand;
        p.strandsPerGuide = d.strandsPerGuide;
        p.divisions = d.divisions;
        p.lengthChunks = counts.lengthChunks;
        p.strandsPerPatch = counts.strandsPerPatch;
        p.interpolation = d.interpolation;
        p.clumpRadius = d.clumpRadius;
        p.deviation = d.deviation;
        p.coilRadius = d.coilRadius;
        p.coilFrequency = d.coilFrequency;
        p.width = d.width;
        p.lodStrands = d.lodStrands;
        p.lodWidthScale = d.lodWidthScale;
        p.minPixelWidth = d.minPixelWidth;
        p.reverseOrder = d.reverseOrder ? 1u : 0u;
        return p;
    };
    push_ = push(camera);
    lightPush_ = push(light);
}

void HairPass::declareFromLight(PassIo& io)
{
    io.use(solver_.positionsTrack(), Access::VertexShaderRead); // tessellation reads the guides
}

void HairPass::declare(PassIo& io)
{
    declareFromLight(io);
    lightMaps_->declareRead(io);
    if (oit_) {
        io.use(oit_->heads(), Access::FragmentStorageWrite);
        io.use(oit_->nodes(), Access::FragmentStorageWrite);
        io.use(oit_->counters(), Access::FragmentStorageWrite);
    }
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

void HairPass::draw(VkCommandBuffer cmd, FrameContext& frame, VkPipeline pipeline,
                    const std::vector<VkWriteDescriptorSet>& extra, gpu::HairPush push)
{
    if (counts_.guides == 0 || counts_.strandsPerGuide == 0 || counts_.divisions == 0)
        return;
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline);
    VkDescriptorBufferInfo frameInfo = uniforms_.descriptor(frame.slot);
    VkDescriptorBufferInfo simInfo{solver_.params(), 0, VK_WHOLE_SIZE};
    VkDescriptorBufferInfo positionsInfo{solver_.positions(), 0, VK_WHOLE_SIZE};
    VkDescriptorBufferInfo trianglesInfo{triangles_, 0, VK_WHOLE_SIZE};
    std::vector<VkWriteDescriptorSet> writes = {
        vk::bufferWrite(gpu::kHairBindingFrame, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, &frameInfo),
        vk::bufferWrite(gpu::kHairBindingSim, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, &simInfo),
        vk::bufferWrite(gpu::kHairBindingPositions, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, &positionsInfo),
        vk::bufferWrite(gpu::kHairBindingTriangles, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, &trianglesInfo)};
    writes.insert(writes.end(), extra.begin(), extra.end());
    ctx_.pushDescriptorSet(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, layout_, 0, uint32_t(writes.size()), writes.data());
    push.samples = uint32_t(target_.samples());
    vkCmdPushConstants(cmd, layout_,
                       VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_TESSELLATION_CONTROL_BIT |
                           VK_SHADER_STAGE_TESSELLATION_EVALUATION_BIT | VK_SHADER_STAGE_GEOMETRY_BIT |
                           VK_SHADER_STAGE_FRAGMENT_BIT,
                       0, sizeof(push), &push);
    // Consecutive patches in draws of at most patchesPerDraw (hair.vert reads gl_VertexIndex,
    // which counts from the draw's first vertex, so the split changes nothing else).
    uint32_t patches = counts_.guides * counts_.lengthChunks;
    for (uint32_t first = 0; first < patches; first += counts_.patchesPerDraw)
        vkCmdDraw(cmd, std::min(counts_.patchesPerDraw, patches - first), counts_.strandChunks, first, 0);
}

void HairPass::recordFromLight(VkCommandBuffer cmd, FrameContext& frame, LightMap map)
{
    if (map == LightMap::Depth)
        draw(cmd, frame, depthPipeline_, {}, lightPush_);
    else
        draw(cmd, frame, opacityPipeline_, {lightMaps_->hairDepthWrite()}, lightPush_); // z0: where the layers start
}

void HairPass::record(VkCommandBuffer cmd, FrameContext& frame)
{
    std::vector<VkWriteDescriptorSet> extra;
    for (const VkWriteDescriptorSet& w : lightMaps_->descriptorWrites())
        extra.push_back(w);
    extra.push_back({.sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET,
                     .dstBinding = gpu::kHairBindingLut,
                     .descriptorCount = 1,
                     .descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER,
                     .pImageInfo = &lut_->info()});
    std::array<VkDescriptorBufferInfo, 3> oitInfos{};
    if (oit_) {
        oitInfos = {VkDescriptorBufferInfo{oit_->headsBuffer(), 0, VK_WHOLE_SIZE},
                    VkDescriptorBufferInfo{oit_->nodesBuffer(), 0, VK_WHOLE_SIZE},
                    VkDescriptorBufferInfo{oit_->countersBuffer(), 0, VK_WHOLE_SIZE}};
        const uint32_t bindings[3] = {gpu::kHairBindingOitHeads, gpu::kHairBindingOitNodes,
                                      gpu::kHairBindingOitCounters};
        for (uint32_t i = 0; i < 3; ++i)
            extra.push_back({.sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET,
                             .dstBinding = bindings[i],
                             .descriptorCount = 1,
                             .descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,
                             .pBufferInfo = &oitInfos[i]});
    }
    if (statistics_)
        vkCmdResetQueryPool(cmd, statistics_, 0, 1);
    target_.beginRendering(cmd, glm::vec3(0.0f));
    if (statistics_)
        vkCmdBeginQuery(cmd, statistics_, 0, 0);
    draw(cmd, frame, oit_ ? oitPipeline_.get() : pipeline_.get(), extra, push_);
    if (statistics_)
        vkCmdEndQuery(cmd, statistics_, 0);
    target_.endRendering(cmd);
}

} // namespace wisp
