// app/headless.h: the headless front end: renders frames into the offscreen target and reads
// them back. Used by `wisp render` (and later `record` and `sweep`), and by the rendering tests.
#pragma once

#include "app/scene.h"
#include "physics/hair_scene.h"
#include "physics/simulation.h"
#include "renderer/camera.h"
#include "renderer/oit.h"
#include "renderer/strand_raster.h"
#include "renderer/settings.h"
#include "gpu/context.h"

#include <cstdint>
#include <string>
#include <vector>

namespace wisp {

class Renderer;
class Frame;

struct Picture {
    uint32_t width = 0;
    uint32_t height = 0;
    std::vector<uint8_t> rgba;  // tightly packed, top row first, sRGB
    std::string hairCounts;     // what the hair draw was split into (empty without hair)
    OitStats oit;               // the OIT lists of this frame (zeros in MSAA mode or without hair)
    RasterStats raster;         // the compute path's counts (zeros when the hair is drawn by graphics)
};

// Hair to simulate and draw with the head.
struct HairRun {
    const HairScene* scene = nullptr;
    SimSettings sim;
    uint32_t frames = 0;               // simulated frames before the picture
    float framesPerSecond = 30.0f;     // simulated time per frame = 1 / fps
    glm::vec4 sphere{0.0f};            // the user's sphere (xyz, radius; 0 = none)
};

// Host and device memory at one moment: long runs report it at their start and end (a soak's
// memory must stay flat).
struct MemorySample {
    uint64_t hostResidentBytes = 0;
    vk::DeviceMemoryStats device;  // Wisp's live device allocations
};
MemorySample sampleMemory();
// "host RSS 41.2 -> 41.3 MiB, device 23 -> 23 allocations (12.0 -> 12.0 MiB)"
std::string describeMemory(const MemorySample& start, const MemorySample& end);

// One full frame of `renderer` (all its passes) seen by `camera`, read back.
Picture renderFrame(const vk::Context& ctx, Renderer& renderer, Frame& frame, const OrbitCamera& camera);

// The fixed steps [first, first + count) of a run at `stepHz`, posed by `timeline`: step k runs
// from k / stepHz to (k + 1) / stepHz and takes the head turn, sphere and wind the timeline has
// at its end (so the frame drawn after it shows one moment). `head`: the head mesh's bounds.
struct TimedSteps {
    std::vector<gpu::SimStep> steps;
    std::vector<glm::vec3> winds;  // head units / s², one per step
};
TimedSteps timedSteps(const SceneTimeline& timeline, const SimSetup& setup, const Bounds& head, float unitsPerMetre,
                      float stepHz, uint64_t first, uint32_t count);
// Poses `renderer` as `timeline` has it at `seconds` (head turn, sphere, light) and returns the
// camera there (`framing` moved by the timeline's camera).
OrbitCamera poseFrame(Renderer& renderer, const SceneTimeline& timeline, double seconds, const OrbitCamera& framing);

// Renders one frame of `head` (with `hair` when given) as the default camera frames it, or as
// `timeline` poses it (camera, light, head turn, sphere and wind over the simulated frames; the
// picture shows the moment after them, time 0 without hair). Without a timeline the hair's
// sphere and wind hold still. Deterministic for a device.
Picture renderPicture(const vk::Context& ctx, const Head& head, const RenderSettings& settings,
                      const HairRun* hair = nullptr, const SceneTimeline* timeline = nullptr);

// Per-pass GPU time of whole frames (physics stepping one frame's worth each frame, as the window
// does): `warmup` frames, then `frames` timed; medians and p95 in milliseconds, per pass and for
// the frame (the passes' sum).
struct PassTiming {
    std::string name;
    double medianMs = 0.0;
    double p95Ms = 0.0;
};
// `oit` and `raster`, when given, receive the last frame's OIT and compute-path counts.
std::vector<PassTiming> profileFrames(const vk::Context& ctx, const Head& head, const RenderSettings& settings,
                                      const HairRun& hair, uint32_t warmup, uint32_t frames, OitStats* oit = nullptr,
                                      RasterStats* raster = nullptr);

}  // namespace wisp
