// gpu/pipeline.cpp: SPIR-V loading, pipeline layouts and graphics pipelines.
#include "gpu/pipeline.h"

#include "gpu/check.h"
#include "gpu/context.h"

#include <algorithm>
#include <array>
#include <cstdio>
#include <fstream>
#include <map>
#include <stdexcept>
#include <unistd.h>
#include <vector>

#ifndef WISP_SHADER_DIR
#error "WISP_SHADER_DIR must name the build tree's shader directory"
#endif

namespace wisp::vk {

std::filesystem::path shaderDirectory()
{
    std::error_code ec;
    std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", ec);
    if (!ec) {
        std::filesystem::path beside = exe.parent_path() / "shaders";
        if (std::filesystem::is_directory(beside, ec))
            return beside;
    }
    return WISP_SHADER_DIR;
}

namespace {

VkShaderStageFlagBits stageOf(const std::string& fileName)
{
    auto ends = [&](const char* ext) {
        std::string e = std::string(ext) + ".spv";
        return fileName.size() >= e.size() && fileName.compare(fileName.size() - e.size(), e.size(), e) == 0;
    };
    if (ends(".vert"))
        return VK_SHADER_STAGE_VERTEX_BIT;
    if (ends(".tesc"))
        return VK_SHADER_STAGE_TESSELLATION_CONTROL_BIT;
    if (ends(".tese"))
        return VK_SHADER_STAGE_TESSELLATION_EVALUATION_BIT;
    if (ends(".geom"))
        return VK_SHADER_STAGE_GEOMETRY_BIT;
    if (ends(".frag"))
        return VK_SHADER_STAGE_FRAGMENT_BIT;
    if (ends(".comp"))
        return VK_SHADER_STAGE_COMPUTE_BIT;
    throw std::runtime_error("shader '" + fileName + "' has no known stage extension");
}

} // namespace

static std::vector<uint32_t> readSpirv(const std::string& fileName)
{
    std::filesystem::path path = shaderDirectory() / fileName;
    std::ifstream in(path, std::ios::binary | std::ios::ate);
    if (!in)
        throw std::runtime_error("shader '" + path.string() + "' not found: build the wisp_shaders target");
    std::streamsize bytes = in.tellg();
    if (bytes <= 0 || bytes % 4 != 0)
        throw std::runtime_error("shader '" + path.string() + "' is not SPIR-V (size " + std::to_string(bytes) + ")");
    std::vector<uint32_t> code(static_cast<size_t>(bytes) / 4);
    in.seekg(0);
    in.read(reinterpret_cast<char*>(code.data()), bytes);
    return code;
}

std::vector<uint32_t> spirvBindings(std::span<const uint32_t> words)
{
    constexpr uint32_t kMagic = 0x07230203, kVersion14 = 0x00010400;
    constexpr uint32_t kOpEntryPoint = 15, kOpDecorate = 71, kBinding = 33, kDescriptorSet = 34;
    if (words.size() < 5 || words[0] != kMagic)
        throw std::runtime_error("not SPIR-V");
    if (words[1] < kVersion14) // (before 1.4 an entry point lists only its inputs and outputs)
        throw std::runtime_error("SPIR-V older than 1.4: its entry point does not list the descriptors it uses");
    std::vector<uint32_t> used;
    std::map<uint32_t, uint32_t> binding, set;
    for (size_t i = 5; i < words.size();) {
        uint32_t count = words[i] >> 16, op = words[i] & 0xffffu;
        if (count == 0 || i + count > words.size())
            throw std::runtime_error("malformed SPIR-V");
        if (op == kOpEntryPoint) { // model, function, name (nul-terminated), then the globals it uses
            size_t j = i + 3;
            auto ends = [](uint32_t w) {
                return (w & 0xffu) == 0 || (w & 0xff00u) == 0 || (w & 0xff0000u) == 0 || (w & 0xff000000u) == 0;
            };
            while (j < i + count && !ends(words[j]))
                ++j;
            used.insert(used.end(), words.begin() + ptrdiff_t(j + 1), words.begin() + ptrdiff_t(i + count));
        } else if (op == kOpDecorate && count >= 4 && (words[i + 2] == kBinding || words[i + 2] == kDescriptorSet)) {
            (words[i + 2] == kBinding ? binding : set)[words[i + 1]] = words[i + 3];
        }
        i += count;
    }
    std::vector<uint32_t> out;
    for (uint32_t id : used)
        if (binding.count(id) && (!set.count(id) || set[id] == 0))
            out.push_back(binding[id]);
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
    return out;
}

std::vector<uint32_t> shaderBindings(const std::string& shader)
{
    return spirvBindings(readSpirv(shader + ".spv"));
}

ShaderModule loadShader(const Context& ctx, const std::string& fileName)
{
    std::vector<uint32_t> code = readSpirv(fileName);
    size_t bytes = code.size() * 4;
    VkShaderModuleCreateInfo info{
        .sType = VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO, .codeSize = bytes, .pCode = code.data()};
    VkShaderModule module = VK_NULL_HANDLE;
    VK_CHECK(vkCreateShaderModule(ctx.device(), &info, nullptr, &module));
    ctx.setName(module, VK_OBJECT_TYPE_SHADER_MODULE, fileName.c_str());
    return ShaderModule(ctx.device(), module);
}

PipelineLayoutBundle createPipelineLayout(const Context& ctx, const PipelineLayoutDesc& desc)
{
    std::vector<VkDescriptorSetLayoutBinding> bindings;
    for (const DescriptorBinding& b : desc.bindings)
        bindings.push_back(
            {.binding = b.binding, .descriptorType = b.type, .descriptorCount = 1, .stageFlags = b.stages});
    VkDescriptorSetLayoutCreateInfo setInfo{.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO,
                                            .flags = VK_DESCRIPTOR_SET_LAYOUT_CREATE_PUSH_DESCRIPTOR_BIT_KHR,
                                            .bindingCount = static_cast<uint32_t>(bindings.size()),
                                            .pBindings = bindings.data()};
    VkDescriptorSetLayout setLayout = VK_NULL_HANDLE;
    VK_CHECK(vkCreateDescriptorSetLayout(ctx.device(), &setInfo, nullptr, &setLayout));
    ctx.setName(setLayout, VK_OBJECT_TYPE_DESCRIPTOR_SET_LAYOUT, desc.name);
    PipelineLayoutBundle out{.setLayout = DescriptorSetLayout(ctx.device(), setLayout), .layout = {}};

    VkPushConstantRange range{.stageFlags = desc.pushConstantStages, .offset = 0, .size = desc.pushConstantBytes};
    VkPipelineLayoutCreateInfo info{.sType = VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO,
                                    .setLayoutCount = 1,
                                    .pSetLayouts = &setLayout,
                                    .pushConstantRangeCount = desc.pushConstantBytes ? 1u : 0u,
                                    .pPushConstantRanges = &range};
    VkPipelineLayout layout = VK_NULL_HANDLE;
    VK_CHECK(vkCreatePipelineLayout(ctx.device(), &info, nullptr, &layout));
    ctx.setName(layout, VK_OBJECT_TYPE_PIPELINE_LAYOUT, desc.name);
    out.layout = PipelineLayout(ctx.device(), layout);
    return out;
}

Pipeline createGraphicsPipeline(const Context& ctx, const GraphicsPipelineDesc& desc)
{
    std::vector<ShaderModule> modules;
    std::vector<VkPipelineShaderStageCreateInfo> stages;
    for (const std::string& name : desc.shaders) {
        std::string file = name + ".spv";
        modules.push_back(loadShader(ctx, file));
        stages.push_back({.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO,
                          .stage = stageOf(file),
                          .module = modules.back(),
                          .pName = "main"});
    }

    VkVertexInputBindingDescription binding{
        .binding = 0, .stride = desc.vertexStride, .inputRate = VK_VERTEX_INPUT_RATE_VERTEX};
    std::vector<VkVertexInputAttributeDescription> attributes;
    for (const VertexAttribute& a : desc.attributes)
        attributes.push_back({.location = a.location, .binding = 0, .format = a.format, .offset = a.offset});
    VkPipelineVertexInputStateCreateInfo vertexInput{.sType = VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO,
                                                     .vertexBindingDescriptionCount = desc.vertexStride ? 1u : 0u,
                                                     .pVertexBindingDescriptions = &binding,
                                                     .vertexAttributeDescriptionCount =
                                                         static_cast<uint32_t>(attributes.size()),
                                                     .pVertexAttributeDescriptions = attributes.data()};
    VkPipelineInputAssemblyStateCreateInfo inputAssembly{
        .sType = VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO, .topology = desc.topology};
    VkPipelineTessellationStateCreateInfo tessellation{.sType =
                                                           VK_STRUCTURE_TYPE_PIPELINE_TESSELLATION_STATE_CREATE_INFO,
                                                       .patchControlPoints = desc.patchControlPoints};
    VkPipelineViewportStateCreateInfo viewport{
        .sType = VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO, .viewportCount = 1, .scissorCount = 1};
    VkPipelineRasterizationStateCreateInfo raster{.sType = VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO,
                                                  .polygonMode = VK_POLYGON_MODE_FILL,
                                                  .cullMode = desc.cullMode,
                                                  .frontFace = VK_FRONT_FACE_COUNTER_CLOCKWISE,
                                                  .depthBiasEnable =
                                                      desc.depthBiasConstant != 0.0f || desc.depthBiasSlope != 0.0f,
                                                  .depthBiasConstantFactor = desc.depthBiasConstant,
                                                  .depthBiasSlopeFactor = desc.depthBiasSlope,
                                                  .lineWidth = 1.0f};
    VkPipelineMultisampleStateCreateInfo multisample{.sType = VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO,
                                                     .rasterizationSamples = desc.samples};
    VkPipelineDepthStencilStateCreateInfo depth{.sType = VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO,
                                                .depthTestEnable = desc.depthTest,
                                                .depthWriteEnable = desc.depthWrite,
                                                .depthCompareOp = desc.depthCompare};
    VkBlendFactor srcColor = desc.blend == Blend::Alpha ? VK_BLEND_FACTOR_SRC_ALPHA : VK_BLEND_FACTOR_ONE;
    VkBlendFactor dst = desc.blend == Blend::Additive ? VK_BLEND_FACTOR_ONE : VK_BLEND_FACTOR_ONE_MINUS_SRC_ALPHA;
    VkPipelineColorBlendAttachmentState blendAttachment{
        .blendEnable = desc.blend != Blend::None,
        .srcColorBlendFactor = srcColor,
        .dstColorBlendFactor = dst,
        .colorBlendOp = VK_BLEND_OP_ADD,
        .srcAlphaBlendFactor = VK_BLEND_FACTOR_ONE,
        .dstAlphaBlendFactor = dst,
        .alphaBlendOp = VK_BLEND_OP_ADD,
        .colorWriteMask = desc.colorWrite ? VkColorComponentFlags(VK_COLOR_COMPONENT_R_BIT | VK_COLOR_COMPONENT_G_BIT |
                                                                  VK_COLOR_COMPONENT_B_BIT | VK_COLOR_COMPONENT_A_BIT)
                                          : VkColorComponentFlags(0)};
    VkPipelineColorBlendStateCreateInfo blend{.sType = VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO,
                                              .attachmentCount = desc.colorFormat ? 1u : 0u,
                                              .pAttachments = &blendAttachment};
    std::array<VkDynamicState, 2> dynamicStates = {VK_DYNAMIC_STATE_VIEWPORT, VK_DYNAMIC_STATE_SCISSOR};
    VkPipelineDynamicStateCreateInfo dynamic{.sType = VK_STRUCTURE_TYPE_PIPELINE_DYNAMIC_STATE_CREATE_INFO,
                                             .dynamicStateCount = static_cast<uint32_t>(dynamicStates.size()),
                                             .pDynamicStates = dynamicStates.data()};
    VkPipelineRenderingCreateInfo rendering{.sType = VK_STRUCTURE_TYPE_PIPELINE_RENDERING_CREATE_INFO,
                                            .colorAttachmentCount = desc.colorFormat ? 1u : 0u,
                                            .pColorAttachmentFormats = &desc.colorFormat,
                                            .depthAttachmentFormat = desc.depthFormat};
    VkGraphicsPipelineCreateInfo info{.sType = VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO,
                                      .pNext = &rendering,
                                      .stageCount = static_cast<uint32_t>(stages.size()),
                                      .pStages = stages.data(),
                                      .pVertexInputState = &vertexInput,
                                      .pInputAssemblyState = &inputAssembly,
                                      .pTessellationState = desc.patchControlPoints ? &tessellation : nullptr,
                                      .pViewportState = &viewport,
                                      .pRasterizationState = &raster,
                                      .pMultisampleState = &multisample,
                                      .pDepthStencilState = &depth,
                                      .pColorBlendState = &blend,
                                      .pDynamicState = &dynamic,
                                      .layout = desc.layout};
    VkPipeline pipeline = VK_NULL_HANDLE;
    VK_CHECK(vkCreateGraphicsPipelines(ctx.device(), VK_NULL_HANDLE, 1, &info, nullptr, &pipeline));
    ctx.setName(pipeline, VK_OBJECT_TYPE_PIPELINE, desc.name);
    return Pipeline(ctx.device(), pipeline);
}

namespace {

// The driver's statistics of a pipeline's executables, one line each on stderr (WISP_SHADER_STATS).
void printShaderStats(const Context& ctx, VkPipeline pipeline, const char* name)
{
    auto properties = reinterpret_cast<PFN_vkGetPipelineExecutablePropertiesKHR>(
        vkGetDeviceProcAddr(ctx.device(), "vkGetPipelineExecutablePropertiesKHR"));
    auto statistics = reinterpret_cast<PFN_vkGetPipelineExecutableStatisticsKHR>(
        vkGetDeviceProcAddr(ctx.device(), "vkGetPipelineExecutableStatisticsKHR"));
    if (!properties || !statistics)
        return;
    VkPipelineInfoKHR info{.sType = VK_STRUCTURE_TYPE_PIPELINE_INFO_KHR, .pipeline = pipeline};
    uint32_t count = 0;
    VK_CHECK(properties(ctx.device(), &info, &count, nullptr));
    for (uint32_t e = 0; e < count; ++e) {
        VkPipelineExecutableInfoKHR executable{
            .sType = VK_STRUCTURE_TYPE_PIPELINE_EXECUTABLE_INFO_KHR, .pipeline = pipeline, .executableIndex = e};
        uint32_t n = 0;
        VK_CHECK(statistics(ctx.device(), &executable, &n, nullptr));
        std::vector<VkPipelineExecutableStatisticKHR> stats(
            n, {.sType = VK_STRUCTURE_TYPE_PIPELINE_EXECUTABLE_STATISTIC_KHR});
        VK_CHECK(statistics(ctx.device(), &executable, &n, stats.data()));
        std::string line = std::string("wisp: shader stats ") + name + ":";
        for (const VkPipelineExecutableStatisticKHR& st : stats) {
            line += " " + std::string(st.name) + "=";
            switch (st.format) {
            case VK_PIPELINE_EXECUTABLE_STATISTIC_FORMAT_BOOL32_KHR:
                line += st.value.b32 ? "true" : "false";
                break;
            case VK_PIPELINE_EXECUTABLE_STATISTIC_FORMAT_INT64_KHR:
                line += std::to_string(st.value.i64);
                break;
            case VK_PIPELINE_EXECUTABLE_STATISTIC_FORMAT_UINT64_KHR:
                line += std::to_string(st.value.u64);
                break;
            case VK_PIPELINE_EXECUTABLE_STATISTIC_FORMAT_FLOAT64_KHR:
                line += std::to_string(st.value.f64);
                break;
            default:
                line += "?";
            }
        }
        std::fprintf(stderr, "%s\n", line.c_str());
    }
}

} // namespace

Pipeline createComputePipeline(const Context& ctx, VkPipelineLayout layout, const std::string& shader, const char* name,
                               const std::vector<uint32_t>& constants)
{
    std::string file = shader + ".spv";
    ShaderModule module = loadShader(ctx, file);
    std::vector<VkSpecializationMapEntry> entries;
    for (uint32_t i = 0; i < constants.size(); ++i)
        entries.push_back({.constantID = i, .offset = i * 4, .size = 4});
    VkSpecializationInfo specialization{.mapEntryCount = uint32_t(entries.size()),
                                        .pMapEntries = entries.data(),
                                        .dataSize = constants.size() * 4,
                                        .pData = constants.data()};
    VkComputePipelineCreateInfo info{
        .sType = VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO,
        .flags = ctx.shaderStats() ? VkPipelineCreateFlags(VK_PIPELINE_CREATE_CAPTURE_STATISTICS_BIT_KHR) : 0u,
        .stage = {.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO,
                  .stage = stageOf(file),
                  .module = module,
                  .pName = "main",
                  .pSpecializationInfo = constants.empty() ? nullptr : &specialization},
        .layout = layout};
    VkPipeline pipeline = VK_NULL_HANDLE;
    VK_CHECK(vkCreateComputePipelines(ctx.device(), VK_NULL_HANDLE, 1, &info, nullptr, &pipeline));
    ctx.setName(pipeline, VK_OBJECT_TYPE_PIPELINE, name);
    if (ctx.shaderStats())
        printShaderStats(ctx, pipeline, name);
    return Pipeline(ctx.device(), pipeline);
}

ComputeKernel createComputeKernel(const Context& ctx, VkPipelineLayout layout, const std::string& shader,
                                  const char* name, const std::vector<uint32_t>& constants)
{
    return {.pipeline = createComputePipeline(ctx, layout, shader, name, constants),
            .bindings = shaderBindings(shader),
            .name = name};
}

Sampler createSampler(const Context& ctx, VkFilter filter, bool compare, const char* name)
{
    VkSamplerCreateInfo info{.sType = VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO,
                             .magFilter = filter,
                             .minFilter = filter,
                             .mipmapMode = VK_SAMPLER_MIPMAP_MODE_NEAREST,
                             .addressModeU = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE,
                             .addressModeV = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE,
                             .addressModeW = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE,
                             .compareEnable = compare ? VK_TRUE : VK_FALSE,
                             .compareOp = VK_COMPARE_OP_LESS_OR_EQUAL,
                             .maxLod = 0.0f,
                             .borderColor = VK_BORDER_COLOR_FLOAT_OPAQUE_WHITE};
    VkSampler sampler = VK_NULL_HANDLE;
    VK_CHECK(vkCreateSampler(ctx.device(), &info, nullptr, &sampler));
    ctx.setName(sampler, VK_OBJECT_TYPE_SAMPLER, name);
    return Sampler(ctx.device(), sampler);
}

void memoryBarrier(VkCommandBuffer cmd, VkPipelineStageFlags2 srcStage, VkAccessFlags2 srcAccess,
                   VkPipelineStageFlags2 dstStage, VkAccessFlags2 dstAccess)
{
    VkMemoryBarrier2 barrier{.sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER_2,
                             .srcStageMask = srcStage,
                             .srcAccessMask = srcAccess,
                             .dstStageMask = dstStage,
                             .dstAccessMask = dstAccess};
    VkDependencyInfo dep{
        .sType = VK_STRUCTURE_TYPE_DEPENDENCY_INFO, .memoryBarrierCount = 1, .pMemoryBarriers = &barrier};
    vkCmdPipelineBarrier2(cmd, &dep);
}

void computeToComputeBarrier(VkCommandBuffer cmd)
{
    memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                  VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                  VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
}

void transferToHostBarrier(VkCommandBuffer cmd)
{
    memoryBarrier(cmd, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                  VK_PIPELINE_STAGE_2_HOST_BIT, VK_ACCESS_2_HOST_READ_BIT);
}

uint32_t groupCount(uint32_t items, uint32_t groupSize)
{
    return (items + groupSize - 1) / groupSize;
}

} // namespace wisp::vk
