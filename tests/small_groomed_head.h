// tests/small_groomed_head.h: the small groomed head the rendering suites share: grown guides on the
// default head, a 200 x 150 picture with a 512² shadow map and light strands, rendered offscreen.
#pragma once

#include "app/session/headless.h"
#include "assets/head.h"
#include "gpu/frame.h"
#include "physics/gpu_solver.h"
#include "physics/groomed_head.h"
#include "renderer/renderer.h"
#include "renderer/settings.h"

namespace wisp::test {

inline GroomedHead smallGroomedHead(uint32_t guides)
{
    GrowthSettings g;
    g.guides = guides;
    return buildGrownHead(defaultHeadPath(), g);
}

inline RenderSettings smallRenderSettings()
{
    RenderSettings s;
    s.width = 200;
    s.height = 150;
    s.shadows.mapSize = 512;
    s.strands.strandsPerGuide = 8;
    s.strands.divisions = 12;
    return s;
}

// The scene's head and hair as the default camera frames them (the hair unsimulated).
inline Picture renderHair(const vk::Context& ctx, const GroomedHead& scene, const RenderSettings& s)
{
    HairSession session(ctx, scene, SimSettings{}, stillTimeline(glm::vec4(0.0f), glm::vec3(0.0f), s.light));
    return renderPicture(ctx, session, s);
}

// A renderer with the scene's head and its hair attached (unsimulated: the solver holds the rest
// pose), for the tests that run its passes themselves: its frame (one in flight) and the camera
// that frames the scene at the settings' aspect.
struct HairRenderer {
    HairRenderer(const vk::Context& ctx, const GroomedHead& scene, const RenderSettings& s)
        : renderer(ctx, s, 1),
          solver(ctx, scene.strands,
                 makeSimSetup(SimSettings{}, scene.strands, scene.gpuColliders, scene.unitsPerMetre), glm::mat4(1.0f)),
          frame(ctx, 1)
    {
        renderer.setHead(scene.head);
        renderer.attachHair(solver, scene.strands, scene.unitsPerMetre);
        camera = OrbitCamera::framing(renderer.sceneBounds(), float(s.width) / float(s.height));
    }
    Renderer renderer;
    GpuSolver solver;
    Frame frame; // (destroyed first: it waits for the device)
    OrbitCamera camera;
};

} // namespace wisp::test
