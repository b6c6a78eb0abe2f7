// tests/test_physics_scenes.cpp: the physics' invariants as numbers on real scenes, run on the
// GPU (lavapipe in CI) through the same loop as `wisp simulate`: stretch, penetration, root drift
// and resets over 1,000 steps; coming to rest; the sphere pushing hair aside and the hair
// recovering; a head turn followed with inertia; a styled groom keeping its shape.
#include "app/session/simulate.h"
#include "physics/groomed_head.h"
#include "test_support.h"

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

using namespace wisp;

namespace {

GroomedHead defaultScene(uint32_t guides)
{
    GrowthSettings g;
    g.guides = guides;
    return buildGrownHead(defaultHeadPath(), g);
}

struct Deviation {
    float mean = 0.0f;
    float max = 0.0f;
};

// How far free vertices of `a` are from `b`.
Deviation deviation(const SimState& a, const std::vector<glm::vec4>& b)
{
    Deviation d;
    size_t n = 0;
    for (size_t i = 0; i < a.positions.size(); ++i) {
        if (a.positions[i].w == 0.0f)
            continue;
        float x = glm::length(glm::vec3(a.positions[i]) - glm::vec3(b[i]));
        d.mean += x;
        d.max = std::max(d.max, x);
        ++n;
    }
    d.mean /= float(std::max<size_t>(n, 1));
    return d;
}

} // namespace

TEST(PhysicsScenes, ThousandStepsWithGravityAndWindKeepTheInvariants)
{
    GroomedHead scene = defaultScene(150);
    SimSettings sim;
    sim.wind = glm::vec3(3.0f, 0.0f, 1.0f);
    vk::Context ctx(test::validatedOptions());
    SimulationReport r = simulateHeadless(ctx, scene, sim, 1000, {}, 100);
    float diagonal = scene.head.mesh.bounds().diagonal();
    std::fprintf(stderr, "stretch %g penetration %g drift %g resets %u\n", double(r.last.maxStretch),
                 double(r.last.maxPenetration / diagonal), double(r.last.rootDrift), r.nonfiniteResets);
    EXPECT_LT(r.last.maxStretch, 1e-4f);
    EXPECT_LT(r.last.maxPenetration / diagonal, 0.01f);
    EXPECT_LT(r.last.rootDrift, 1e-6f * diagonal); // roots are placed by the head transform exactly
    EXPECT_EQ(r.nonfiniteResets, 0u);
    // The wind moved the hair: it is still in motion at the end.
    EXPECT_GT(r.last.kineticEnergy, 1e-3f);
    EXPECT_EQ(ctx.validationMessages(), 0u);
}

TEST(PhysicsScenes, HairAtRestUnderGravityComesToRest)
{
    GroomedHead scene = defaultScene(150);
    vk::Context ctx(test::validatedOptions());
    SimulationReport r = simulateHeadless(ctx, scene, SimSettings{}, 1500, {}, 50);
    ASSERT_GE(r.energy.size(), 10u);
    float first = r.energy.front().second, last = r.energy.back().second;
    std::fprintf(stderr, "energy first %g last %g\n", double(first), double(last));
    EXPECT_GT(first, 0.0f);
    EXPECT_LT(last, 1e-4f * first);
    // It settles for good: the last third of the run stays tiny.
    for (size_t i = r.energy.size() * 2 / 3; i < r.energy.size(); ++i)
        EXPECT_LT(r.energy[i].second, 1e-3f * first) << "step " << r.energy[i].first;
    EXPECT_EQ(ctx.validationMessages(), 0u);
}

TEST(PhysicsScenes, SpherePushedThroughTheHairDisplacesItAndItRecovers)
{
    GroomedHead scene = defaultScene(150);
    vk::Context ctx(test::validatedOptions());
    SimSettings sim;
    // A 5 cm sphere sweeps across the back of the head, through the bob's hair, from t = 3 s to 4 s,
    // then is gone.
    Motion motion;
    motion.sphere = [](float t) {
        if (t < 3.0f || t > 4.0f)
            return glm::vec4(0.0f);
        float u = t - 3.0f;
        return glm::vec4(-0.2f + 0.4f * u, 0.12f, -0.14f, 0.05f);
    };
    SimulationReport still = simulateHeadless(ctx, scene, sim, 900, {}, 900);
    SimulationReport during = simulateHeadless(ctx, scene, sim, 420, motion, 420); // t = 3.5 s
    SimulationReport after = simulateHeadless(ctx, scene, sim, 900, motion, 900);  // t = 7.5 s
    SimulationReport stillMid = simulateHeadless(ctx, scene, sim, 420, {}, 420);
    Deviation pushed = deviation(during.state, stillMid.state.positions);
    Deviation recovered = deviation(after.state, still.state.positions);
    std::fprintf(stderr, "pushed mean %g max %g; recovered mean %g max %g\n", double(pushed.mean), double(pushed.max),
                 double(recovered.mean), double(recovered.max));
    EXPECT_GT(pushed.max, 0.02f);                 // some hair moved at least 2 cm out of the sphere's way
    EXPECT_LT(during.last.maxPenetration, 0.01f); // and none stayed inside it (or the head)
    EXPECT_LT(recovered.mean, 0.25f * pushed.mean);
    EXPECT_LT(recovered.max, 0.5f * pushed.max);
    EXPECT_EQ(after.nonfiniteResets, 0u);
    EXPECT_EQ(ctx.validationMessages(), 0u);
}

TEST(PhysicsScenes, HairFollowsATurningHeadWithInertia)
{
    GroomedHead scene = defaultScene(120);
    vk::Context ctx(test::validatedOptions());
    SimSettings sim;
    // The head turns 40 degrees about y between t = 2 s and 2.3 s, then holds.
    auto turn = [](float t) {
        float u = glm::clamp((t - 2.0f) / 0.3f, 0.0f, 1.0f);
        float angle = glm::radians(40.0f) * u * u * (3.0f - 2.0f * u);
        return glm::rotate(glm::mat4(1.0f), angle, glm::vec3(0, 1, 0));
    };
    Motion motion;
    motion.head = turn;
    SimulationReport before = simulateHeadless(ctx, scene, sim, 240, {}, 240);        // settled, t = 2 s
    SimulationReport justAfter = simulateHeadless(ctx, scene, sim, 280, motion, 280); // t = 2.33 s
    SimulationReport settled = simulateHeadless(ctx, scene, sim, 900, motion, 900);   // t = 7.5 s
    // Where the settled hair would be if it turned rigidly with the head.
    glm::mat4 R = turn(10.0f);
    std::vector<glm::vec4> rigid;
    for (const glm::vec4& p : before.state.positions)
        rigid.push_back(R * glm::vec4(glm::vec3(p), 1.0f));
    Deviation lag = deviation(justAfter.state, rigid);
    Deviation rest = deviation(settled.state, rigid);
    std::fprintf(stderr, "lag mean %g, settled mean %g, drift %g\n", double(lag.mean), double(rest.mean),
                 double(settled.last.rootDrift));
    EXPECT_LT(justAfter.last.rootDrift, 1e-5f); // roots turn with the head exactly
    EXPECT_LT(settled.last.rootDrift, 1e-5f);
    EXPECT_GT(lag.mean, 3.0f * rest.mean); // the hair lags behind the turn ...
    EXPECT_LT(rest.mean, 0.01f);           // ... and catches up once the head holds still
    EXPECT_EQ(ctx.validationMessages(), 0u);
}

TEST(PhysicsScenes, StyledGroomKeepsItsShapeWithShapeStiffness)
{
    WISP_REQUIRE_DATA(hair, "sintel-lite/sintel_hair_228x32.tfx");
    WISP_REQUIRE_DATA(head, "sintel-lite/sintel_lite.obj");
    HairPartSource styled{.file = hair, .placement = std::nullopt, .settings = styledPartDefaults()};
    HairPartSource limp = styled;
    limp.settings.globalStiffness = 0.0f;
    limp.settings.localStiffness = 0.0f;
    vk::Context ctx(test::validatedOptions());
    float meanLength = 0.0f;
    Deviation kept, fell;
    for (int pass = 0; pass < 2; ++pass) {
        GroomedHead scene = buildLoadedHead(head, {pass == 0 ? styled : limp}, 16);
        meanLength = 0.0f;
        for (size_t s = 0; s < scene.strands.strandCount(); ++s)
            for (uint32_t i = 1; i < 16; ++i)
                meanLength += glm::length(scene.strands.rest[s * 16 + i] - scene.strands.rest[s * 16 + i - 1]);
        meanLength /= float(scene.strands.strandCount());
        SimulationReport r = simulateHeadless(ctx, scene, SimSettings{}, 300, {}, 300);
        std::vector<glm::vec4> rest;
        for (const glm::vec3& p : scene.strands.rest)
            rest.emplace_back(p, 1.0f);
        (pass == 0 ? kept : fell) = deviation(r.state, rest);
        EXPECT_EQ(r.nonfiniteResets, 0u);
    }
    std::fprintf(stderr, "strand length %g; styled mean %g max %g; limp mean %g max %g\n", double(meanLength),
                 double(kept.mean), double(kept.max), double(fell.mean), double(fell.max));
    EXPECT_LT(kept.mean, 0.05f * meanLength); // within 5% of a strand's length on average
    EXPECT_LT(kept.mean, 0.3f * fell.mean);   // and much closer than the same groom without stiffness
    EXPECT_EQ(ctx.validationMessages(), 0u);
}
