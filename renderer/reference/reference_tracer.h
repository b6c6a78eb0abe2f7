// renderer/reference/reference_tracer.h: the path-traced reference on the GPU: the scene's
// hierarchy, segments and triangles uploaded once, then passes of reference_trace.comp (a few
// samples per pixel each, so no dispatch runs long enough to trip a watchdog) accumulating every
// pixel's even and odd samples apart, and the sums read back. Also the sums resolved into the
// picture, tone-mapped over the backdrop as the real-time frame is, with the noise left.
#pragma once

#include "gpu/compute_stage.h"
#include "gpu/frame.h"
#include "gpu/pipeline.h"
#include "gpu/resources.h"
#include "renderer/reference/reference_scene.h"

#include <functional>
#include <memory>
#include <vector>

namespace wisp {

namespace vk {
class Context;
}

class ReferenceTracer {
public:
    ReferenceTracer(const vk::Context& ctx, const reference::ReferenceScene& scene, const gpu::ReferenceParams& params);

    // Samples [0, samples) of every pixel, `perPass` a pass; `progress(done, samples)` after each.
    void render(uint32_t samples, uint32_t perPass, const std::function<void(uint32_t, uint32_t)>& progress = {});
    // The sums: width x height vec4 of the even samples (radiance, backdrop count), then of the odd.
    // Also reads back the rays cast, raysCast().
    std::vector<glm::vec4> sums();
    // Every ray the samples so far cast (each walk of the hierarchy), as of the last sums().
    uint64_t raysCast() const { return raysCast_; }

private:
    ComputeStage stage(int which);

    const vk::Context& ctx_;
    gpu::ReferenceParams params_;
    gpu::ReferencePush push_{};
    vk::Buffer paramsBuffer_, nodes_, prims_, segments_, triangles_, sums_, readback_, rays_, raysReadback_;
    TrackedBuffer sumsTrack_, raysTrack_;
    uint64_t raysCast_ = 0;
    StageLayout layout_;
    vk::ComputeKernel kernel_;
    std::vector<std::unique_ptr<ComputeStagePass>> passes_; // clear, trace, read back
    Frame frame_;
};

// The reference's picture: each pixel's mean radiance over the samples that met the scene,
// exposed and tone-mapped as the real-time frame (toneMapAces), laid over the backdrop
// (frameBackground) by the share of samples that met nothing, sRGB-encoded.
struct ReferencePicture {
    uint32_t width = 0;
    uint32_t height = 0;
    std::vector<uint8_t> rgba;
    // The same in linear radiance before exposure and tone mapping, RGBA floats, top row first: RGB
    // the mean over all the pixel's samples (those that met nothing bring 0: premultiplied), A the
    // share of samples that met the scene (coverage). `wisp render --reference --out F.exr`.
    std::vector<float> linear;
    // The noise left: the RMS over pixels and channels, in 8-bit levels, of half the difference of
    // the even and odd samples' pictures (each the mean of half the samples: their difference has
    // twice the variance of either, four times the whole mean's). -1 with fewer than 2 samples.
    double noiseLevels = -1.0;
};
ReferencePicture resolveReference(const std::vector<glm::vec4>& sums, const gpu::FrameParams& frame, uint32_t samples);

} // namespace wisp
