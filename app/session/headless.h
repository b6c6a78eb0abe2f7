// app/session/headless.h: the headless front end: renders a hair session's frames into the offscreen
// target and reads them back, or times them pass by pass. Used by `wisp render`, `record` and
// `sweep`, and by the rendering tests.
#pragma once

#include "app/scene/scene_timeline.h"
#include "app/session/hair_session.h"
#include "gpu/context.h"
#include "gpu/frame.h"
#include "physics/groomed_head.h"
#include "physics/simulation.h"
#include "renderer/camera.h"
#include "renderer/compute/strand_raster.h"
#include "renderer/oit_stats.h"
#include "renderer/renderer.h"
#include "renderer/settings.h"

#include <cstdint>
#include <string>
#include <vector>

namespace wisp {

struct Picture {
    uint32_t width = 0;
    uint32_t height = 0;
    std::vector<uint8_t> rgba; // tightly packed, top row first, sRGB
    std::string hairCounts;    // what the hair draw was split into (empty without hair)
    OitStats oit;              // the OIT lists of this frame (zeros in MSAA mode or without hair)
    RasterStats raster;        // the compute path's counts (zeros when the hair is drawn by graphics)
};

// Host and device memory at one moment: long runs report it at their start and end (a soak's
// memory must stay flat).
struct MemorySample {
    uint64_t hostResidentBytes = 0;
    vk::DeviceMemoryStats device; // Wisp's live device allocations
};
MemorySample sampleMemory();
// "host RSS 41.2 -> 41.3 MiB, device 23 -> 23 allocations (12.0 -> 12.0 MiB)"
std::string describeMemory(const MemorySample& start, const MemorySample& end);

// One full frame of `renderer` (all its passes) seen by `camera`, read back.
Picture renderFrame(const vk::Context& ctx, Renderer& renderer, Frame& frame, const OrbitCamera& camera);

// Poses `renderer` as `timeline` has it at `seconds` (head turn, sphere, light) and returns the
// camera there (`framing` moved by the timeline's camera).
OrbitCamera poseFrame(Renderer& renderer, const SceneTimeline& timeline, double seconds, const OrbitCamera& framing);

// Runs `session`'s next `steps` fixed steps alone (the physics pass of `renderer`, 32 steps a
// submission), drawing nothing.
void runSteps(Frame& frame, Renderer& renderer, HairSession& session, uint32_t steps);

// Where every offscreen picture of a session starts: a renderer of `settings` drawing `session`'s
// head and hair, its frame, `frames` simulated frames of `fps` run (each exactly round(step_hz /
// fps) fixed steps, the physics pass alone), the renderer posed by the session's timeline at that
// moment (head turn, sphere, light) and the camera there (the default framing of the settings'
// aspect, moved by the timeline's camera). renderPicture, profileFrames and the reference
// (app/session/reference_render.h) each start from one.
struct PosedFrame {
    PosedFrame(const vk::Context& ctx, HairSession& session, const RenderSettings& settings, uint32_t frames = 0,
               float fps = 30.0f);
    Renderer renderer;
    Frame frame;
    OrbitCamera camera;
};

// Renders one frame of `session`'s head and hair after `frames` simulated frames of `fps` (each
// exactly round(step_hz / fps) fixed steps), posed by its timeline (camera, light, head turn,
// sphere and wind; the picture shows the moment after them). Deterministic for a device.
Picture renderPicture(const vk::Context& ctx, HairSession& session, const RenderSettings& settings, uint32_t frames = 0,
                      float fps = 30.0f);
// The head alone, as the default camera frames it, lit by the settings' light.
Picture renderPicture(const vk::Context& ctx, const Head& head, const RenderSettings& settings);
// The hair `renderer` draws, as `wisp render` prints it (its counts, and how it is drawn).
std::string describeHairCounts(const Renderer& renderer);

// Per-pass GPU time of whole frames (physics stepping one frame's worth each frame, as the window
// does): `warmup` frames, then `frames` timed; medians and p95 in milliseconds, per pass and for
// the frame (the passes' sum).
struct PassTiming {
    std::string name;
    double medianMs = 0.0;
    double p95Ms = 0.0;
};
// `oit` and `raster`, when given, receive the last frame's OIT and compute-path counts.
// `timedSteps` false: the timed frames take no steps (the hair holds where the warm-up left it),
// so the difference from a profile with them is what the physics costs a frame.
std::vector<PassTiming> profileFrames(const vk::Context& ctx, HairSession& session, const RenderSettings& settings,
                                      float fps, uint32_t warmup, uint32_t frames, OitStats* oit = nullptr,
                                      RasterStats* raster = nullptr, bool timedSteps = true);

} // namespace wisp
