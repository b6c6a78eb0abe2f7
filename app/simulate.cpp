// app/simulate.cpp: runs fixed steps in batches (one submit each), samples the kinetic energy
// after every batch, and reports the final quality metrics.
#include "app/simulate.h"

#include "physics/gpu_solver.h"
#include "physics/hair_scene.h"
#include "renderer/frame.h"
#include "renderer/physics_pass.h"

#include <nlohmann/json.hpp>

#include <cstdio>
#include <iostream>

namespace wisp {

int runSimulate(const SimulateOptions& o)
{
    HairScene scene = buildGrownScene(o.headFile, o.growth);
    SimSetup setup = makeSimSetup(o.sim, scene.strands, scene.gpuColliders, scene.unitsPerMetre);
    vk::Context ctx(o.context);
    glm::mat4 head(1.0f);
    GpuSolver solver(ctx, scene.strands, setup, head);
    PhysicsPass physics(solver);
    Frame frame(ctx, 1);
    glm::vec4 sphere = o.sphere.value_or(glm::vec4(0.0f));

    // Steps go in batches of one submit each; the last step of a batch is submitted alone, so the
    // positions before and after it give the kinetic energy of the motion.
    constexpr uint32_t kBatch = 25;
    float stepSeconds = 1.0f / o.sim.stepHz;
    nlohmann::json energy = nlohmann::json::array();
    double gpuMs = 0.0;
    uint32_t done = 0;
    auto submit = [&](uint32_t count) {
        std::vector<gpu::SimStep> steps;
        for (uint32_t k = 0; k < count; ++k)
            steps.push_back(makeStep(setup, head, sphere, float(done + k) * stepSeconds));
        physics.setSteps(std::move(steps));
        FrameContext& fc = frame.begin({});
        std::vector<Pass*> passes = {&physics};
        frame.run(fc, passes);
        frame.submit(fc);
        frame.waitIdle();
        for (const vk::ScopeTime& t : frame.timings())
            gpuMs += t.milliseconds;
        done += count;
    };
    SimState state;
    SimMetrics m;
    while (done < o.steps) {
        uint32_t n = std::min(kBatch, o.steps - done);
        if (n > 1)
            submit(n - 1);
        std::vector<glm::vec4> before = solver.readState().positions;
        submit(1);
        state = solver.readState();
        m = measure(state, before, stepSeconds, scene.strands, setup, makeStep(setup, head, sphere, float(done) * stepSeconds));
        energy.push_back({{"step", done}, {"value", m.kineticEnergy}});
        if (!o.json)
            std::fprintf(stderr, "\rsimulate: %u / %u steps", done, o.steps);
    }
    if (!o.json)
        std::fprintf(stderr, "\n");

    float diagonal = scene.head.mesh.bounds().diagonal();
    nlohmann::json out = {{"steps", o.steps},
                          {"strands", scene.strands.strandCount()},
                          {"vertices", scene.strands.vertexCount()},
                          {"vertices_per_strand", scene.strands.verticesPerStrand},
                          {"substeps", setup.substeps},
                          {"step_hz", o.sim.stepHz},
                          {"max_stretch", m.maxStretch},
                          {"max_penetration", m.maxPenetration / diagonal},
                          {"root_drift", m.rootDrift},
                          {"nonfinite_resets", state.nonfiniteResets},
                          {"kinetic_energy", energy},
                          {"gpu_ms_per_step", gpuMs / double(o.steps)},
                          {"colliders", scene.colliders.size()},
                          {"colliders_fitted", scene.collidersFitted},
                          {"device", ctx.report().name}};
    if (o.json) {
        std::cout << out.dump() << "\n";
    } else {
        std::printf("%zu guides x %u vertices, %u steps at %g Hz x %u substeps on %s\n", scene.strands.strandCount(),
                    scene.strands.verticesPerStrand, o.steps, double(o.sim.stepHz), setup.substeps, ctx.report().name.c_str());
        std::printf("  max stretch       %.3g\n  max penetration   %.3g of the head's diagonal\n  root drift        %.3g\n"
                    "  non-finite resets %u\n  kinetic energy    %.4g (last)\n  GPU time per step %.4f ms\n",
                    double(m.maxStretch), double(m.maxPenetration / diagonal), double(m.rootDrift), state.nonfiniteResets,
                    double(m.kineticEnergy), gpuMs / double(o.steps));
    }
    if (ctx.validationMessages() > 0) {
        std::fprintf(stderr, "wisp: %u Vulkan validation messages (printed above)\n", ctx.validationMessages());
        return 1;
    }
    return 0;
}

}  // namespace wisp
