// tests/test_sim_cpu.cpp: the simulation without a device: the shared math (shaders/shared/sim.h)
// against hand-computed values, the CPU reference on a hand-checked step, the CPU reference on a
// grown groom (every term: wind, the sphere, colliders, the grid) keeping its invariants, the
// fixed-point grid's scale, and root sampling. (The GPU kernels against it: test_gpu_solver.cpp.)
#include "app/settings/settings_table.h"
#include "assets/signed_distance.h"
#include "core/error.h"
#include "physics/colliders.h"
#include "physics/cpu_solver.h"
#include "physics/groom_metrics.h"
#include "physics/groomed_head.h"
#include "physics/growth.h"
#include "physics/hair_style.h"
#include "physics/step_clock.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <glm/gtc/matrix_transform.hpp>
#include <memory>
#include <random>
#include <string>
#include <utility>
#include <vector>

using namespace wisp;

// ---- Shared math -----------------------------------------------------------------------------

TEST(SimMath, FtlProjectKeepsTheRestLengthAlongTheLine)
{
    glm::vec3 p = gpu::ftlProject(glm::vec3(1, 2, 3), glm::vec3(4, 6, 3), 2.5f);
    EXPECT_NEAR(glm::length(p - glm::vec3(1, 2, 3)), 2.5f, 1e-6f);
    EXPECT_NEAR(p.x, 1.0f + 2.5f * 0.6f, 1e-6f); // along (3, 4, 0) / 5
    EXPECT_NEAR(p.y, 2.0f + 2.5f * 0.8f, 1e-6f);
}

TEST(SimMath, MinimalRotationTakesAToBAndIsARotation)
{
    glm::vec3 a = glm::normalize(glm::vec3(1, 0.3f, -0.2f));
    glm::vec3 b = glm::normalize(glm::vec3(-0.4f, 1, 0.5f));
    glm::mat3 R = gpu::minimalRotation(a, b);
    glm::vec3 rb = R * a;
    EXPECT_NEAR(glm::length(rb - b), 0.0f, 1e-5f);
    glm::mat3 I = glm::transpose(R) * R;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            EXPECT_NEAR(I[i][j], i == j ? 1.0f : 0.0f, 1e-5f);
    EXPECT_NEAR(glm::determinant(R), 1.0f, 1e-5f);
    // The axis a x b is left alone.
    glm::vec3 axis = glm::normalize(glm::cross(a, b));
    EXPECT_NEAR(glm::length(R * axis - axis), 0.0f, 1e-5f);
}

TEST(SimMath, TrilinearWeightsSumToOneAndInterpolate)
{
    glm::vec3 f(0.2f, 0.7f, 0.35f);
    float sum = 0.0f, x = 0.0f;
    for (uint32_t k = 0; k < 8; ++k) {
        sum += gpu::cornerWeight(f, k);
        x += gpu::cornerWeight(f, k) * float(gpu::cornerOffset(k).x);
    }
    EXPECT_NEAR(sum, 1.0f, 1e-6f);
    EXPECT_NEAR(x, 0.2f, 1e-6f); // interpolating the corner coordinate gives the point back
    gpu::GridCell c = gpu::gridCell(glm::vec3(1.3f, -0.5f, 2.0f), glm::vec3(0.0f), 0.5f);
    EXPECT_EQ(c.base, glm::ivec3(2, -1, 4));
    EXPECT_NEAR(c.frac.x, 0.6f, 1e-5f);
    EXPECT_FALSE(gpu::cellInside(c.base, 8));
    EXPECT_TRUE(gpu::cellInside(glm::ivec3(6, 0, 6), 8));
    EXPECT_FALSE(gpu::cellInside(glm::ivec3(7, 0, 0), 8)); // corner 8 would be outside
}

TEST(SimMath, SphereAndEllipsoidContacts)
{
    gpu::Contact s = gpu::sphereContact(glm::vec3(0), 1.0f, glm::vec3(0, 0.5f, 0), 0.1f);
    EXPECT_NEAR(s.depth, 0.6f, 1e-6f);
    EXPECT_NEAR(s.normal.y, 1.0f, 1e-6f);
    // An ellipsoid of radii (2, 1, 1): a point on its x axis, 0.5 inside.
    Ellipsoid e{.name = "e", .center = glm::vec3(0), .radii = glm::vec3(2, 1, 1), .rotationDeg = glm::vec3(0)};
    gpu::Contact c = gpu::ellipsoidContact(toGpu(e), glm::vec3(1.5f, 0, 0), 0.0f);
    EXPECT_NEAR(c.depth, 0.5f, 1e-6f);
    EXPECT_NEAR(c.normal.x, 1.0f, 1e-6f);
    EXPECT_LT(gpu::ellipsoidContact(toGpu(e), glm::vec3(0, 1.2f, 0), 0.0f).depth, 0.0f);
    // Rotated 90 degrees about z, its long axis is y.
    e.rotationDeg = glm::vec3(0, 0, 90);
    EXPECT_NEAR(gpu::ellipsoidContact(toGpu(e), glm::vec3(0, 1.5f, 0), 0.0f).depth, 0.5f, 1e-5f);
    // A head moved by +10 in x carries its colliders along.
    glm::mat4 head = glm::translate(glm::mat4(1.0f), glm::vec3(10, 0, 0));
    EXPECT_NEAR(gpu::headColliderContact(toGpu(e), head, glm::vec3(10, 1.5f, 0), 0.0f).depth, 0.5f, 1e-5f);
}

TEST(SimMath, TheQuickInsideTestLetsThroughEveryPointTheContactFindsInside)
{
    // The solvers skip a collider's contact where ellipsoidMayContain says no: that must never skip
    // a point the contact puts inside (depth > 0), with or without a margin, however turned.
    Ellipsoid e{.name = "e",
                .center = glm::vec3(0.1f, -0.2f, 0.3f),
                .radii = glm::vec3(2, 1, 0.5f),
                .rotationDeg = glm::vec3(20, 35, -50)};
    gpu::Ellipsoid g = toGpu(e);
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> coord(-2.5f, 2.5f);
    int inside = 0, skipped = 0;
    for (int n = 0; n < 20000; ++n) {
        glm::vec3 p(coord(rng), coord(rng), coord(rng));
        for (float margin : {0.0f, 0.05f}) {
            float depth = gpu::ellipsoidContact(g, p, margin).depth;
            bool may = gpu::ellipsoidMayContain(g, p, margin);
            if (depth > 0.0f) {
                ++inside;
                EXPECT_TRUE(may) << "skipped a point " << depth << " inside at margin " << margin;
            }
            if (!may)
                ++skipped;
        }
    }
    // Both kinds occur, so the test says something; most points of the box lie outside.
    EXPECT_GT(inside, 1000);
    EXPECT_GT(skipped, 20000);
}

TEST(SimMath, WindActsAcrossTheStrandOnly)
{
    glm::vec3 w(3, 0, 0);
    EXPECT_NEAR(glm::length(gpu::windAcceleration(glm::vec3(1, 0, 0), w)), 0.0f, 1e-6f);
    glm::vec3 across = gpu::windAcceleration(glm::vec3(0, -1, 0), w);
    EXPECT_NEAR(across.x, 3.0f, 1e-6f);
    EXPECT_NEAR(across.y, 0.0f, 1e-6f);
    // Gusts differ between strands and over time, and stay within [0.15, 1.25] of the base wind
    // in strength (0.75..1.25 gain x 0.2..1.0 gust and turbulence).
    float a = gpu::strandWind(w, 0.5f, 1.0f, 1).x, b = gpu::strandWind(w, 0.5f, 1.0f, 2).x;
    EXPECT_NE(a, b);
    float lo = 1e9f, hi = -1e9f;
    for (float t = 0.0f; t < 60.0f; t += 0.01f) {
        float x = gpu::strandWind(w, 0.5f, t, 7).x / 3.0f;
        lo = std::min(lo, x);
        hi = std::max(hi, x);
    }
    EXPECT_GE(lo, 0.15f);
    EXPECT_LE(hi, 1.25f);
    EXPECT_GT(hi - lo, 0.3f); // it does vary
    // The noise is smooth: small steps in time change it little.
    EXPECT_NEAR(gpu::valueNoise(3.50f, 9), gpu::valueNoise(3.51f, 9), 0.03f);
}

TEST(SimMath, TwoLinkJointKeepsBothLengths)
{
    glm::vec3 a(0.0f), b(1.5f, 0.0f, 0.0f);
    for (glm::vec3 near : {glm::vec3(0.7f, -0.3f, 0.0f), glm::vec3(0.2f, 0.1f, 0.9f), glm::vec3(0.75f, 0.0f, 0.0f)}) {
        glm::vec3 j = gpu::twoLinkJoint(a, b, 1.0f, 0.8f, near);
        EXPECT_NEAR(glm::length(j - a), 1.0f, 1e-6f);
        EXPECT_NEAR(glm::length(j - b), 0.8f, 1e-6f);
    }
    // The nearer of the circle's points: below the axis when asked from below.
    EXPECT_LT(gpu::twoLinkJoint(a, b, 1.0f, 0.8f, glm::vec3(0.7f, -0.3f, 0.0f)).y, 0.0f);
    // Taut: both segments share the stretch on the line.
    glm::vec3 t = gpu::twoLinkJoint(a, glm::vec3(2.0f, 0.0f, 0.0f), 1.0f, 0.6f, glm::vec3(1.0f, 1.0f, 0.0f));
    EXPECT_NEAR(t.x, 2.0f / 1.6f, 1e-6f);
    EXPECT_NEAR(t.y, 0.0f, 1e-6f);
}

TEST(SimMath, FixedPointScaleCannotOverflow)
{
    // The worst node sum, every vertex's full weight at the largest splat speed, stays below 2^62.
    for (uint64_t vertices : {1ull, 1000ull, 3200000ull, 100000000ull})
        for (float speed : {0.5f, 20.0f, 2000.0f}) {
            double worst = double(vertices) * std::max(1.0, double(speed)) * double(gridFixedScale(vertices, speed));
            EXPECT_LE(worst, std::ldexp(1.0, 62) * 1.0001);
            EXPECT_GT(worst, std::ldexp(1.0, 61)); // and uses most of the range
        }
}

// ---- CPU reference, by hand ------------------------------------------------------------------

namespace {

// A straight strand of four unit segments along +x, at rest, with only gravity -10 in y acting
// (no drag, shape, wind, grid or colliders); one substep of 0.1 s is run on the CPU reference.
struct OneStep {
    StrandSet strands;
    SimSetup setup;
    std::unique_ptr<CpuSolver> cpu;
};

OneStep oneStepOfAStraightStrand(float ftlDamping)
{
    OneStep o;
    o.strands.verticesPerStrand = 4;
    PartSettings part;
    part.globalStiffness = part.localStiffness = part.drag = 0.0f;
    part.ftlDamping = ftlDamping;
    o.strands.parts.push_back(part);
    o.strands.add({{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {3, 0, 0}}, 0, 1, false);
    SimSettings s;
    s.stepHz = 10.0f;
    s.substeps = 1;
    s.gravity = 10.0f;
    s.gridFriction = 0.0f;
    s.gridResolution = 8;
    o.setup = makeSimSetup(s, o.strands, {}, 1.0f);
    o.cpu = std::make_unique<CpuSolver>(o.strands, o.setup, glm::mat4(1.0f));
    o.cpu->step(makeStep(o.setup, glm::mat4(1.0f), glm::vec4(0.0f), 0.0f));
    return o;
}

} // namespace

TEST(CpuReference, OneStepOfOneSegmentByHand)
{
    OneStep o = oneStepOfAStraightStrand(0.0f);
    const SimState& state = o.cpu->state();
    // Predicted: every free vertex drops by dt² g = 0.1 to y = -0.1. FTL: vertex 1 moves onto
    // the unit circle around the root along (1, -0.1): (1, -0.1) / sqrt(1.01).
    glm::vec3 p1(state.positions[1]);
    EXPECT_NEAR(p1.x, 1.0f / std::sqrt(1.01f), 1e-6f);
    EXPECT_NEAR(p1.y, -0.1f / std::sqrt(1.01f), 1e-6f);
    // With s_damp = 0 the velocity is the plain (p - x) / dt.
    glm::vec3 v1(state.velocities[1]);
    EXPECT_NEAR(v1.y, (p1.y - 0.0f) / 0.1f, 1e-5f);
    // Every segment keeps its length exactly.
    for (int i = 1; i < 4; ++i)
        EXPECT_NEAR(glm::length(glm::vec3(state.positions[i]) - glm::vec3(state.positions[i - 1])), 1.0f, 1e-6f);
}

TEST(CpuReference, VelocityCorrectionUsesTheChildsCorrection)
{
    // With s_damp = 1: v_1 = (p_1 - x_1)/dt - d_2/dt, d_2 = vertex 2's FTL correction.
    OneStep o = oneStepOfAStraightStrand(1.0f);
    const SimState& state = o.cpu->state();
    glm::vec3 p1(state.positions[1]), p2(state.positions[2]);
    glm::vec3 predicted2(2.0f, -0.1f, 0.0f);
    glm::vec3 d2 = p2 - predicted2;
    glm::vec3 expected = (p1 - glm::vec3(1, 0, 0)) / 0.1f - d2 / 0.1f;
    EXPECT_NEAR(glm::length(glm::vec3(state.velocities[1]) - expected), 0.0f, 1e-5f);
}

TEST(CpuReference, AStrandPinnedAtBothEndsKeepsEverySegment)
{
    // A loop hanging from the root to a pinned tip (TressFX bothEndsImmovable): FTL from the root
    // alone stretched the last segment to the tip (measured on a real ponytail part: stretch 2 to
    // 7.5, kinetic energy 1e7 within 10 steps). With the bend at the middle vertex (sim.h),
    // every segment keeps its length under gravity and a turning head, and it settles after.
    StrandSet strands;
    strands.verticesPerStrand = 12;
    strands.parts.push_back(PartSettings{});
    for (int s = 0; s < 3; ++s) {
        std::vector<glm::vec3> points;
        for (int i = 0; i < 12; ++i) {
            float u = float(i) / 11.0f;
            // From (0, 0.1, 0) to (0.08, 0.1, 0), sagging 0.05 (arc 1.1 to 1.6 times the gap).
            points.push_back(
                glm::vec3(0.08f * u, 0.1f - (0.03f + 0.01f * float(s)) * 4.0f * u * (1.0f - u), 0.01f * float(s)));
        }
        strands.add(points, 0, s == 2 ? 2u : 1u, true);
    }
    SimSettings settings;
    settings.gridResolution = 8;
    SimSetup setup = makeSimSetup(settings, strands, {}, 1.0f);
    CpuSolver cpu(strands, setup, glm::mat4(1.0f));
    std::vector<glm::vec4> previous;
    gpu::SimStep step{};
    float moving = 0.0f;
    for (uint32_t k = 0; k < 600; ++k) {
        previous = cpu.state().positions;
        float t = float(k) / settings.stepHz;
        glm::mat4 head = glm::rotate(glm::mat4(1.0f), k < 120 ? 0.5f * std::sin(6.0f * t) : 0.0f, glm::vec3(0, 1, 0));
        step = makeStep(setup, head, glm::vec4(0.0f), t);
        cpu.step(step);
        SimMetrics m = measure(cpu.state(), previous, 1.0f / settings.stepHz, strands, setup, step);
        ASSERT_LT(m.maxStretch, 1e-4f) << "step " << k;
        ASSERT_LT(m.rootDrift, 1e-6f) << "step " << k;
        if (k < 120)
            moving = std::max(moving, m.kineticEnergy);
        if (k == 599) {
            EXPECT_LT(m.kineticEnergy, 1e-3f * moving) << "it settles once the head stops";
        }
    }
    EXPECT_GT(moving, 1e-3f) << "the turning head moves it";
    EXPECT_EQ(cpu.state().nonfiniteResets, 0u);
    // The tip stays where the head puts it.
    for (size_t s = 0; s < 3; ++s)
        EXPECT_NEAR(glm::length(glm::vec3(cpu.state().positions[s * 12 + 11]) - strands.rest[s * 12 + 11]), 0.0f,
                    1e-6f);
}

TEST(CpuReference, GrownGroomKeepsItsInvariantsUnderEveryTerm)
{
    // 40 guides on the default head, 60 steps (half a second) with wind, a sphere pushed into the
    // hair and the hair-hair grid: segments keep their length, roots stay where the head puts
    // them, nothing goes non-finite, and no vertex is left deep inside a collider.
    GrowthSettings growth;
    growth.guides = 40;
    growth.verticesPerStrand = 12;
    GroomedHead scene = buildGrownHead(defaultHeadPath(), growth);
    SimSettings settings;
    settings.wind = glm::vec3(3.0f, 0.0f, 1.0f);
    settings.gridFriction = 0.2f;
    settings.gridRepulsion = 0.1f;
    settings.gridResolution = 16;
    SimSetup setup = makeSimSetup(settings, scene.strands, scene.gpuColliders, scene.unitsPerMetre);
    CpuSolver cpu(scene.strands, setup, glm::mat4(1.0f));
    Bounds b = scene.strands.bounds();
    glm::vec4 sphere(b.center() + glm::vec3(0.0f, 0.0f, 0.5f * b.size().z), 0.1f * b.diagonal());
    std::vector<glm::vec4> previous;
    gpu::SimStep step{};
    for (uint32_t k = 0; k < 60; ++k) {
        previous = cpu.state().positions;
        step = makeStep(setup, glm::mat4(1.0f), sphere, float(k) / settings.stepHz);
        cpu.step(step);
    }
    SimMetrics m = measure(cpu.state(), previous, 1.0f / settings.stepHz, scene.strands, setup, step);
    EXPECT_EQ(cpu.state().nonfiniteResets, 0u);
    EXPECT_LT(m.maxStretch, 1e-4f);
    EXPECT_EQ(m.rootDrift, 0.0f);
    EXPECT_LT(m.maxPenetration, 0.01f * scene.head.mesh.bounds().diagonal());
    for (const glm::vec4& p : cpu.state().positions)
        ASSERT_TRUE(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z));
}

// ---- The hair-hair grid's settings at every allowed value -----------------------------

namespace {

struct GroomRun {
    float worstEnergy = 0.0f;
    float lastEnergy = 0.0f; // the last step's, a second after the head stopped
    float worstPenetration = 0.0f;
    float worstStretch = 0.0f;
    uint32_t resets = 0;
    bool finite = true;
};

// `steps` steps: the head turns to and fro for the first half, then holds still.
GroomRun runGroom(const GroomedHead& scene, const SimSettings& settings, uint32_t steps)
{
    SimSetup setup = makeSimSetup(settings, scene.strands, scene.gpuColliders, scene.unitsPerMetre);
    CpuSolver cpu(scene.strands, setup, glm::mat4(1.0f));
    GroomRun run;
    for (uint32_t k = 0; k < steps; ++k) {
        std::vector<glm::vec4> previous = cpu.state().positions;
        float t = float(std::min(k, steps / 2)) / settings.stepHz;
        glm::mat4 head = glm::rotate(glm::mat4(1.0f), 0.4f * std::sin(4.0f * t), glm::vec3(0, 1, 0));
        gpu::SimStep step = makeStep(setup, head, glm::vec4(0.0f), float(k) / settings.stepHz);
        cpu.step(step);
        SimMetrics m = measure(cpu.state(), previous, 1.0f / settings.stepHz, scene.strands, setup, step);
        run.worstEnergy = std::max(run.worstEnergy, m.kineticEnergy);
        run.worstPenetration = std::max(run.worstPenetration, m.maxPenetration);
        run.worstStretch = std::max(run.worstStretch, m.maxStretch);
        run.lastEnergy = m.kineticEnergy;
    }
    for (const glm::vec4& p : cpu.state().positions)
        run.finite = run.finite && std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z);
    run.resets = cpu.state().nonfiniteResets;
    return run;
}

} // namespace

TEST(CpuReference, RepulsionAndFrictionAreStableAtEveryAllowedValue)
{
    // `--repulsion 0.1` blew the default bob up (worst kinetic energy 28,958 against 1.2 without,
    // penetration 0.17 of the head's diagonal): its push was an impulse of the density gradient
    // counted in vertices, so it grew with the groom's vertex count and built up step after step.
    // On two small grooms (the bob, and fur: the crop cut to 4 cm), repulsion at its extremes and
    // midpoints, and friction at its extremes with full repulsion, must keep the energy within a
    // few times what the same run has without repulsion, add no penetration beyond the collision
    // margin, stretch nothing, and let the hair settle once the head stops.
    Range repulsion = settingSpec("repulsion").range;
    Range friction = settingSpec("friction").range;
    GrowthSettings bob;
    bob.guides = 200;
    GrowthSettings fur;
    applyHairStyle(fur, *findHairStyle("crop"));
    fur.guides = 200;
    fur.lengthMetres = 0.04f;
    fur.trimLevelMetres = 0.0f;
    fur.hairlineLength = 1.0f;
    for (const auto& [name, growth] : {std::pair{"bob", bob}, std::pair{"fur", fur}}) {
        GroomedHead scene = buildGrownHead(defaultHeadPath(), growth);
        const uint32_t steps = 240;
        SimSettings base;
        base.gridResolution = 16;
        GroomRun without = runGroom(scene, base, steps);
        float margin = base.collisionMarginMetres * scene.unitsPerMetre;
        std::vector<std::pair<float, float>> cases; // (repulsion, friction)
        for (double f : {0.25, 0.5, 0.75, 1.0})
            cases.emplace_back(float(repulsion.min + f * (repulsion.max - repulsion.min)), base.gridFriction);
        cases.emplace_back(float(repulsion.max), float(friction.min));
        cases.emplace_back(float(repulsion.max), float(friction.max));
        for (auto [r, f] : cases) {
            SimSettings s = base;
            s.gridRepulsion = r;
            s.gridFriction = f;
            GroomRun run = runGroom(scene, s, steps);
            std::string what =
                std::string(name) + ", repulsion " + std::to_string(r) + ", friction " + std::to_string(f);
            std::fprintf(stderr, "%s: worst energy %g (without repulsion %g), last %g, penetration %g (%g)\n",
                         what.c_str(), double(run.worstEnergy), double(without.worstEnergy), double(run.lastEnergy),
                         double(run.worstPenetration), double(without.worstPenetration));
            EXPECT_TRUE(run.finite) << what;
            EXPECT_EQ(run.resets, 0u) << what;
            EXPECT_LT(run.worstStretch, 1e-4f) << what;
            EXPECT_LT(run.worstEnergy, 4.0f * without.worstEnergy) << what;
            EXPECT_LT(run.worstPenetration, without.worstPenetration + margin) << what;
            EXPECT_LT(run.lastEnergy, 0.02f * run.worstEnergy) << what << ": it settles once the head stops";
        }
    }
}

TEST(GridRepulsion, ABoundedBlendTowardTheSeparationSpeed)
{
    // Down a gradient of twice the rest density per cell the target is the full separation speed
    // (|g| capped at 1); the component along it is blended by `repulsion`, the rest left alone,
    // and a vertex already moving apart faster keeps its velocity.
    glm::vec3 gradient(0.0f, 0.0f, -2.0f * 50.0f); // density falls toward +z; rest density 50
    glm::vec3 v(1.0f, 0.0f, -3.0f);
    glm::vec3 dv = gpu::gridRepulsionChange(v, gradient, 0.25f, 2.0f, 50.0f);
    EXPECT_NEAR(dv.x, 0.0f, 1e-6f);
    EXPECT_NEAR(dv.z, 0.25f * (2.0f - -3.0f), 1e-5f);
    EXPECT_EQ(gpu::gridRepulsionChange(glm::vec3(0, 0, 5), gradient, 1.0f, 2.0f, 50.0f), glm::vec3(0.0f));
    // Half a rest density per cell: half the speed; at repulsion 1 the vertex moves at it exactly.
    glm::vec3 w = gpu::gridRepulsionChange(glm::vec3(0.0f), glm::vec3(0, 0, -25.0f), 1.0f, 2.0f, 50.0f);
    EXPECT_NEAR(w.z, 1.0f, 1e-6f);
    // Nothing of it points into a collider within reach.
    gpu::Contact c{glm::vec3(0, 0, 1), 0.01f}; // a collider behind the vertex (-z): its normal is +z
    glm::vec3 kept = gpu::withoutPartInto(glm::vec3(1, 0, -2), c);
    EXPECT_EQ(kept, glm::vec3(1, 0, 0));
    EXPECT_EQ(gpu::withoutPartInto(glm::vec3(1, 0, 2), c), glm::vec3(1, 0, 2));
}

TEST(GridRepulsion, RestDensityIsTheDensityAVertexSeesWhateverTheGroomsSize)
{
    // The same strands twice over (two copies of each) double the density a vertex sees; the
    // repulsion, measured against it, is the same for both.
    GrowthSettings g;
    g.guides = 100;
    GroomedHead one = buildGrownHead(defaultHeadPath(), g);
    StrandSet two = one.strands;
    for (size_t s = 0; s < one.strands.strandCount(); ++s) {
        auto first = one.strands.rest.begin() + std::ptrdiff_t(s * g.verticesPerStrand);
        two.add(std::vector<glm::vec3>(first, first + g.verticesPerStrand), 0, 1, false);
    }
    SimSettings s;
    SimSetup a = makeSimSetup(s, one.strands, one.gpuColliders, one.unitsPerMetre);
    SimSetup b = makeSimSetup(s, two, one.gpuColliders, one.unitsPerMetre);
    EXPECT_GT(a.params.gridRestDensity, 1.0f);
    EXPECT_NEAR(b.params.gridRestDensity, 2.0f * a.params.gridRestDensity, 1e-3f * a.params.gridRestDensity);
    EXPECT_NEAR(a.params.gridSeparationSpeed, gpu::kRepulsionCellsPerStep * a.params.gridCellSize * s.stepHz, 1e-6f);
}

// ---- Root sampling -----------------------------------------------------------------------------

namespace {

// Two triangles in the plane z = 0: one of area 0.5, one of area 4.5 (nine times larger).
Mesh twoTriangles()
{
    Mesh m;
    m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {10, 0, 0}, {13, 0, 0}, {10, 3, 0}};
    m.normals.assign(6, glm::vec3(0, 0, 1));
    m.indices = {0, 1, 2, 3, 4, 5};
    return m;
}

} // namespace

TEST(RootSampling, AreaWeightedAndDeterministic)
{
    Mesh m = twoTriangles();
    std::vector<RootSample> a = sampleRoots(m, {0, 1}, 20000, false, 7);
    std::vector<RootSample> b = sampleRoots(m, {0, 1}, 20000, false, 7);
    size_t onSmall = 0;
    for (size_t i = 0; i < a.size(); ++i) {
        ASSERT_EQ(a[i].position, b[i].position); // same seed, same roots
        onSmall += a[i].triangle == 0 ? 1 : 0;
        EXPECT_NEAR(a[i].normal.z, 1.0f, 1e-6f);
    }
    // Area-weighted: 10% of the roots on the small triangle (binomial sigma about 0.2%).
    EXPECT_NEAR(double(onSmall) / 20000.0, 0.1, 0.01);
    // Uniform inside a triangle: the mean of the big one's samples is its centroid.
    glm::vec3 mean(0.0f);
    size_t n = 0;
    for (const RootSample& r : a)
        if (r.triangle == 1) {
            mean += r.position;
            ++n;
        }
    mean /= float(n);
    EXPECT_NEAR(mean.x, 11.0f, 0.03f);
    EXPECT_NEAR(mean.y, 1.0f, 0.03f);
    EXPECT_NE(sampleRoots(m, {0, 1}, 10, false, 8)[0].position, a[0].position); // another seed differs
}

TEST(RootSampling, PoissonDiskKeepsRootsApart)
{
    Mesh m = twoTriangles();
    std::vector<RootSample> plain = sampleRoots(m, {1}, 400, false, 3);
    std::vector<RootSample> blue = sampleRoots(m, {1}, 400, true, 3);
    auto minDistance = [](const std::vector<RootSample>& s) {
        float best = 1e9f;
        for (size_t i = 0; i < s.size(); ++i)
            for (size_t j = i + 1; j < s.size(); ++j)
                best = std::min(best, glm::length(s[i].position - s[j].position));
        return best;
    };
    ASSERT_EQ(blue.size(), 400u);
    // 400 disks tiling 4.5 square units have radius sqrt(4.5 / (400 pi)) = 0.06; blue noise keeps
    // roots well apart, random sampling does not.
    EXPECT_GT(minDistance(blue), 0.03f);
    EXPECT_LT(minDistance(plain), 0.01f);
}

TEST(RootSampling, AnEmptyScalpIsAClearError)
{
    Mesh m = twoTriangles();
    EXPECT_THROW(sampleRoots(m, {}, 10, false, 1), UserError);
}

TEST(StepClock, FramesTakeRoundedStepsAndRealTimeIsSpentInWholeSteps)
{
    StepClock clock(120.0f);
    EXPECT_EQ(clock.stepsPerFrame(30.0f), 4u);
    EXPECT_EQ(clock.stepsPerFrame(60.0f), 2u);
    EXPECT_EQ(clock.stepsPerFrame(1000.0f), 1u); // at least one
    EXPECT_EQ(clock.stepsPerFrame(50.0f), 2u);   // round(2.4)
    // 26 ms of real time: three steps of 8.33 ms, the rest carried to the next frame.
    EXPECT_EQ(clock.stepsDue(0.026, 8), 3u);
    EXPECT_EQ(clock.stepsDue(0.005, 8), 0u);
    EXPECT_EQ(clock.stepsDue(0.005, 8), 1u);
    // A stall: capped, and the backlog dropped (the simulation slows down instead of spiralling).
    EXPECT_EQ(clock.stepsDue(1.0, 8), 8u);
    EXPECT_EQ(clock.stepsDue(0.0, 8), 0u);
    clock.advance(240);
    EXPECT_DOUBLE_EQ(clock.seconds(), 2.0);
    EXPECT_FLOAT_EQ(clock.stepStart(240), 2.0f);
    EXPECT_DOUBLE_EQ(clock.stepEnd(239), 2.0);
    clock.setStepHz(60.0f); // time runs on at the new rate
    EXPECT_DOUBLE_EQ(clock.seconds(), 2.0);
    EXPECT_EQ(clock.stepsDone(), 120u);
}

// ---- The head mesh's field in the solver ---------------------------------------------------------

namespace {

// Strands growing straight out of the upper half of a sphere mesh of radius 0.1 m (the "head"),
// with only a small ellipsoid deep inside it: gravity drapes them over the sphere, through it
// unless the mesh's field holds them out.
struct MeshBall {
    Mesh mesh = makeSphereMesh(24, 48);
    StrandSet strands;
    std::vector<gpu::Ellipsoid> colliders;
};

MeshBall meshBall(uint32_t count, uint32_t V)
{
    MeshBall b;
    for (glm::vec3& p : b.mesh.positions)
        p *= 0.1f;
    Ellipsoid core{.name = "core", .center = glm::vec3(0), .radii = glm::vec3(0.03f), .rotationDeg = glm::vec3(0)};
    b.colliders.push_back(toGpu(core));
    b.strands.verticesPerStrand = V;
    // No pull toward the rest pose: the strands fall.
    b.strands.parts.push_back(PartSettings{.globalStiffness = 0.0f, .localStiffness = 0.0f});
    for (uint32_t s = 0; s < count; ++s) {
        float t = (float(s) + 0.5f) / float(count);
        float y = 0.2f + 0.8f * t, r = std::sqrt(1.0f - y * y), phi = 2.39996323f * float(s);
        glm::vec3 n(r * std::cos(phi), y, r * std::sin(phi));
        std::vector<glm::vec3> points(V);
        for (uint32_t i = 0; i < V; ++i)
            points[i] = n * (0.1f + 0.15f * float(i) / float(V - 1));
        b.strands.add(points, 0, 1, false);
    }
    return b;
}

} // namespace

TEST(CpuReference, MeshFieldHoldsHairOutOfTheMeshItself)
{
    // A second of draping: with the mesh's field few strands end inside the sphere mesh; with the
    // colliders alone (sdf_resolution 0) most do.
    MeshBall b = meshBall(60, 12);
    MeshSignedDistance exact(b.mesh);
    float diagonal = b.mesh.bounds().diagonal();
    InsideMesh with, without;
    for (uint32_t resolution : {64u, 0u}) {
        SimSettings s;
        s.sdfResolution = resolution;
        s.gridFriction = 0.0f;
        SimSetup setup = makeSimSetup(s, b.strands, b.colliders, 1.0f, b.mesh);
        ASSERT_EQ(setup.sdf != nullptr, resolution > 0);
        ASSERT_EQ(setup.params.sdf.dims.x > 0u, resolution > 0);
        CpuSolver cpu(b.strands, setup, glm::mat4(1.0f));
        for (uint32_t n = 0; n < 120; ++n)
            cpu.step(makeStep(setup, glm::mat4(1.0f), glm::vec4(0.0f), float(n) / s.stepHz));
        std::vector<glm::vec3> positions;
        for (const glm::vec4& p : cpu.state().positions)
            positions.push_back(glm::vec3(p));
        (resolution > 0 ? with : without) = insideMesh(exact, diagonal, positions, 12);
        EXPECT_EQ(cpu.state().nonfiniteResets, 0u);
    }
    std::fprintf(stderr, "inside the mesh: with the field %s; without %s\n", with.describe().c_str(),
                 without.describe().c_str());
    // Measured: 3.3% of strands with the field (two strands whose vertices went deeper than the band,
    // where the field is flat and pushes no more), 100% without.
    EXPECT_LE(with.strandShare(), 0.05);
    EXPECT_LE(with.vertexShare(), 0.05);
    EXPECT_GE(without.strandShare(), 0.3);
    EXPECT_GE(without.vertexShare(), 0.3);
}
