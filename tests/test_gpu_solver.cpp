// tests/test_gpu_solver.cpp: the simulation on the GPU: the kernels against the CPU reference on
// awkward sizes, the grid's sums, and resets of non-finite strands. (The shared math, the CPU
// reference by hand and root sampling are CPU tests: test_sim_cpu.cpp.)
#include "core/error.h"
#include "gpu/frame.h"
#include "physics/colliders.h"
#include "physics/cpu_solver.h"
#include "physics/gpu_solver.h"
#include "physics/groomed_head.h"
#include "physics_trials.h"
#include "renderer/physics_pass.h"
#include "test_support.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <functional>
#include <glm/gtc/matrix_transform.hpp>
#include <limits>
#include <memory>
#include <string>
#include <utility>

using namespace wisp;

// ---- Scenes for the solver tests -------------------------------------------------------------

namespace {

// A ball "head" of radius 0.1 m at the origin with strands on its upper half, all in code.
struct BallScene {
    StrandSet strands;
    std::vector<gpu::Ellipsoid> colliders;
    SimSetup setup;
};

// `hanging`: strands hang straight down from their roots (near equilibrium) instead of growing outward.
BallScene ballScene(uint32_t strandCount, uint32_t V, const SimSettings& settings, float colliderRadius = 0.1f,
                    bool hanging = false)
{
    BallScene b;
    Ellipsoid ball{
        .name = "ball", .center = glm::vec3(0), .radii = glm::vec3(colliderRadius), .rotationDeg = glm::vec3(0)};
    b.colliders.push_back(toGpu(ball));
    b.strands.verticesPerStrand = V;
    b.strands.parts.push_back(PartSettings{});
    for (uint32_t s = 0; s < strandCount; ++s) {
        // Roots spread over the upper hemisphere (golden-angle spiral); strands grow outward.
        float t = (float(s) + 0.5f) / float(strandCount);
        float y = 0.2f + 0.8f * t, r = std::sqrt(1.0f - y * y), phi = 2.39996323f * float(s);
        glm::vec3 n(r * std::cos(phi), y, r * std::sin(phi));
        std::vector<glm::vec3> points(V);
        for (uint32_t i = 0; i < V; ++i)
            points[i] = hanging ? 0.1f * n - glm::vec3(0.0f, 0.15f * float(i) / float(V - 1), 0.0f)
                                : n * (0.1f + 0.15f * float(i) / float(V - 1));
        b.strands.add(points, 0, 1, false);
    }
    b.setup = makeSimSetup(settings, b.strands, b.colliders, 1.0f);
    return b;
}

// Runs `steps` steps on the GPU, `batch` per submit; returns the final state.
SimState runGpu(const vk::Context& ctx, GpuSolver& solver, const SimSetup& setup, uint32_t steps,
                const std::function<gpu::SimStep(uint32_t)>& stepAt, uint32_t batch = 50)
{
    PhysicsPass pass(solver);
    Frame frame(ctx, 1);
    for (uint32_t done = 0; done < steps;) {
        uint32_t n = std::min(batch, steps - done);
        std::vector<gpu::SimStep> list;
        for (uint32_t k = 0; k < n; ++k)
            list.push_back(stepAt(done + k));
        pass.setSteps(std::move(list));
        FrameContext& fc = frame.begin({});
        std::vector<Pass*> passes = {&pass};
        frame.run(fc, passes);
        frame.submit(fc);
        frame.waitIdle();
        done += n;
    }
    (void)setup;
    return solver.readState();
}

} // namespace

// ---- GPU against the CPU reference -------------------------------------------------------------

struct GpuCpuCase {
    uint32_t strands;
    uint32_t vertices;
};

class GpuMatchesCpu : public testing::TestWithParam<GpuCpuCase> {};

namespace {

struct Agreement {
    float max = 0.0f;
    float p90 = 0.0f; // 90% of vertices agree at least this well
};

Agreement agreement(const SimState& a, const SimState& b)
{
    std::vector<float> d;
    for (size_t i = 0; i < a.positions.size(); ++i)
        d.push_back(glm::length(glm::vec3(a.positions[i]) - glm::vec3(b.positions[i])));
    std::sort(d.begin(), d.end());
    return {d.back(), d[d.size() * 9 / 10]};
}

} // namespace

// One step with every term (gravity, wind, drag, shape, head motion, the sphere and the head
// colliders in contact, the grid) agrees to float rounding. Over many steps a chain of 32 or 64
// links swinging far from equilibrium is chaotic: rounding differences grow about tenfold every
// five steps (measured: 1e-8 after 1 step, 5e-5 after 10, millimetres after 40 at the worst
// vertex), whatever the implementation. So the long comparison runs hanging strands near
// equilibrium, nudged by wind, the grid and the turning head, with no contacts, where it must stay
// at rounding level.
TEST_P(GpuMatchesCpu, OneStepWithContactsAndFortyStepsWithout)
{
    GpuCpuCase c = GetParam();
    SimSettings s;
    s.wind = glm::vec3(4.0f, 0.0f, 1.0f);
    s.gridFriction = 0.1f;
    s.gridResolution = 16;
    vk::Context ctx(test::validatedOptions());
    for (bool contacts : {true, false}) {
        // Without contacts the collider sits well inside the roots and there is no sphere.
        BallScene b = ballScene(c.strands, c.vertices, s, contacts ? 0.1f : 0.03f, !contacts);
        uint32_t steps = contacts ? 1 : 40;
        auto stepAt = [&](uint32_t n) {
            float t = float(n) / s.stepHz;
            glm::mat4 head = glm::rotate(glm::mat4(1.0f), 0.3f * std::sin(2.0f * t), glm::vec3(0, 1, 0));
            glm::vec4 sphere = contacts ? glm::vec4(0.25f - 0.5f * t, 0.15f, 0.0f, 0.06f) : glm::vec4(0.0f);
            return makeStep(b.setup, head, sphere, t);
        };
        CpuSolver cpu(b.strands, b.setup, glm::mat4(1.0f));
        for (uint32_t n = 0; n < steps; ++n)
            cpu.step(stepAt(n));
        GpuSolver gpuSolver(ctx, b.strands, b.setup, glm::mat4(1.0f));
        SimState gpu = runGpu(ctx, gpuSolver, b.setup, steps, stepAt, 7);
        ASSERT_EQ(gpu.positions.size(), cpu.state().positions.size());
        Agreement a = agreement(gpu, cpu.state());
        std::fprintf(stderr, "%s: max %g p90 %g\n", contacts ? "contacts, 1 step" : "no contacts, 40 steps",
                     double(a.max), double(a.p90));
        EXPECT_LT(a.max, contacts ? 1e-6f : 2e-6f);
        for (size_t i = 0; i < gpu.velocities.size(); ++i)
            ASSERT_LT(glm::length(glm::vec3(gpu.velocities[i]) - glm::vec3(cpu.state().velocities[i])), 1e-3f) << i;
        EXPECT_EQ(gpu.nonfiniteResets, 0u);
        EXPECT_EQ(cpu.state().nonfiniteResets, 0u);
    }
    EXPECT_EQ(ctx.validationMessages(), 0u);
}

INSTANTIATE_TEST_SUITE_P(AwkwardSizes, GpuMatchesCpu,
                         testing::Values(GpuCpuCase{1, 16}, GpuCpuCase{65, 4}, GpuCpuCase{63, 16}, GpuCpuCase{130, 32},
                                         GpuCpuCase{7, 64}),
                         [](const testing::TestParamInfo<GpuCpuCase>& param) {
                             return std::to_string(param.param.strands) + "x" + std::to_string(param.param.vertices);
                         });

// The head mesh's field in the penalty: strands grown out of a sphere mesh that the field alone
// keeps them off (its ellipsoid sits deep inside), a wide margin so that many vertices are in
// contact, the head turning: one step agrees with the CPU reference to rounding (each solver reads
// the field its own build made: the kernels', and their CPU twin's), ten to the divergence of long
// chains the comparisons above describe (measured: 3e-8 after one step, at most 1.8e-4 after ten
// at 7 x 64, nine vertices in ten within 1.3e-6).
TEST_P(GpuMatchesCpu, MeshFieldInContact)
{
    GpuCpuCase c = GetParam();
    SimSettings s;
    s.collisionMarginMetres = 0.02f;
    s.sdfResolution = 41;
    s.gridResolution = 16;
    vk::Context ctx(test::validatedOptions());
    BallScene b = ballScene(c.strands, c.vertices, s, 0.03f);
    Mesh sphere = makeSphereMesh(13, 29);
    for (glm::vec3& p : sphere.positions)
        p *= 0.1f;
    b.setup = makeSimSetup(s, b.strands, b.colliders, 1.0f, sphere);
    for (uint32_t steps : {1u, 10u}) {
        auto stepAt = [&](uint32_t n) {
            float t = float(n) / s.stepHz;
            glm::mat4 head = glm::rotate(glm::mat4(1.0f), 0.3f * std::sin(2.0f * t), glm::vec3(0, 1, 0));
            return makeStep(b.setup, head, glm::vec4(0.0f), t);
        };
        CpuSolver cpu(b.strands, b.setup, glm::mat4(1.0f));
        for (uint32_t n = 0; n < steps; ++n)
            cpu.step(stepAt(n));
        GpuSolver gpuSolver(ctx, b.strands, b.setup, glm::mat4(1.0f));
        ASSERT_NE(gpuSolver.meshSdf(), nullptr);
        SimState gpu = runGpu(ctx, gpuSolver, b.setup, steps, stepAt, 3);
        Agreement a = agreement(gpu, cpu.state());
        std::fprintf(stderr, "mesh field, %u steps: max %g p90 %g\n", steps, double(a.max), double(a.p90));
        EXPECT_LT(a.max, steps == 1 ? 1e-6f : 1e-3f);
        EXPECT_LT(a.p90, steps == 1 ? 1e-6f : 1e-5f);
        // The field acted: without it the same steps end elsewhere (strands of 4 vertices barely
        // bend in ten steps, and never reach past their rest pose's depth).
        if (steps == 10 && c.vertices >= 16) {
            SimSettings off = s;
            off.sdfResolution = 0;
            SimSetup bare = makeSimSetup(off, b.strands, b.colliders, 1.0f, sphere);
            CpuSolver without(b.strands, bare, glm::mat4(1.0f));
            for (uint32_t n = 0; n < steps; ++n)
                without.step(makeStep(
                    bare, glm::rotate(glm::mat4(1.0f), 0.3f * std::sin(2.0f * float(n) / s.stepHz), glm::vec3(0, 1, 0)),
                    glm::vec4(0.0f), float(n) / s.stepHz));
            EXPECT_GT(agreement(without.state(), cpu.state()).max, 1e-4f);
        }
    }
    EXPECT_EQ(ctx.validationMessages(), 0u);
}

// Strands pinned at both ends (the bend at the middle vertex, sim.h) on the GPU against
// the CPU: loops from a root to a tip on the ball, wind and a turning head, at the awkward sizes:
// one step agrees to rounding, and after 30 both keep every segment's length.
TEST_P(GpuMatchesCpu, StrandsPinnedAtBothEnds)
{
    GpuCpuCase c = GetParam();
    SimSettings s;
    s.wind = glm::vec3(4.0f, 0.0f, 1.0f);
    s.gridFriction = 0.1f;
    s.gridResolution = 16;
    BallScene b;
    b.colliders.push_back(
        toGpu(Ellipsoid{.name = "ball", .center = glm::vec3(0), .radii = glm::vec3(0.03f), .rotationDeg = {}}));
    b.strands.verticesPerStrand = c.vertices;
    b.strands.parts.push_back(PartSettings{});
    for (uint32_t k = 0; k < c.strands; ++k) {
        float phi = 2.39996323f * float(k);
        glm::vec3 root(0.1f * std::cos(phi), 0.05f, 0.1f * std::sin(phi));
        glm::vec3 tip(0.1f * std::cos(phi + 0.8f), 0.05f, 0.1f * std::sin(phi + 0.8f));
        std::vector<glm::vec3> points;
        for (uint32_t i = 0; i < c.vertices; ++i) {
            float u = float(i) / float(c.vertices - 1);
            points.push_back(glm::mix(root, tip, u) - glm::vec3(0.0f, 0.2f * u * (1.0f - u), 0.0f));
        }
        b.strands.add(points, 0, c.vertices > 4 && k % 3 == 0 ? 2u : 1u, true);
    }
    b.setup = makeSimSetup(s, b.strands, b.colliders, 1.0f);
    auto stepAt = [&](uint32_t n) {
        float t = float(n) / s.stepHz;
        return makeStep(b.setup, glm::rotate(glm::mat4(1.0f), 0.3f * std::sin(2.0f * t), glm::vec3(0, 1, 0)),
                        glm::vec4(0.0f), t);
    };
    vk::Context ctx(test::validatedOptions());
    { // one step agrees to rounding
        CpuSolver cpu(b.strands, b.setup, glm::mat4(1.0f));
        cpu.step(stepAt(0));
        GpuSolver gpuSolver(ctx, b.strands, b.setup, glm::mat4(1.0f));
        EXPECT_LT(agreement(runGpu(ctx, gpuSolver, b.setup, 1, stepAt), cpu.state()).max, 1e-6f);
    }
    // Over 30 steps rounding grows (the bend's velocity rule switches on a sign), so both keep the
    // invariants and stay close.
    CpuSolver cpu(b.strands, b.setup, glm::mat4(1.0f));
    constexpr uint32_t kSteps = 30;
    std::vector<glm::vec4> previous;
    for (uint32_t n = 0; n < kSteps; ++n) {
        previous = cpu.state().positions;
        cpu.step(stepAt(n));
    }
    GpuSolver gpuSolver(ctx, b.strands, b.setup, glm::mat4(1.0f));
    SimState gpu = runGpu(ctx, gpuSolver, b.setup, kSteps, stepAt, 7);
    Agreement a = agreement(gpu, cpu.state());
    EXPECT_LT(a.max, 2e-4f);
    EXPECT_LT(a.p90, 2e-5f);
    SimMetrics onCpu = measure(cpu.state(), previous, 1.0f / s.stepHz, b.strands, b.setup, stepAt(kSteps - 1));
    SimMetrics onGpu = measure(gpu, previous, 1.0f / s.stepHz, b.strands, b.setup, stepAt(kSteps - 1));
    EXPECT_LT(onCpu.maxStretch, 1e-4f);
    EXPECT_LT(onGpu.maxStretch, 1e-4f);
    EXPECT_LT(onGpu.rootDrift, 1e-6f);
    EXPECT_EQ(gpu.nonfiniteResets, 0u);
    EXPECT_EQ(ctx.validationMessages(), 0u);
}

// Repulsion (shared/sim_grid.h: the continuous density gradient, the blend toward the separation
// speed, nothing pushed into a collider) on the GPU against the CPU at its midpoint and its
// maximum, with friction and contacts: three steps agree to rounding (and differ from the same run
// without repulsion, so the path is exercised); then 120 steps on the GPU alone keep the hair
// finite and unstretched, add no penetration beyond the margin and keep the worst energy (every
// 10th step) within a few times the run without it.
TEST(GpuSolver, RepulsionMatchesTheCpuAndStaysBoundedAtItsExtremes)
{
    vk::Context ctx(test::validatedOptions());
    auto run = [&](float repulsion, uint32_t steps, SimMetrics* last) {
        SimSettings s;
        s.gridFriction = 0.1f;
        s.gridResolution = 16;
        s.gridRepulsion = repulsion;
        BallScene b = ballScene(63, 16, s);
        auto stepAt = [&](uint32_t n) {
            float t = float(n) / s.stepHz;
            glm::mat4 head = glm::rotate(glm::mat4(1.0f), 0.3f * std::sin(2.0f * t), glm::vec3(0, 1, 0));
            return makeStep(b.setup, head, glm::vec4(0.25f - 0.5f * t, 0.15f, 0.0f, 0.06f), t);
        };
        GpuSolver gpuSolver(ctx, b.strands, b.setup, glm::mat4(1.0f));
        SimState after;
        for (uint32_t done = 0; done < steps;) { // measured every 10th step: the worst of each metric
            uint32_t n = std::min(10u, steps - done);
            auto from = [&](uint32_t first) { return [&, first](uint32_t k) { return stepAt(first + k); }; };
            SimState before = runGpu(ctx, gpuSolver, b.setup, n - 1, from(done), 7);
            after = runGpu(ctx, gpuSolver, b.setup, 1, from(done + n - 1));
            done += n;
            if (!last)
                continue;
            SimMetrics m = measure(after, before.positions, 1.0f / s.stepHz, b.strands, b.setup, stepAt(done - 1));
            last->kineticEnergy = std::max(last->kineticEnergy, m.kineticEnergy);
            last->maxPenetration = std::max(last->maxPenetration, m.maxPenetration);
            last->maxStretch = std::max(last->maxStretch, m.maxStretch);
        }
        CpuSolver cpu(b.strands, b.setup, glm::mat4(1.0f));
        if (steps <= 3)
            for (uint32_t n = 0; n < steps; ++n)
                cpu.step(stepAt(n));
        return std::pair{after, cpu.state()};
    };
    SimState plain = run(0.0f, 3, nullptr).first;
    SimMetrics without{};
    run(0.0f, 120, &without);
    for (float repulsion : {0.5f, 1.0f}) {
        auto [gpu, cpu] = run(repulsion, 3, nullptr);
        Agreement a = agreement(gpu, cpu);
        float speeds = 0.0f, change = 0.0f;
        for (size_t i = 0; i < gpu.velocities.size(); ++i) {
            speeds = std::max(speeds, glm::length(glm::vec3(gpu.velocities[i]) - glm::vec3(cpu.velocities[i])));
            change = std::max(change, glm::length(glm::vec3(gpu.velocities[i]) - glm::vec3(plain.velocities[i])));
        }
        std::fprintf(stderr, "repulsion %g: 3 steps max %g, velocities %g, change from none %g\n", double(repulsion),
                     double(a.max), double(speeds), double(change));
        EXPECT_LT(a.max, 1e-5f);
        EXPECT_LT(speeds, 1e-3f);
        EXPECT_GT(change, 1e-2f);
        SimMetrics m{};
        SimState state = run(repulsion, 120, &m).first;
        std::fprintf(stderr, "repulsion %g: 120 steps worst energy %g (without %g), penetration %g, stretch %g\n",
                     double(repulsion), double(m.kineticEnergy), double(without.kineticEnergy),
                     double(m.maxPenetration), double(m.maxStretch));
        EXPECT_EQ(state.nonfiniteResets, 0u);
        EXPECT_LT(m.maxStretch, 1e-4f);
        EXPECT_LT(m.maxPenetration, without.maxPenetration + 0.003f);
        EXPECT_LT(m.kineticEnergy, 4.0f * without.kineticEnergy + 1e-3f);
    }
    EXPECT_EQ(ctx.validationMessages(), 0u);
}

// A handful of the stability trials (tests/test_sim_stability.cpp: every physics setting at its
// extremes and midpoint on the CPU) on the GPU against the CPU: the settings at the top of their
// ranges where the shared math has the most to do (the collision margin, the penalty, repulsion,
// full local stiffness, the float grid), on the bob and fur. One step agrees to rounding; over the
// two seconds the motion is chaotic (GpuMatchesCpu), so the GPU run keeps the CPU's bounds and its
// worst kinetic energy, both sampled every 5th step, stays within a factor of two of the CPU's.
TEST(GpuSolver, StabilityTrialsMatchTheCpu)
{
    vk::Context ctx(test::validatedOptions());
    struct Case {
        const char* groom;
        const char* assignment;
    };
    const Case cases[] = {{"bob", "collision_margin=0.05"},
                          {"bob", "penalty_stiffness=100000"},
                          {"bob", "repulsion=1"},
                          {"bob", "local_stiffness=1"},
                          {"bob", "grid_atomics=float"},
                          {"fur", "collision_margin=0.05"},
                          {"fur", "repulsion=1"}};
    constexpr uint32_t kEvery = 5;
    for (const auto& [groomName, growth] : test::trialGrooms()) {
        GroomedHead scene = buildGrownHead(defaultHeadPath(), growth);
        float diagonal = scene.head.mesh.bounds().diagonal();
        float rest = test::restPenetration(scene);
        float margin = SimSettings{}.collisionMarginMetres * scene.unitsPerMetre;
        for (const Case& c : cases) {
            if (groomName != c.groom)
                continue;
            Settings settings;
            applySetting(settings, c.assignment);
            const SimSettings& sim = settings.sim;
            StrandSet strands = test::strandsUnder(scene, sim);
            SimSetup setup = makeSimSetup(sim, strands, scene.gpuColliders, scene.unitsPerMetre);
            const int settle = int(test::trialSettleSteps(sim));
            auto stepAt = [&](uint32_t k) { return test::trialStep(setup, sim, int(k) - settle); };
            std::string what = groomName + ", " + c.assignment;
            { // one step agrees to rounding
                CpuSolver cpu(strands, setup, glm::mat4(1.0f));
                cpu.step(stepAt(0));
                GpuSolver gpuSolver(ctx, strands, setup, glm::mat4(1.0f));
                EXPECT_LT(agreement(runGpu(ctx, gpuSolver, setup, 1, stepAt), cpu.state()).max, 1e-5f) << what;
            }
            const uint32_t steps = test::trialSteps(sim) + uint32_t(settle);
            test::TrialRun onCpu, onGpu;
            CpuSolver cpu(strands, setup, glm::mat4(1.0f));
            GpuSolver gpuSolver(ctx, strands, setup, glm::mat4(1.0f));
            runGpu(ctx, gpuSolver, setup, uint32_t(settle), stepAt, 10);
            for (uint32_t n = 0; n < uint32_t(settle); ++n)
                cpu.step(stepAt(n));
            for (uint32_t done = uint32_t(settle); done < steps; done += kEvery) {
                auto from = [&](uint32_t first) { return [&, first](uint32_t k) { return stepAt(first + k); }; };
                SimState before = runGpu(ctx, gpuSolver, setup, kEvery - 1, from(done), kEvery);
                SimState after = runGpu(ctx, gpuSolver, setup, 1, from(done + kEvery - 1));
                uint32_t k = done + kEvery - 1;
                onGpu.add(measure(after, before.positions, 1.0f / sim.stepHz, strands, setup, stepAt(k)), k, steps);
                for (uint32_t n = done; n < k; ++n)
                    cpu.step(stepAt(n));
                std::vector<glm::vec4> previous = cpu.state().positions;
                cpu.step(stepAt(k));
                onCpu.add(measure(cpu.state(), previous, 1.0f / sim.stepHz, strands, setup, stepAt(k)), k, steps);
                if (done + kEvery >= steps)
                    onGpu.finish(after);
            }
            onCpu.finish(cpu.state());
            std::fprintf(stderr,
                         "%s: worst energy GPU %.4g CPU %.4g, a second after %.3g %.3g, penetration %.3g %.3g "
                         "of the diagonal, stretch %.2g %.2g\n",
                         what.c_str(), double(onGpu.worstEnergy), double(onCpu.worstEnergy), double(onGpu.lastEnergy),
                         double(onCpu.lastEnergy), double(onGpu.worstPenetration / diagonal),
                         double(onCpu.worstPenetration / diagonal), double(onGpu.worstStretch),
                         double(onCpu.worstStretch));
            EXPECT_TRUE(onGpu.finite) << what;
            EXPECT_EQ(onGpu.resets, 0u) << what;
            EXPECT_LT(onGpu.worstStretch, 1e-4f) << what;
            EXPECT_LT(onGpu.worstPenetration, rest + margin) << what;
            EXPECT_GT(onGpu.worstEnergy, 0.5f * onCpu.worstEnergy) << what;
            EXPECT_LT(onGpu.worstEnergy, 2.0f * onCpu.worstEnergy) << what;
            EXPECT_LT(onGpu.lastEnergy, 0.03f * onCpu.worstEnergy) << what << ": it settles";
        }
    }
    EXPECT_EQ(ctx.validationMessages(), 0u);
}

class GridAtomicsModes : public testing::TestWithParam<SimSettings::GridAtomics> {};

TEST_P(GridAtomicsModes, SplatConservesDensity)
{
    SimSettings s;
    s.gridResolution = 24;
    s.gridAtomics = GetParam();
    BallScene b = ballScene(100, 16, s);
    vk::Context ctx(test::validatedOptions());
    GpuSolver solver(ctx, b.strands, b.setup, glm::mat4(1.0f));
    EXPECT_EQ(solver.fixedPointGrid(), GetParam() == SimSettings::GridAtomics::Fixed);
    runGpu(ctx, solver, b.setup, 3,
           [&](uint32_t n) { return makeStep(b.setup, glm::mat4(1.0f), glm::vec4(0.0f), float(n) / 120.0f); });
    double density = 0.0;
    for (const gpu::GridNode& node : solver.readGrid())
        density += node.density;
    // Every vertex lies inside the grid and adds weights summing to one.
    EXPECT_NEAR(density, double(b.strands.vertexCount()), 1e-3 * double(b.strands.vertexCount()));
    CpuSolver cpu(b.strands, b.setup, glm::mat4(1.0f));
    cpu.step(makeStep(b.setup, glm::mat4(1.0f), glm::vec4(0.0f), 0.0f));
    double cpuDensity = 0.0;
    for (const gpu::GridNode& node : cpu.grid())
        cpuDensity += node.density;
    EXPECT_NEAR(cpuDensity, double(b.strands.vertexCount()), 1e-3 * double(b.strands.vertexCount()));
    EXPECT_EQ(ctx.validationMessages(), 0u);
}

INSTANTIATE_TEST_SUITE_P(Modes, GridAtomicsModes,
                         testing::Values(SimSettings::GridAtomics::Fixed, SimSettings::GridAtomics::Float),
                         [](const testing::TestParamInfo<SimSettings::GridAtomics>& param) {
                             return param.param == SimSettings::GridAtomics::Fixed ? "Fixed" : "Float";
                         });

TEST(GpuSolver, FixedPointGridIsDeterministic)
{
    // Integer sums commute: two runs of the same steps give the same bits, whatever order the
    // device ran the threads in (float atomics do not promise this).
    SimSettings s;
    s.wind = glm::vec3(4.0f, 0.0f, 1.0f);
    s.gridFriction = 0.2f;
    BallScene b = ballScene(300, 16, s);
    vk::Context ctx(test::validatedOptions());
    auto stepAt = [&](uint32_t n) {
        return makeStep(b.setup, glm::mat4(1.0f), glm::vec4(0.1f, 0.15f, 0.0f, 0.05f), float(n) / 120.0f);
    };
    GpuSolver first(ctx, b.strands, b.setup, glm::mat4(1.0f));
    GpuSolver second(ctx, b.strands, b.setup, glm::mat4(1.0f));
    SimState a = runGpu(ctx, first, b.setup, 60, stepAt, 20);
    SimState c = runGpu(ctx, second, b.setup, 60, stepAt, 20);
    ASSERT_TRUE(first.fixedPointGrid());
    EXPECT_EQ(std::memcmp(a.positions.data(), c.positions.data(), a.positions.size() * sizeof(glm::vec4)), 0);
    EXPECT_EQ(std::memcmp(a.velocities.data(), c.velocities.data(), a.velocities.size() * sizeof(glm::vec4)), 0);
    EXPECT_EQ(ctx.validationMessages(), 0u);
}

TEST(GpuSolver, NonFiniteValuesResetStrandsAndAreCounted)
{
    SimSettings s;
    s.wind = glm::vec3(std::numeric_limits<float>::quiet_NaN(), 0.0f, 0.0f); // poisons every free vertex
    BallScene b = ballScene(10, 8, s);
    vk::Context ctx(test::validatedOptions());
    GpuSolver solver(ctx, b.strands, b.setup, glm::mat4(1.0f));
    SimState state = runGpu(ctx, solver, b.setup, 3, [&](uint32_t n) {
        return makeStep(b.setup, glm::mat4(1.0f), glm::vec4(0.0f), float(n) / 120.0f);
    });
    // Each substep resets all 10 strands: 3 steps x 2 substeps x 10.
    EXPECT_EQ(state.nonfiniteResets, 3u * b.setup.substeps * 10u);
    for (const glm::vec4& p : state.positions)
        EXPECT_TRUE(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z));
    // Reset means the rest pose, exactly.
    for (size_t i = 0; i < state.positions.size(); ++i)
        EXPECT_NEAR(glm::length(glm::vec3(state.positions[i]) - b.strands.rest[i]), 0.0f, 1e-6f);
    CpuSolver cpu(b.strands, b.setup, glm::mat4(1.0f));
    cpu.step(makeStep(b.setup, glm::mat4(1.0f), glm::vec4(0.0f), 0.0f));
    EXPECT_EQ(cpu.state().nonfiniteResets, b.setup.substeps * 10u);
    EXPECT_EQ(ctx.validationMessages(), 0u);
}

TEST(GpuSolver, WorkloadLargerThanMemoryIsRefusedWithSizes)
{
    SimSettings s;
    BallScene b = ballScene(4, 4, s);
    b.setup.params.gridResolution = 256;
    b.setup.params.gridNodeCount = 256u * 256u * 256u;
    vk::Context ctx(test::validatedOptions());
    // Make the device look small by asking for far more grid than it has: 2048 MiB on lavapipe.
    b.setup.params.gridNodeCount = 0xFFFFFFFFu;
    try {
        GpuSolver solver(ctx, b.strands, b.setup, glm::mat4(1.0f));
        FAIL() << "expected a UserError";
    } catch (const UserError& e) {
        std::string what = e.what();
        EXPECT_NE(what.find("needs"), std::string::npos) << what;
        EXPECT_NE(what.find("MiB of GPU memory"), std::string::npos) << what;
        EXPECT_NE(what.find("' has "), std::string::npos) << what;
    }
}
