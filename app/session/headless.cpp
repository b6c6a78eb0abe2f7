// app/session/headless.cpp: offscreen frames: the simulated frames run the physics pass alone (one submit
// per batch), then one full frame renders and reads back the picture; profiles time whole frames.
#include "app/session/headless.h"

#include "core/host_memory.h"
#include "gpu/timestamps.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <memory>

namespace wisp {

MemorySample sampleMemory()
{
    return {hostResidentBytes(), vk::deviceMemoryStats()};
}

std::string describeMemory(const MemorySample& start, const MemorySample& end)
{
    auto mib = [](uint64_t bytes) { return double(bytes) / (1024.0 * 1024.0); };
    char text[200];
    std::snprintf(text, sizeof(text), "host RSS %.1f -> %.1f MiB, device %llu -> %llu allocations (%.1f -> %.1f MiB)",
                  mib(start.hostResidentBytes), mib(end.hostResidentBytes),
                  static_cast<unsigned long long>(start.device.allocations),
                  static_cast<unsigned long long>(end.device.allocations), mib(start.device.bytes),
                  mib(end.device.bytes));
    return text;
}

Picture renderFrame(const vk::Context& ctx, Renderer& renderer, Frame& frame, const OrbitCamera& camera)
{
    // A frame that overflowed the automatic OIT pool is drawn again with the pool grown (the
    // physics has no steps left by then, so it draws the same moment); each try at least half
    // as large again, within the device's limits.
    for (int attempt = 0;; ++attempt) {
        ReadbackPass readback(ctx, renderer.target());
        std::vector<TrackedImage*> transient = renderer.transientImages();
        FrameContext& fc = frame.begin(transient);
        renderer.prepare(fc, camera, 0.0f);
        std::vector<Pass*> passes = renderer.passes();
        passes.push_back(&readback);
        frame.run(fc, passes);
        frame.submit(fc);
        frame.waitIdle();
        OitStats oit = renderer.oitStats(fc.slot);
        if (oit.overflow > 0 && attempt < 8 && renderer.growOit(oit))
            continue;
        VkExtent2D e = renderer.target().extent();
        return {e.width, e.height, readback.pixels(), "", oit, renderer.rasterStats(fc.slot)};
    }
}

OrbitCamera poseFrame(Renderer& renderer, const SceneTimeline& timeline, double seconds, const OrbitCamera& framing)
{
    SceneState s = timeline.at(seconds);
    renderer.setHeadTransform(headYawTransform(renderer.sceneBounds(), s.headYawDeg));
    renderer.setSphere(s.sphere);
    renderer.settings().light = s.light;
    return poseCamera(framing, s.camera);
}

void runSteps(Frame& frame, Renderer& renderer, HairSession& session, uint32_t steps)
{
    constexpr uint32_t kBatch = 32;
    for (uint32_t done = 0; done < steps;) {
        uint32_t n = std::min(kBatch, steps - done);
        renderer.setSteps(session.nextSteps(n));
        FrameContext& fc = frame.begin({});
        std::vector<Pass*> passes = {renderer.physics()};
        frame.run(fc, passes);
        frame.submit(fc);
        frame.waitIdle();
        done += n;
    }
    renderer.setSteps({});
}

PosedFrame::PosedFrame(const vk::Context& ctx, HairSession& session, const RenderSettings& settings, uint32_t frames,
                       float fps)
    : renderer(ctx, settings, 1), frame(ctx, 1)
{
    renderer.setHead(session.scene().head);
    session.attachTo(renderer);
    if (session.hasHair())
        runSteps(frame, renderer, session, frames * session.clock().stepsPerFrame(fps));
    float aspect = static_cast<float>(settings.width) / static_cast<float>(settings.height);
    camera = poseFrame(renderer, session.timeline(), session.clock().seconds(),
                       OrbitCamera::framing(renderer.sceneBounds(), aspect));
}

std::string describeHairCounts(const Renderer& renderer)
{
    StrandCounts c = renderer.hairCounts();
    return "hair: " + std::to_string(c.guides) + " guides x " + std::to_string(c.strandsPerGuide) + " strands x " +
           std::to_string(c.divisions) + " divisions = " + std::to_string(c.segments()) + " segments, " +
           renderer.describeHairDraw();
}

Picture renderPicture(const vk::Context& ctx, HairSession& session, const RenderSettings& settings, uint32_t frames,
                      float fps)
{
    PosedFrame posed(ctx, session, settings, frames, fps);
    Picture picture = renderFrame(ctx, posed.renderer, posed.frame, posed.camera);
    // The compute path's bins grow after a frame that outgrew them: that frame is drawn again.
    for (int again = 0; again < 2 && picture.raster.overflow > 0; ++again)
        picture = renderFrame(ctx, posed.renderer, posed.frame, posed.camera);
    if (session.hasHair())
        picture.hairCounts = describeHairCounts(posed.renderer);
    return picture;
}

Picture renderPicture(const vk::Context& ctx, const Head& head, const RenderSettings& settings)
{
    GroomedHead bald;
    bald.head = head;
    HairSession session(ctx, std::move(bald), SimSettings{},
                        stillTimeline(glm::vec4(0.0f), glm::vec3(0.0f), settings.light));
    return renderPicture(ctx, session, settings);
}

std::vector<PassTiming> profileFrames(const vk::Context& ctx, HairSession& session, const RenderSettings& settings,
                                      float fps, uint32_t warmup, uint32_t frames, OitStats* oit, RasterStats* raster,
                                      bool timedSteps)
{
    // The scene's first pose (its camera, head and light), held: what is timed is the drawing.
    PosedFrame posed(ctx, session, settings);
    Renderer& renderer = posed.renderer;
    Frame& frame = posed.frame;
    const OrbitCamera& camera = posed.camera;
    uint32_t stepsPerFrame = session.clock().stepsPerFrame(fps);
    std::map<std::string, std::vector<double>> samples;
    std::vector<std::string> order;
    std::vector<double> totals;
    // The clock is fixed, so each frame records the next frame's steps beside its own drawing
    // (Renderer::setStepsAhead): every frame draws the moment it would with its steps first. The
    // first frame takes its own.
    auto stepsOf = [&](uint32_t n) {
        bool steps = n < warmup + frames && (timedSteps || n < warmup);
        return steps ? session.nextSteps(stepsPerFrame) : std::vector<gpu::SimStep>{};
    };
    for (uint32_t n = 0; n < warmup + frames; ++n) {
        renderer.setSteps(n == 0 ? stepsOf(0) : std::vector<gpu::SimStep>{});
        float now = session.clock().stepStart(session.clock().stepsDone());
        renderer.setStepsAhead(stepsOf(n + 1));
        std::vector<TrackedImage*> transient = renderer.transientImages();
        FrameContext& fc = frame.begin(transient);
        renderer.prepare(fc, camera, now);
        std::vector<Pass*> passes = renderer.passes();
        frame.run(fc, passes);
        frame.submit(fc);
        frame.waitIdle();
        OitStats lists = renderer.oitStats(fc.slot);
        if (lists.overflow > 0 && renderer.growOit(lists)) {
            if (n >= warmup)
                --n; // the pool grew: this frame is not timed, one more is
            continue;
        }
        if (oit)
            *oit = lists;
        if (raster)
            *raster = renderer.rasterStats(fc.slot);
        if (n < warmup)
            continue;
        double total = 0.0;
        for (const vk::ScopeTime& t : vk::timingsByName(frame.timings())) {
            if (!samples.count(t.name))
                order.push_back(t.name);
            samples[t.name].push_back(t.milliseconds);
            total += t.milliseconds;
        }
        totals.push_back(total);
    }
    auto stats = [](const std::string& name, std::vector<double> v) {
        std::sort(v.begin(), v.end());
        return PassTiming{name, v[v.size() / 2], v[std::min(v.size() - 1, v.size() * 95 / 100)]};
    };
    std::vector<PassTiming> out;
    for (const std::string& name : order)
        out.push_back(stats(name, samples[name]));
    out.push_back(stats("frame", totals));
    return out;
}

} // namespace wisp
