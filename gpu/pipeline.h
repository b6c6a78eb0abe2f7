// gpu/pipeline.h: shader modules loaded from the build tree's SPIR-V, pipeline layouts
// with one push-descriptor set, and graphics pipelines for dynamic rendering described by a
// struct of named fields.
#pragma once

#include "gpu/handle.h"

#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace wisp::vk {

class Context;

// Where compiled shaders live: <executable dir>/shaders, else the build tree's (compiled in).
std::filesystem::path shaderDirectory();
ShaderModule loadShader(const Context& ctx, const std::string& fileName);

struct DescriptorBinding {
    uint32_t binding = 0;
    VkDescriptorType type = VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
    VkShaderStageFlags stages = VK_SHADER_STAGE_ALL_GRAPHICS;
};

struct PipelineLayoutDesc {
    std::vector<DescriptorBinding> bindings; // set 0, a push-descriptor set
    uint32_t pushConstantBytes = 0;
    VkShaderStageFlags pushConstantStages = VK_SHADER_STAGE_ALL_GRAPHICS;
    const char* name = "unnamed layout";
};

struct PipelineLayoutBundle {
    DescriptorSetLayout setLayout;
    PipelineLayout layout;
};
PipelineLayoutBundle createPipelineLayout(const Context& ctx, const PipelineLayoutDesc& desc);

struct VertexAttribute {
    uint32_t location = 0;
    VkFormat format = VK_FORMAT_R32G32B32_SFLOAT;
    uint32_t offset = 0;
};

enum class Blend {
    None,          // the fragment replaces the attachment
    Alpha,         // src * a + dst * (1 - a)
    Premultiplied, // src + dst * (1 - a): colours already multiplied by their alpha
    Additive,      // src + dst (accumulation, e.g. deep opacity layers)
};

struct GraphicsPipelineDesc {
    VkPipelineLayout layout = VK_NULL_HANDLE;
    std::vector<std::string> shaders; // file names in shaderDirectory(), stage from the extension
    uint32_t vertexStride = 0;
    std::vector<VertexAttribute> attributes;
    VkPrimitiveTopology topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
    uint32_t patchControlPoints = 0;
    VkCullModeFlags cullMode = VK_CULL_MODE_BACK_BIT;
    bool depthTest = true;
    bool depthWrite = true;
    VkCompareOp depthCompare = VK_COMPARE_OP_LESS_OR_EQUAL;
    // Slope-scaled depth bias (shadow maps): constant in depth units of the format, slope per texel.
    float depthBiasConstant = 0.0f;
    float depthBiasSlope = 0.0f;
    Blend blend = Blend::None;
    bool colorWrite = true; // false: the attachment is bound but never written (fragments only store)
    VkFormat colorFormat = VK_FORMAT_UNDEFINED;
    VkFormat depthFormat = VK_FORMAT_UNDEFINED;
    VkSampleCountFlagBits samples = VK_SAMPLE_COUNT_1_BIT;
    const char* name = "unnamed pipeline";
};
Pipeline createGraphicsPipeline(const Context& ctx, const GraphicsPipelineDesc& desc);
// `constants[i]` is the shader's specialization constant i, 32 bits each (a bool is 0 or 1).
Pipeline createComputePipeline(const Context& ctx, VkPipelineLayout layout, const std::string& shader, const char* name,
                               const std::vector<uint32_t>& constants = {});

// The set-0 bindings a shader's entry point uses, from its SPIR-V (1.4 or later, whose entry point
// lists every global it uses: code a specialization constant turns off included), sorted.
std::vector<uint32_t> spirvBindings(std::span<const uint32_t> words);
std::vector<uint32_t> shaderBindings(const std::string& shader); // the compiled shader's, by name
// A compute pipeline and the bindings its shader uses: a compute stage (gpu/compute_stage.h) that
// dispatches it must list every one of them.
struct ComputeKernel {
    Pipeline pipeline;
    std::vector<uint32_t> bindings;
    const char* name = "";
    VkPipeline get() const { return pipeline; }
    explicit operator bool() const { return bool(pipeline); }
};
ComputeKernel createComputeKernel(const Context& ctx, VkPipelineLayout layout, const std::string& shader,
                                  const char* name, const std::vector<uint32_t>& constants = {});

// A clamp-to-edge sampler without mipmaps: `filter` for magnification and minification, and
// with `compare` a depth comparison (LESS_OR_EQUAL: shadow maps).
Sampler createSampler(const Context& ctx, VkFilter filter, bool compare, const char* name);

// A global memory dependency (no image layouts, no particular buffer).
void memoryBarrier(VkCommandBuffer cmd, VkPipelineStageFlags2 srcStage, VkAccessFlags2 srcAccess,
                   VkPipelineStageFlags2 dstStage, VkAccessFlags2 dstAccess);
// A compute -> compute dependency on all shader storage (between dispatches of one pass).
void computeToComputeBarrier(VkCommandBuffer cmd);
// Copies (transfer writes) made visible to the host once the submission's fence signals.
void transferToHostBarrier(VkCommandBuffer cmd);
uint32_t groupCount(uint32_t items, uint32_t groupSize); // ceil(items / groupSize)

// One descriptor of a push-descriptor set (Context::pushDescriptorSet): a buffer, or an image (and
// its sampler, for combined image samplers). `info` must outlive the push.
inline VkWriteDescriptorSet bufferWrite(uint32_t binding, VkDescriptorType type, const VkDescriptorBufferInfo* info)
{
    return {.sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET,
            .dstBinding = binding,
            .descriptorCount = 1,
            .descriptorType = type,
            .pBufferInfo = info};
}
inline VkWriteDescriptorSet imageWrite(uint32_t binding, VkDescriptorType type, const VkDescriptorImageInfo* info)
{
    return {.sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET,
            .dstBinding = binding,
            .descriptorCount = 1,
            .descriptorType = type,
            .pImageInfo = info};
}

} // namespace wisp::vk
