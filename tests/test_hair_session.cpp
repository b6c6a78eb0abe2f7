// tests/test_hair_session.cpp: the hair session every front end runs: steps posed by a scene's
// timeline at their end, the solver rebuilt only when what it packs changes, and its kernels
// reloaded (F5). Its clock is tested in test_sim_cpu.cpp.
#include "app/session/hair_session.h"
#include "app/session/headless.h"
#include "test_support.h"

#include <gtest/gtest.h>

using namespace wisp;

namespace {

GroomedHead smallScene(uint32_t guides)
{
    GrowthSettings g;
    g.guides = guides;
    return buildGrownHead(defaultHeadPath(), g);
}

} // namespace

TEST(HairSession, StepsArePosedByTheTimelineAtTheirEnd)
{
    vk::Context ctx(test::validatedOptions());
    SceneKey a, b;
    a.time = 0.0;
    a.headYawDeg = 0.0f;
    a.wind = glm::vec3(0.0f);
    b.time = 1.0;
    b.headYawDeg = 40.0f;
    b.wind = glm::vec3(10.0f, 0.0f, 0.0f);
    SceneTimeline timeline({a, b}, SceneInterpolation::Linear, SceneState{});
    HairSession session(ctx, smallScene(8), SimSettings{}, timeline);
    std::vector<gpu::SimStep> steps = session.nextSteps(120); // one second at 120 Hz
    ASSERT_EQ(steps.size(), 120u);
    EXPECT_EQ(session.clock().stepsDone(), 120u);
    EXPECT_FLOAT_EQ(steps[0].time, 0.0f);
    EXPECT_FLOAT_EQ(steps[119].time, 119.0f / 120.0f);
    // The last step ends at 1 s: the head turned 40 degrees, the wind at 10 m/s² (in head units).
    glm::mat4 expected = headYawTransform(session.headBounds(), 40.0f);
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r)
            EXPECT_NEAR(steps[119].headTransform[c][r], expected[c][r], 1e-6f);
    EXPECT_NEAR(steps[119].wind.x, 10.0f * session.scene().unitsPerMetre, 1e-4f);
    EXPECT_NEAR(steps[0].wind.x, 10.0f / 120.0f * session.scene().unitsPerMetre, 1e-4f); // the first ends at 1/120 s
    EXPECT_EQ(ctx.validationMessages(), 0u);
}

// A profile steps its warm-up's frames and, unless still, its timed frames (each frame the next
// one's steps beside its drawing); a still profile's timed frames take none.
TEST(HairSession, AStillProfileStepsOnlyInItsWarmUp)
{
    vk::Context ctx(test::validatedOptions());
    RenderSettings s;
    s.width = 64;
    s.height = 48;
    s.shadows.mapSize = 256;
    s.strands.strandsPerGuide = 2;
    for (bool timedSteps : {true, false}) {
        HairSession session(ctx, smallScene(8), SimSettings{}, stillTimeline(glm::vec4(0.0f), glm::vec3(0.0f)));
        uint64_t perFrame = session.clock().stepsPerFrame(30.0f);
        std::vector<PassTiming> t = profileFrames(ctx, session, s, 30.0f, 2, 3, nullptr, nullptr, timedSteps);
        EXPECT_EQ(session.clock().stepsDone(), perFrame * (timedSteps ? 5u : 2u)) << timedSteps;
        EXPECT_FALSE(t.empty());
    }
    EXPECT_EQ(ctx.validationMessages(), 0u);
}

TEST(HairSession, TheSolverIsRebuiltOnlyWhenWhatItPacksChanges)
{
    vk::Context ctx(test::validatedOptions());
    SimSettings sim;
    HairSession session(ctx, smallScene(16), sim, stillTimeline(glm::vec4(0.0f), glm::vec3(0.0f)));
    GpuSolver* before = session.solver();
    sim.wind = glm::vec3(2.0f, 0.0f, 0.0f);
    sim.windFrequency = 1.5f;
    EXPECT_FALSE(session.setSim(sim, glm::mat4(1.0f))); // the wind rides in the steps
    EXPECT_EQ(session.solver(), before);
    EXPECT_FLOAT_EQ(session.nextSteps(1).front().windFrequency, 1.5f);
    sim.gridFriction = 0.5f;
    EXPECT_TRUE(session.setSim(sim, glm::mat4(1.0f)));
    sim.globalStiffness = 0.3f; // every part's stiffness is packed too
    EXPECT_TRUE(session.setSim(sim, glm::mat4(1.0f)));
    EXPECT_FLOAT_EQ(session.scene().strands.parts[0].globalStiffness, 0.3f);
    EXPECT_EQ(ctx.validationMessages(), 0u);
}

TEST(HairSession, ReloadedKernelsSimulateAsBefore)
{
    // F5 makes the solver's pipelines again from the SPIR-V on disk; with unchanged shaders the
    // hair moves exactly as it did.
    vk::Context ctx(test::validatedOptions());
    SimSettings sim;
    sim.wind = glm::vec3(3.0f, 0.0f, 1.0f);
    SceneTimeline still = stillTimeline(glm::vec4(0.0f), sim.wind);
    HairSession plain(ctx, smallScene(40), sim, still), reloaded(ctx, smallScene(40), sim, still);
    reloaded.reloadShaders();
    RenderSettings s;
    s.width = 96;
    s.height = 72;
    s.shadows.mapSize = 256;
    s.strands.strandsPerGuide = 4;
    Picture a = renderPicture(ctx, plain, s, 6, 30.0f);
    Picture b = renderPicture(ctx, reloaded, s, 6, 30.0f);
    EXPECT_TRUE(a.rgba == b.rgba);
    EXPECT_EQ(ctx.validationMessages(), 0u);
}
