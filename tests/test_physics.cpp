// tests/test_physics.cpp: the simulation. The shared math against hand-computed values; the CPU
// reference on a hand-checked step; the GPU kernels against the CPU reference on awkward sizes;
// and the physics' invariants as numbers (stretch, penetration, root drift, resets, energy).
#include "core/error.h"
#include "physics/colliders.h"
#include "physics/cpu_solver.h"
#include "physics/gpu_solver.h"
#include "physics/hair_scene.h"
#include "renderer/frame.h"
#include "renderer/physics_pass.h"
#include "test_support.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <cstdio>
#include <functional>
#include <glm/gtc/matrix_transform.hpp>
#include <limits>
#include <memory>

using namespace wisp;

// ---- Shared math -----------------------------------------------------------------------------

TEST(SimMath, FtlProjectKeepsTheRestLengthAlongTheLine)
{
    glm::vec3 p = gpu::ftlProject(glm::vec3(1, 2, 3), glm::vec3(4, 6, 3), 2.5f);
    EXPECT_NEAR(glm::length(p - glm::vec3(1, 2, 3)), 2.5f, 1e-6f);
    EXPECT_NEAR(p.x, 1.0f + 2.5f * 0.6f, 1e-6f);  // along (3, 4, 0) / 5
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
    EXPECT_NEAR(x, 0.2f, 1e-6f);  // interpolating the corner coordinate gives the point back
    gpu::GridCell c = gpu::gridCell(glm::vec3(1.3f, -0.5f, 2.0f), glm::vec3(0.0f), 0.5f);
    EXPECT_EQ(c.base, glm::ivec3(2, -1, 4));
    EXPECT_NEAR(c.frac.x, 0.6f, 1e-5f);
    EXPECT_FALSE(gpu::cellInside(c.base, 8));
    EXPECT_TRUE(gpu::cellInside(glm::ivec3(6, 0, 6), 8));
    EXPECT_FALSE(gpu::cellInside(glm::ivec3(7, 0, 0), 8));  // corner 8 would be outside
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
    EXPECT_GT(hi - lo, 0.3f);  // it does vary
    // The noise is smooth: small steps in time change it little.
    EXPECT_NEAR(gpu::valueNoise(3.50f, 9), gpu::valueNoise(3.51f, 9), 0.03f);
}

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
    Ellipsoid ball{.name = "ball", .center = glm::vec3(0), .radii = glm::vec3(colliderRadius), .rotationDeg = glm::vec3(0)};
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

}  // namespace

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

}  // namespace

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

// ---- GPU against the CPU reference -------------------------------------------------------------

struct GpuCpuCase {
    uint32_t strands;
    uint32_t vertices;
};

class GpuMatchesCpu : public testing::TestWithParam<GpuCpuCase> {};

namespace {

struct Agreement {
    float max = 0.0f;
    float p90 = 0.0f;  // 90% of vertices agree at least this well
};

Agreement agreement(const SimState& a, const SimState& b)
{
    std::vector<float> d;
    for (size_t i = 0; i < a.positions.size(); ++i)
        d.push_back(glm::length(glm::vec3(a.positions[i]) - glm::vec3(b.positions[i])));
    std::sort(d.begin(), d.end());
    return {d.back(), d[d.size() * 9 / 10]};
}

}  // namespace

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
        std::fprintf(stderr, "%s: max %g p90 %g\n", contacts ? "contacts, 1 step" : "no contacts, 40 steps", double(a.max), double(a.p90));
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
    runGpu(ctx, solver, b.setup, 3, [&](uint32_t n) { return makeStep(b.setup, glm::mat4(1.0f), glm::vec4(0.0f), float(n) / 120.0f); });
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

TEST(SimMath, FixedPointScaleCannotOverflow)
{
    // The worst node sum, every vertex's full weight at the largest splat speed, stays below 2^62.
    for (uint64_t vertices : {1ull, 1000ull, 3200000ull, 100000000ull})
        for (float speed : {0.5f, 20.0f, 2000.0f}) {
            double worst = double(vertices) * std::max(1.0, double(speed)) * double(gridFixedScale(vertices, speed));
            EXPECT_LE(worst, std::ldexp(1.0, 62) * 1.0001);
            EXPECT_GT(worst, std::ldexp(1.0, 61));  // and uses most of the range
        }
}

TEST(GpuSolver, NonFiniteValuesResetStrandsAndAreCounted)
{
    SimSettings s;
    s.wind = glm::vec3(std::numeric_limits<float>::quiet_NaN(), 0.0f, 0.0f);  // poisons every free vertex
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
        EXPECT_NE(what.find("bytes"), std::string::npos) << what;
    }
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

}  // namespace

TEST(RootSampling, AreaWeightedAndDeterministic)
{
    Mesh m = twoTriangles();
    std::vector<RootSample> a = sampleRoots(m, {0, 1}, 20000, false, 7);
    std::vector<RootSample> b = sampleRoots(m, {0, 1}, 20000, false, 7);
    size_t onSmall = 0;
    for (size_t i = 0; i < a.size(); ++i) {
        ASSERT_EQ(a[i].position, b[i].position);  // same seed, same roots
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
    EXPECT_NE(sampleRoots(m, {0, 1}, 10, false, 8)[0].position, a[0].position);  // another seed differs
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
