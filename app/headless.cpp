// app/headless.cpp: offscreen frames: the simulated frames run the physics pass alone (one submit
// per batch), then one full frame renders and reads back the picture.
#include "app/headless.h"

#include "core/host_memory.h"
#include "physics/gpu_solver.h"
#include "gpu/frame.h"
#include "renderer/renderer.h"

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
                  static_cast<unsigned long long>(end.device.allocations), mib(start.device.bytes), mib(end.device.bytes));
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

TimedSteps timedSteps(const SceneTimeline& timeline, const SimSetup& setup, const Bounds& head, float unitsPerMetre,
                      float stepHz, uint64_t first, uint32_t count)
{
    TimedSteps out;
    float stepSeconds = 1.0f / stepHz;
    for (uint64_t k = first; k < first + count; ++k) {
        SceneState s = timeline.at(double(k + 1) / double(stepHz));
        out.steps.push_back(makeStep(setup, headYawTransform(head, s.headYawDeg), s.sphere, float(k) * stepSeconds));
        out.winds.push_back(s.wind * unitsPerMetre);
    }
    return out;
}

OrbitCamera poseFrame(Renderer& renderer, const SceneTimeline& timeline, double seconds, const OrbitCamera& framing)
{
    SceneState s = timeline.at(seconds);
    renderer.setHeadTransform(headYawTransform(renderer.sceneBounds(), s.headYawDeg));
    renderer.setSphere(s.sphere);
    renderer.settings().light = s.light;
    return poseCamera(framing, s.camera);
}

Picture renderPicture(const vk::Context& ctx, const Head& head, const RenderSettings& settings, const HairRun* hair,
                      const SceneTimeline* timeline)
{
    Renderer renderer(ctx, settings, 1);
    renderer.setHead(head);
    Frame frame(ctx, 1);
    SceneState still;
    still.light = settings.light;
    if (hair) {
        still.sphere = hair->sphere;
        still.wind = hair->sim.wind;
    }
    SceneTimeline held({}, SceneInterpolation::Linear, still);
    const SceneTimeline& poses = timeline ? *timeline : held;
    const Bounds headBounds = renderer.sceneBounds();

    std::unique_ptr<GpuSolver> solver;
    double seconds = 0.0;
    if (hair) {
        SceneState start = poses.at(0.0);
        SimSettings sim = hair->sim;
        sim.wind = start.wind;
        SimSetup setup = makeSimSetup(sim, hair->scene->strands, hair->scene->gpuColliders, hair->scene->unitsPerMetre);
        solver = std::make_unique<GpuSolver>(ctx, hair->scene->strands, setup, headYawTransform(headBounds, start.headYawDeg));
        renderer.attachHair(*solver, hair->scene->strands, hair->scene->unitsPerMetre);
        // Fixed steps only: each frame advances exactly round(stepHz / fps) steps of 1 / stepHz.
        uint32_t stepsPerFrame = std::max(1u, uint32_t(std::lround(hair->sim.stepHz / hair->framesPerSecond)));
        uint32_t totalSteps = hair->frames * stepsPerFrame;
        constexpr uint32_t kBatch = 32;
        for (uint32_t done = 0; done < totalSteps;) {
            uint32_t n = std::min(kBatch, totalSteps - done);
            TimedSteps steps = timedSteps(poses, setup, headBounds, hair->scene->unitsPerMetre, hair->sim.stepHz, done, n);
            renderer.setSteps(std::move(steps.steps), std::move(steps.winds));
            FrameContext& fc = frame.begin({});
            std::vector<Pass*> passes = {renderer.physics()};
            frame.run(fc, passes);
            frame.submit(fc);
            frame.waitIdle();
            done += n;
        }
        renderer.setSteps({});
        seconds = double(totalSteps) / double(hair->sim.stepHz);
    }

    float aspect = static_cast<float>(settings.width) / static_cast<float>(settings.height);
    OrbitCamera camera = poseFrame(renderer, poses, seconds, OrbitCamera::framing(headBounds, aspect));

    Picture picture = renderFrame(ctx, renderer, frame, camera);
    // The compute path's bins grow after a frame that outgrew them: that frame is drawn again.
    for (int again = 0; again < 2 && picture.raster.overflow > 0; ++again)
        picture = renderFrame(ctx, renderer, frame, camera);
    if (hair) {
        HairDrawCounts c = renderer.hairCounts();
        picture.hairCounts = "hair: " + std::to_string(c.guides) + " guides x " + std::to_string(c.strandsPerGuide) +
                             " strands x " + std::to_string(c.divisions) + " divisions = " +
                             std::to_string(c.segments()) + " segments, ";
        if (renderer.hairRaster() == HairRaster::Compute)
            picture.hairCounts += "drawn in compute (hair_raster=compute)";
        else
            picture.hairCounts += "drawn as " + std::to_string(uint64_t(c.guides) * c.lengthChunks * c.strandChunks) +
                                  " patches of up to " + std::to_string(c.strandsPerPatch) + " strands x " +
                                  std::to_string((c.divisions + c.lengthChunks - 1) / c.lengthChunks) +
                                  " divisions (" + std::to_string(c.strandChunks) + " instances, " +
                                  std::to_string(c.draws()) + " draws)";
    }
    return picture;
}

std::vector<PassTiming> profileFrames(const vk::Context& ctx, const Head& head, const RenderSettings& settings,
                                      const HairRun& hair, uint32_t warmup, uint32_t frames, OitStats* oit,
                                      RasterStats* raster)
{
    Renderer renderer(ctx, settings, 1);
    renderer.setHead(head);
    Frame frame(ctx, 1);
    SimSetup setup = makeSimSetup(hair.sim, hair.scene->strands, hair.scene->gpuColliders, hair.scene->unitsPerMetre);
    GpuSolver solver(ctx, hair.scene->strands, setup, glm::mat4(1.0f));
    renderer.attachHair(solver, hair.scene->strands, hair.scene->unitsPerMetre);
    uint32_t stepsPerFrame = std::max(1u, uint32_t(std::lround(hair.sim.stepHz / hair.framesPerSecond)));
    float stepSeconds = 1.0f / hair.sim.stepHz;
    OrbitCamera camera = OrbitCamera::framing(renderer.sceneBounds(), float(settings.width) / float(settings.height));
    std::map<std::string, std::vector<double>> samples;
    std::vector<std::string> order;
    std::vector<double> totals;
    uint64_t step = 0;
    for (uint32_t n = 0; n < warmup + frames; ++n) {
        std::vector<gpu::SimStep> steps;
        for (uint32_t k = 0; k < stepsPerFrame; ++k, ++step)
            steps.push_back(makeStep(setup, glm::mat4(1.0f), hair.sphere, float(step) * stepSeconds));
        renderer.setSteps(std::move(steps));
        std::vector<TrackedImage*> transient = renderer.transientImages();
        FrameContext& fc = frame.begin(transient);
        renderer.prepare(fc, camera, float(step) * stepSeconds);
        std::vector<Pass*> passes = renderer.passes();
        frame.run(fc, passes);
        frame.submit(fc);
        frame.waitIdle();
        OitStats lists = renderer.oitStats(fc.slot);
        if (lists.overflow > 0 && renderer.growOit(lists)) {
            if (n >= warmup)
                --n;  // the pool grew: this frame is not timed, one more is
            continue;
        }
        if (oit)
            *oit = lists;
        if (raster)
            *raster = renderer.rasterStats(fc.slot);
        if (n < warmup)
            continue;
        double total = 0.0;
        for (const vk::ScopeTime& t : frame.timings()) {
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

}  // namespace wisp
