// app/session/reference_render.h: `wisp render --reference`: the path-traced reference of the frame `wisp
// render` draws (the same session, simulated frames, pose, camera, lights and look), through
// renderer/reference/.
#pragma once

#include "app/session/hair_session.h"
#include "gpu/context.h"
#include "renderer/reference/reference_tracer.h"
#include "renderer/settings.h"

#include <cstdint>
#include <functional>
#include <string>

namespace wisp {

struct ReferenceOptions {
    uint32_t samples = 64;    // per pixel
    uint32_t seed = 1;        // the same seed, the same picture
    uint32_t maxBounces = 64; // scattering events a path may have at most (roulette ends most before)
    uint32_t perPass = 2;     // samples per pixel a pass (a pass is one dispatch)
};

struct ReferenceRender {
    ReferencePicture picture;
    uint64_t segments = 0;  // strand segments traced
    uint64_t triangles = 0; // mesh triangles traced
    uint64_t nodes = 0;     // the hierarchy's nodes
    uint64_t rays = 0;      // rays cast (the paths' and the shadow rays)
    double traceSeconds = 0.0;
};

// What the reference traces for the frame renderPicture(ctx, session, settings, frames, fps) draws:
// the scene (its strands and meshes, the hierarchy) and the path tracer's block.
struct ReferenceFrame {
    reference::ReferenceScene scene;
    gpu::ReferenceParams params{};
};
ReferenceFrame prepareReference(const vk::Context& ctx, HairSession& session, RenderSettings settings, uint32_t frames,
                                float fps, const ReferenceOptions& options);

// Renders the reference of the frame renderPicture(ctx, session, settings, frames, fps) draws;
// `progress(done, total, seconds)` after each pass of samples, `seconds` since the tracing began (the
// time describeReference reports, the simulation and the scene's building before it not counted).
ReferenceRender renderReference(const vk::Context& ctx, HairSession& session, RenderSettings settings, uint32_t frames,
                                float fps, const ReferenceOptions& options,
                                const std::function<void(uint32_t, uint32_t, double)>& progress = {});

// "reference: 64 samples per pixel at WxH in 3.2 s (... samples/s, ... rays/s); ... segments, ...", noise
std::string describeReference(const ReferenceRender& r, const ReferenceOptions& options);

} // namespace wisp
