// app/session/simulate.cpp: runs fixed steps in batches (one submit each); the last step of each batch is
// submitted alone so the positions before and after it give the kinetic energy of the motion. When
// the head turns, batches end every 60 Hz frame's worth of steps and the tips' lag is sampled there;
// the side standoff (physics/groom_metrics.h) is measured at rest and on the final positions.
#include "app/session/simulate.h"

#include "core/error.h"
#include "gpu/frame.h"
#include "physics/gpu_solver.h"
#include "renderer/physics_pass.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdio>
#include <iostream>
#include <map>
#include <unistd.h>

namespace wisp {

namespace {

constexpr float kTipLagSampleHz = 60.0f;

// Whether the head's rotation changes over the next `steps` steps (a turn to measure the tips' lag
// against), checked at the end of every step.
bool headTurns(const HairSession& session, uint32_t steps)
{
    const StepClock& clock = session.clock();
    glm::mat3 start(session.headTransformAt(clock.seconds()));
    for (uint64_t k = clock.stepsDone(); k < clock.stepsDone() + steps; ++k) {
        glm::mat3 now(session.headTransformAt(clock.stepEnd(k)));
        for (int c = 0; c < 3; ++c)
            if (glm::length(now[c] - start[c]) > 1e-5f)
                return true;
    }
    return false;
}

} // namespace

SimulationReport simulateHeadless(const vk::Context& ctx, HairSession& session, uint32_t steps, uint32_t sampleEvery,
                                  const std::function<void(uint32_t)>& progress)
{
    GpuSolver& solver = *session.solver();
    PhysicsPass physics(solver);
    Frame frame(ctx, 1);
    const GroomedHead& scene = session.scene();
    float stepSeconds = session.clock().stepSeconds();

    SimulationReport report;
    double gpuMs = 0.0;
    uint32_t done = 0;
    gpu::SimStep last{};
    last.headTransform = session.headTransformAt(session.clock().seconds());

    // A head that turns during the run: the tips are sampled every 60 Hz frame's worth of steps.
    std::optional<TipLagMeter> lag;
    uint32_t lagEvery = session.clock().stepsPerFrame(kTipLagSampleHz);
    if (headTurns(session, steps)) {
        lag.emplace(scene.strands, session.headBounds().center());
        lag->sample(session.clock().seconds(), solver.readState().positions, last.headTransform);
    }
    auto submit = [&](uint32_t count) {
        std::vector<gpu::SimStep> list = session.nextSteps(count);
        last = list.back();
        physics.setSteps(std::move(list));
        FrameContext& fc = frame.begin({});
        std::vector<Pass*> passes = {&physics};
        frame.run(fc, passes);
        frame.submit(fc);
        frame.waitIdle();
        for (const vk::ScopeTime& t : frame.timings())
            gpuMs += t.milliseconds;
        done += count;
    };
    // `count` steps, in batches of at most lagEvery when the tips are sampled.
    auto advance = [&](uint32_t count) {
        while (count > 0) {
            uint32_t n = lag ? std::min(count, lagEvery) : count;
            submit(n);
            count -= n;
            if (lag && count > 0)
                lag->sample(session.clock().seconds(), solver.readState().positions, last.headTransform);
        }
    };
    while (done < steps) {
        uint32_t n = std::min(std::max(sampleEvery, 1u), steps - done);
        double msBefore = gpuMs;
        if (n > 1)
            advance(n - 1);
        std::vector<glm::vec4> before = solver.readState().positions;
        if (lag && n > 1)
            lag->sample(session.clock().seconds(), before, last.headTransform);
        submit(1);
        report.state = solver.readState();
        if (lag)
            lag->sample(session.clock().seconds(), report.state.positions, last.headTransform);
        report.last =
            measure(report.state, before, stepSeconds, scene.strands, session.setup(), last); // the step just run
        report.worst.maxStretch = std::max(report.worst.maxStretch, report.last.maxStretch);
        report.worst.maxPenetration = std::max(report.worst.maxPenetration, report.last.maxPenetration);
        report.worst.rootDrift = std::max(report.worst.rootDrift, report.last.rootDrift);
        report.worst.kineticEnergy = std::max(report.worst.kineticEnergy, report.last.kineticEnergy);
        report.energy.emplace_back(done, report.last.kineticEnergy);
        if (report.energy.size() == 1)
            report.memoryStart = sampleMemory();
        report.stepMs.emplace_back(done, (gpuMs - msBefore) / double(n));
        if (progress)
            progress(done);
    }
    report.memoryEnd = sampleMemory();
    report.gpuMsPerStep = gpuMs / double(std::max(steps, 1u));
    report.nonfiniteResets = report.state.nonfiniteResets;
    report.headTransform = last.headTransform;
    if (lag)
        report.tipLag = lag->result();
    return report;
}

SimulationReport simulateHeadless(const vk::Context& ctx, const GroomedHead& scene, const SimSettings& sim,
                                  uint32_t steps, const Motion& motion, uint32_t sampleEvery,
                                  const std::function<void(uint32_t)>& progress)
{
    HairSession session(ctx, scene, sim, stillTimeline(glm::vec4(0.0f), sim.wind));
    session.setPoses([&](double seconds) {
        float t = float(seconds);
        return StepPose{
            .head = motion.head(t), .sphere = motion.sphere(t), .wind = motion.wind ? motion.wind(t) : sim.wind};
    });
    // The solver starts from rest where the motion has the head at time 0.
    session.reset(motion.head(0.0f));
    return simulateHeadless(ctx, session, steps, sampleEvery, progress);
}

std::vector<DispatchTiming> profilePhysics(const vk::Context& ctx, HairSession& session, uint32_t warmupSteps,
                                           uint32_t timedSteps)
{
    GpuSolver& solver = *session.solver();
    vk::GpuTimer timer(ctx, 8, "profile.timestamps");
    std::map<std::string, std::vector<double>> samples;
    std::vector<std::string> order;
    std::vector<double> totals;
    for (uint32_t n = 0; n < warmupSteps + timedSteps; ++n) {
        gpu::SimStep step = session.nextSteps(1).front();
        ctx.submitAndWait([&](VkCommandBuffer cmd) {
            timer.reset(cmd);
            solver.recordStep(cmd, step, &timer);
        });
        if (n < warmupSteps)
            continue;
        double total = 0.0;
        for (const vk::ScopeTime& t : timer.read()) {
            if (!samples.count(t.name))
                order.push_back(t.name);
            samples[t.name].push_back(t.milliseconds);
            total += t.milliseconds;
        }
        totals.push_back(total);
    }
    // The same steps recorded 25 to a command buffer under one scope, as `simulate` runs them:
    // the batch's time divided by its steps, per batch.
    constexpr uint32_t kBatch = 25;
    std::vector<double> batched;
    for (uint32_t b = 0; b < std::max(1u, timedSteps / kBatch); ++b) {
        std::vector<gpu::SimStep> steps = session.nextSteps(kBatch);
        ctx.submitAndWait([&](VkCommandBuffer cmd) {
            timer.reset(cmd);
            timer.begin(cmd, "batch");
            for (const gpu::SimStep& step : steps)
                solver.recordStep(cmd, step);
            timer.end(cmd);
        });
        batched.push_back(timer.read().front().milliseconds / double(kBatch));
    }
    auto stats = [](const std::string& name, std::vector<double> v) {
        std::sort(v.begin(), v.end());
        return DispatchTiming{name, v[v.size() / 2], v[std::min(v.size() - 1, v.size() * 95 / 100)]};
    };
    std::vector<DispatchTiming> out;
    for (const std::string& name : order)
        out.push_back(stats(name, samples[name]));
    out.push_back(stats("step", totals));
    out.push_back(stats("step_in_batches_of_25", batched));
    return out;
}

namespace {

// The head mesh's field the solver reads: its grid and the GPU time its build took (null: none).
nlohmann::json meshSdfJson(HairSession& session)
{
    const GpuMeshSdf* sdf = session.solver() ? session.solver()->meshSdf() : nullptr;
    if (!sdf)
        return nullptr;
    const gpu::SdfGrid& g = sdf->grid();
    return {{"resolution", session.sim().sdfResolution},
            {"nodes", {g.dims.x, g.dims.y, g.dims.z}},
            {"cell", g.origin.w},
            {"band", g.band.x},
            {"build_ms", sdf->buildMs()}};
}

} // namespace

int runSimulate(const vk::Context& ctx, HairSession& session, const SimulateOptions& o)
{
    const GroomedHead& scene = session.scene();
    const SimSettings& sim = session.sim();
    if (o.profile) {
        std::vector<DispatchTiming> timings = profilePhysics(ctx, session, o.warmup, o.steps);
        nlohmann::json out = {{"strands", scene.strands.strandCount()},
                              {"vertices_per_strand", scene.strands.verticesPerStrand},
                              {"vertices", scene.strands.vertexCount()},
                              {"grid_resolution", sim.gridResolution},
                              {"grid_atomics", sim.gridAtomics == SimSettings::GridAtomics::Fixed ? "fixed" : "float"},
                              {"substeps", sim.substeps},
                              {"warmup_steps", o.warmup},
                              {"timed_steps", o.steps},
                              {"device", ctx.report().name},
                              {"mesh_sdf", meshSdfJson(session)},
                              {"settings", settingsJson(o.settings)}};
        for (const DispatchTiming& t : timings)
            out["ms"][t.name] = {{"median", t.medianMs}, {"p95", t.p95Ms}};
        if (o.json) {
            std::cout << out.dump() << "\n";
        } else {
            std::printf("%zu guides x %u vertices, grid %u^3, %u substeps on %s (%u warm-up, %u timed steps)\n",
                        scene.strands.strandCount(), scene.strands.verticesPerStrand, sim.gridResolution, sim.substeps,
                        ctx.report().name.c_str(), o.warmup, o.steps);
            for (const DispatchTiming& t : timings)
                std::printf("  %-15s median %8.4f ms   p95 %8.4f ms\n", t.name.c_str(), t.medianMs, t.p95Ms);
        }
        return ctx.validationMessages() > 0 ? kExitInternalError : 0;
    }
    // On a terminal one line rewritten in place; in a log (stderr not a terminal) a line of its own
    // every 10%, never lines run together by carriage returns.
    bool tty = isatty(STDERR_FILENO) != 0;
    uint32_t lastLogged = 0;
    SimulationReport r = simulateHeadless(ctx, session, o.steps, o.sampleEvery, [&](uint32_t done) {
        if (o.json)
            return;
        if (tty) {
            std::fprintf(stderr, "\rsimulate: %u / %u steps", done, o.steps);
        } else if (done == o.steps || done - lastLogged >= std::max(1u, o.steps / 10)) {
            std::fprintf(stderr, "simulate: %u / %u steps\n", done, o.steps);
            lastLogged = done;
        }
    });
    if (!o.json && tty)
        std::fprintf(stderr, "\n");

    const SimSetup& setup = session.setup();
    float diagonal = scene.head.mesh.bounds().diagonal();
    nlohmann::json energy = nlohmann::json::array();
    for (const auto& [step, value] : r.energy)
        energy.push_back({{"step", step}, {"value", value}});
    nlohmann::json stepMs = nlohmann::json::array();
    for (const auto& [step, value] : r.stepMs)
        stepMs.push_back({{"step", step}, {"ms", value}});
    nlohmann::json parts = nlohmann::json::array();
    for (const PartSettings& p : scene.strands.parts)
        parts.push_back({{"name", p.name},
                         {"global_stiffness", p.globalStiffness},
                         {"local_stiffness", p.localStiffness},
                         {"damping", p.ftlDamping},
                         {"drag", p.drag}});
    // The side standoff of the rest pose and of the final positions, both in head space.
    SideStandoff restStandoff = sideStandoff(scene.head.mesh, scene.strands, scene.unitsPerMetre);
    glm::mat4 toHead = glm::inverse(r.headTransform);
    std::vector<glm::vec3> finalPositions;
    finalPositions.reserve(r.state.positions.size());
    for (const glm::vec4& p : r.state.positions)
        finalPositions.push_back(glm::vec3(toHead * glm::vec4(glm::vec3(p), 1.0f)));
    SideStandoff finalStandoff =
        sideStandoff(scene.head.mesh, finalPositions, scene.strands.verticesPerStrand, scene.unitsPerMetre);
    // The hair against the mesh itself, beside the colliders' penetration.
    MeshSignedDistance headDistance(scene.head.mesh);
    InsideMesh restInside = insideMesh(headDistance, diagonal, scene.strands);
    InsideMesh finalInside = insideMesh(headDistance, diagonal, finalPositions, scene.strands.verticesPerStrand);
    nlohmann::json tipLag = nullptr;
    if (r.tipLag)
        tipLag = {{"peak", r.tipLag->peakDeg},
                  {"final", r.tipLag->finalDeg},
                  {"peak_at_s", r.tipLag->peakAtSeconds},
                  {"head_yaw_max", r.tipLag->largestHeadYawDeg},
                  {"tips", r.tipLag->tips},
                  {"samples", r.tipLag->samples}};

    nlohmann::json out = {{"steps", o.steps},
                          {"strands", scene.strands.strandCount()},
                          {"vertices", scene.strands.vertexCount()},
                          {"vertices_per_strand", scene.strands.verticesPerStrand},
                          {"parts", parts},
                          {"substeps", setup.substeps},
                          {"step_hz", sim.stepHz},
                          {"max_stretch", r.last.maxStretch},
                          {"max_penetration", r.last.maxPenetration / diagonal},
                          {"root_drift", r.last.rootDrift},
                          {"nonfinite_resets", r.nonfiniteResets},
                          {"side_standoff", {{"rest", restStandoff.value}, {"final", finalStandoff.value}}},
                          {"inside_mesh",
                           {{"rest", restInside.toJson()},
                            {"final", finalInside.toJson()},
                            {"depth", kInsideDepth},
                            {"skipped_root_vertices", kInsideSkippedVertices},
                            {"reference", "head diagonal"}}},
                          {"tip_lag_deg", tipLag},
                          {"worst",
                           {{"max_stretch", r.worst.maxStretch},
                            {"max_penetration", r.worst.maxPenetration / diagonal},
                            {"root_drift", r.worst.rootDrift},
                            {"kinetic_energy", r.worst.kineticEnergy}}},
                          {"memory",
                           {{"host_rss_bytes", {r.memoryStart.hostResidentBytes, r.memoryEnd.hostResidentBytes}},
                            {"device_allocations", {r.memoryStart.device.allocations, r.memoryEnd.device.allocations}},
                            {"device_bytes", {r.memoryStart.device.bytes, r.memoryEnd.device.bytes}}}},
                          {"kinetic_energy", energy},
                          {"gpu_ms_per_step", r.gpuMsPerStep},
                          {"gpu_ms_per_step_over_time", stepMs},
                          {"grid_resolution", sim.gridResolution},
                          {"colliders", scene.colliders.size()},
                          {"colliders_fitted", scene.collidersFitted},
                          {"mesh_sdf", meshSdfJson(session)},
                          {"loaded_hair", loadedHairJson(scene)},
                          {"rigid_strands", rigidStrandsJson(scene)},
                          {"device", ctx.report().name},
                          {"settings", settingsJson(o.settings)}};
    if (o.json) {
        std::cout << out.dump() << "\n";
    } else {
        std::printf("%zu guides x %u vertices in %zu part(s), %u steps at %g Hz x %u substeps on %s\n",
                    scene.strands.strandCount(), scene.strands.verticesPerStrand, scene.strands.parts.size(), o.steps,
                    double(sim.stepHz), setup.substeps, ctx.report().name.c_str());
        std::printf(
            "  max stretch       %.3g\n  max penetration   %.3g of the head's diagonal\n  root drift        %.3g\n"
            "  non-finite resets %u\n  kinetic energy    %.4g (last)\n  GPU time per step %.4f ms\n",
            double(r.last.maxStretch), double(r.last.maxPenetration / diagonal), double(r.last.rootDrift),
            r.nonfiniteResets, double(r.last.kineticEnergy), r.gpuMsPerStep);
        std::printf("  side standoff     %.3f at rest, %.3f at the end (hair beyond the head seen from the side, "
                    "of its width)\n",
                    restStandoff.value, finalStandoff.value);
        std::printf("  inside the mesh   %s at the end (%s at rest)\n", finalInside.describe().c_str(),
                    restInside.describe().c_str());
        if (r.tipLag)
            std::printf("  tip lag           %.2f degrees at most (at %.2f s), %.2f at the end, behind a head turning "
                        "up to %.1f degrees\n",
                        r.tipLag->peakDeg, r.tipLag->peakAtSeconds, r.tipLag->finalDeg, r.tipLag->largestHeadYawDeg);
        for (const std::string& line : describeLoadedHair(scene))
            std::printf("  %s\n", line.c_str());
        std::printf(
            "  worst over %zu samples: stretch %.3g, penetration %.3g, root drift %.3g\n  memory            %s\n",
            r.energy.size(), double(r.worst.maxStretch), double(r.worst.maxPenetration / diagonal),
            double(r.worst.rootDrift), describeMemory(r.memoryStart, r.memoryEnd).c_str());
    }
    if (ctx.validationMessages() > 0) {
        std::fprintf(stderr, "wisp: %u Vulkan validation messages (printed above)\n", ctx.validationMessages());
        return kExitInternalError;
    }
    return 0;
}

} // namespace wisp
