// renderer/reference/reference_tracer.cpp: the path tracer's passes and the resolve (see the header).
#include "renderer/reference/reference_tracer.h"

#include "gpu/context.h"
#include "shaders/shared/lighting.h"
#include "shaders/shared/mesh_raster.h"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace wisp {

namespace {

enum Stage { kClear = 0, kTrace = 1, kReadback = 2 };
const char* const kStageNames[] = {"reference.clear", "reference.trace", "reference.readback"};

// A storage buffer holding `data` (at least one element's worth: Vulkan has no empty buffers).
template <typename T> vk::Buffer constantStorage(const vk::Context& ctx, const std::vector<T>& data, const char* name)
{
    std::vector<T> padded = data.empty() ? std::vector<T>(1) : data;
    return ctx.createBufferWithData({.size = padded.size() * sizeof(T), .usage = vk::kStorage, .name = name},
                                    padded.data(), padded.size() * sizeof(T));
}

} // namespace

ReferenceTracer::ReferenceTracer(const vk::Context& ctx, const reference::ReferenceScene& scene,
                                 const gpu::ReferenceParams& params)
    : ctx_(ctx), params_(params), frame_(ctx, 1)
{
    paramsBuffer_ = ctx.createBuffer({.size = sizeof(gpu::ReferenceParams),
                                      .usage = vk::kUniform,
                                      .memory = vk::Memory::Upload,
                                      .name = "reference.params"});
    std::memcpy(paramsBuffer_.mapped(), &params_, sizeof(params_));
    nodes_ = constantStorage(ctx, scene.bvh.nodes, "reference.nodes");
    prims_ = constantStorage(ctx, scene.bvh.prims, "reference.prims");
    segments_ = constantStorage(ctx, scene.segments, "reference.segments");
    triangles_ = constantStorage(ctx, scene.triangles, "reference.triangles");
    VkDeviceSize bytes = VkDeviceSize(2) * params.width * params.height * sizeof(glm::vec4);
    sums_ = ctx.createBuffer(
        {.size = bytes, .usage = vk::kStorage | vk::kTransferSrc | vk::kTransferDst, .name = "reference.sums"});
    readback_ = ctx.createBuffer(
        {.size = bytes, .usage = vk::kTransferDst, .memory = vk::Memory::Readback, .name = "reference.readback"});
    sumsTrack_.buffer = sums_;
    VkDeviceSize rayBytes = VkDeviceSize(params.width) * params.height * sizeof(uint32_t);
    rays_ = ctx.createBuffer(
        {.size = rayBytes, .usage = vk::kStorage | vk::kTransferSrc | vk::kTransferDst, .name = "reference.rays"});
    raysReadback_ = ctx.createBuffer({.size = rayBytes,
                                      .usage = vk::kTransferDst,
                                      .memory = vk::Memory::Readback,
                                      .name = "reference.rays.readback"});
    raysTrack_.buffer = rays_;

    std::vector<ComputeStage> stages;
    for (int s = kClear; s <= kReadback; ++s)
        stages.push_back(stage(s));
    layout_ = StageLayout(ctx, stages, sizeof(gpu::ReferencePush), "reference.layout");
    kernel_ = vk::createComputeKernel(ctx, layout_.layout(), "reference_trace.comp", "reference.trace.pipeline");
    for (int s = kClear; s <= kReadback; ++s)
        passes_.push_back(std::make_unique<ComputeStagePass>(kStageNames[s], layout_, [this, s] { return stage(s); }));
}

ComputeStage ReferenceTracer::stage(int which)
{
    switch (which) {
    case kClear:
        return {.uses = {commandUse(sumsTrack_, Access::TransferDst), commandUse(raysTrack_, Access::TransferDst)},
                .record = [this](StageCommands& c) {
                    c.fill(sumsTrack_, 0u);
                    c.fill(raysTrack_, 0u);
                }};
    case kTrace:
        return {.uses = {uniformBlock(gpu::kReferenceBindingParams, paramsBuffer_.get()),
                         constantBuffer(gpu::kReferenceBindingNodes, nodes_),
                         constantBuffer(gpu::kReferenceBindingPrims, prims_),
                         constantBuffer(gpu::kReferenceBindingSegments, segments_),
                         constantBuffer(gpu::kReferenceBindingTriangles, triangles_),
                         storageBuffer(gpu::kReferenceBindingSums, sumsTrack_, Access::ComputeWrite),
                         storageBuffer(gpu::kReferenceBindingRays, raysTrack_, Access::ComputeWrite)},
                .record = [this](StageCommands& c) {
                    c.dispatch(kernel_, push_, vk::groupCount(params_.width, gpu::kReferenceGroupSize),
                               vk::groupCount(params_.height, gpu::kReferenceGroupSize));
                }};
    default:
        return {.uses = {commandUse(sumsTrack_, Access::TransferSrc), commandUse(raysTrack_, Access::TransferSrc)},
                .record = [this](StageCommands& c) {
                    c.copyToHost(sumsTrack_, readback_, readback_.size());
                    c.copyToHost(raysTrack_, raysReadback_, raysReadback_.size());
                }};
    }
}

void ReferenceTracer::render(uint32_t samples, uint32_t perPass,
                             const std::function<void(uint32_t, uint32_t)>& progress)
{
    auto runPass = [this](int which) {
        FrameContext& fc = frame_.begin({});
        Pass* pass = passes_[size_t(which)].get();
        frame_.run(fc, std::span(&pass, 1));
        frame_.submit(fc);
        frame_.waitIdle();
    };
    runPass(kClear);
    perPass = std::max(perPass, 1u);
    for (uint32_t done = 0; done < samples;) {
        push_.firstSample = done;
        push_.samples = std::min(perPass, samples - done);
        runPass(kTrace);
        done += push_.samples;
        if (progress)
            progress(done, samples);
    }
}

std::vector<glm::vec4> ReferenceTracer::sums()
{
    FrameContext& fc = frame_.begin({});
    Pass* pass = passes_[kReadback].get();
    frame_.run(fc, std::span(&pass, 1));
    frame_.submit(fc);
    frame_.waitIdle();
    std::vector<glm::vec4> out(size_t(2) * params_.width * params_.height);
    std::memcpy(out.data(), readback_.mapped(), out.size() * sizeof(glm::vec4));
    std::vector<uint32_t> rays(size_t(params_.width) * params_.height);
    std::memcpy(rays.data(), raysReadback_.mapped(), rays.size() * sizeof(uint32_t));
    raysCast_ = 0;
    for (uint32_t r : rays)
        raysCast_ += r;
    return out;
}

namespace {

// The display colour (linear, before the sRGB encoding) of `samples` samples summing to `sum`.
glm::vec3 displayColor(glm::vec4 sum, float samples, const gpu::FrameParams& frame, float y)
{
    float hits = samples - sum.w;
    glm::vec3 color = hits > 0.0f ? gpu::toneMapAces(glm::vec3(sum) / hits * frame.exposure) : glm::vec3(0.0f);
    return glm::mix(color, gpu::frameBackground(frame, y), sum.w / samples);
}

} // namespace

ReferencePicture resolveReference(const std::vector<glm::vec4>& sums, const gpu::FrameParams& frame, uint32_t samples)
{
    ReferencePicture out;
    out.width = uint32_t(frame.viewportWidth);
    out.height = uint32_t(frame.viewportHeight);
    size_t pixels = size_t(out.width) * out.height;
    out.rgba.resize(pixels * 4);
    out.linear.resize(pixels * 4);
    float even = float((samples + 1) / 2), odd = float(samples / 2);
    double squares = 0.0;
    for (size_t i = 0; i < pixels; ++i) {
        float y = float(i / out.width) + 0.5f;
        glm::vec3 c = displayColor(sums[i] + sums[pixels + i], float(samples), frame, y);
        for (int k = 0; k < 3; ++k)
            out.rgba[i * 4 + size_t(k)] = uint8_t(std::lround(255.0f * gpu::encodeSrgb(c[k])));
        out.rgba[i * 4 + 3] = 255;
        glm::vec4 all = sums[i] + sums[pixels + i];
        for (int k = 0; k < 3; ++k)
            out.linear[i * 4 + size_t(k)] = all[k] / float(samples);
        out.linear[i * 4 + 3] = 1.0f - all.w / float(samples);
        if (odd > 0.0f) {
            glm::vec3 a = displayColor(sums[i], even, frame, y), b = displayColor(sums[pixels + i], odd, frame, y);
            for (int k = 0; k < 3; ++k) {
                double d = 0.5 * 255.0 * double(gpu::encodeSrgb(a[k]) - gpu::encodeSrgb(b[k]));
                squares += d * d;
            }
        }
    }
    if (odd > 0.0f && pixels > 0)
        out.noiseLevels = std::sqrt(squares / double(pixels * 3));
    return out;
}

} // namespace wisp
