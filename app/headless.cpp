// app/headless.cpp: one offscreen frame: begin, prepare, scene passes, readback, submit, wait.
#include "app/headless.h"

#include "renderer/frame.h"
#include "renderer/renderer.h"

namespace wisp {

Picture renderPicture(const vk::Context& ctx, const Head& head, const RenderSettings& settings)
{
    Renderer renderer(ctx, settings, 1);
    renderer.setHead(head);
    Frame frame(ctx, 1);
    ReadbackPass readback(ctx, renderer.target());

    float aspect = static_cast<float>(settings.width) / static_cast<float>(settings.height);
    OrbitCamera camera = OrbitCamera::framing(renderer.sceneBounds(), aspect);

    std::vector<TrackedImage*> transient = renderer.transientImages();
    FrameContext& fc = frame.begin(transient);
    renderer.prepare(fc, camera, 0.0f);
    std::vector<Pass*> passes = renderer.passes();
    passes.push_back(&readback);
    frame.run(fc, passes);
    frame.submit(fc);
    frame.waitIdle();
    return {settings.width, settings.height, readback.pixels()};
}

}  // namespace wisp
