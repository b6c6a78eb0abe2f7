// tests/test_scene_timeline.cpp: the scene timeline (app/scene/scene_timeline.h) without a GPU: its
// values by hand (linear and smoothstep, held before the first and after the last key, each channel
// between its own keys, looping), and the posed camera.
#include "app/scene/scene_timeline.h"

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include <cmath>

using namespace wisp;

namespace {

SceneKey keyAt(double time)
{
    SceneKey k;
    k.time = time;
    return k;
}

} // namespace

TEST(SceneTimeline, LinearValuesByHand)
{
    SceneState base;
    base.sphere = glm::vec4(1.0f, 2.0f, 3.0f, 0.5f);
    base.light.azimuthDeg = 7.0f;
    SceneKey a = keyAt(1.0), b = keyAt(3.0);
    a.headYawDeg = 10.0f;
    b.headYawDeg = 50.0f;
    a.wind = glm::vec3(0.0f);
    b.wind = glm::vec3(4.0f, 0.0f, -8.0f);
    b.cameraYawDeg = 350.0f; // alone: held at every time
    SceneTimeline t({a, b}, SceneInterpolation::Linear, base);
    EXPECT_FLOAT_EQ(t.at(0.0).headYawDeg, 10.0f); // before the first key: held
    EXPECT_FLOAT_EQ(t.at(1.0).headYawDeg, 10.0f);
    EXPECT_FLOAT_EQ(t.at(1.5).headYawDeg, 20.0f); // a quarter of the way
    EXPECT_FLOAT_EQ(t.at(2.0).headYawDeg, 30.0f);
    EXPECT_FLOAT_EQ(t.at(3.0).headYawDeg, 50.0f);
    EXPECT_FLOAT_EQ(t.at(99.0).headYawDeg, 50.0f); // after the last: held
    glm::vec3 w = t.at(2.5).wind;
    EXPECT_FLOAT_EQ(w.x, 3.0f);
    EXPECT_FLOAT_EQ(w.z, -6.0f);
    EXPECT_FLOAT_EQ(*t.at(0.0).camera.yawDeg, 350.0f);
    EXPECT_FALSE(t.at(2.0).camera.pitchDeg.has_value()); // no key: the framing's
    EXPECT_FALSE(t.at(2.0).camera.target.has_value());
    EXPECT_EQ(t.at(2.0).sphere, base.sphere); // no key: the base
    EXPECT_FLOAT_EQ(t.at(2.0).light.azimuthDeg, 7.0f);
    EXPECT_EQ(t.at(2.0).light.color, base.light.color);
}

TEST(SceneTimeline, SmoothstepEasesBetweenKeys)
{
    SceneKey a = keyAt(1.0), b = keyAt(3.0);
    a.lightElevationDeg = 10.0f;
    b.lightElevationDeg = 50.0f;
    SceneTimeline t({a, b}, SceneInterpolation::Smooth, SceneState{});
    // u = 0.25: 3u² - 2u³ = 0.15625; u = 0.5: 0.5; u = 0.75: 0.84375.
    EXPECT_FLOAT_EQ(t.at(1.5).light.elevationDeg, 10.0f + 40.0f * 0.15625f);
    EXPECT_FLOAT_EQ(t.at(2.0).light.elevationDeg, 30.0f);
    EXPECT_FLOAT_EQ(t.at(2.5).light.elevationDeg, 10.0f + 40.0f * 0.84375f);
    // At rest at the keys: the first step away moves far less than a linear one would.
    float nearStart = t.at(1.01).light.elevationDeg - 10.0f;
    EXPECT_GT(nearStart, 0.0f);
    EXPECT_LT(nearStart, 0.1f * 40.0f * 0.005f);
}

TEST(SceneTimeline, EachChannelMovesBetweenItsOwnKeys)
{
    SceneKey a = keyAt(0.0), b = keyAt(1.0), c = keyAt(2.0);
    a.sphere = glm::vec4(0.0f, 0.0f, 0.0f, 0.1f);
    c.sphere = glm::vec4(2.0f, 0.0f, 0.0f, 0.3f);
    b.wind = glm::vec3(5.0f, 0.0f, 0.0f); // sets the wind only
    a.cameraDistance = 1.0f;
    c.cameraDistance = 2.0f;
    SceneTimeline t({a, b, c}, SceneInterpolation::Linear, SceneState{});
    SceneState s = t.at(1.0);
    EXPECT_FLOAT_EQ(s.sphere.x, 1.0f); // halfway from a to c, through b
    EXPECT_FLOAT_EQ(s.sphere.w, 0.2f);
    EXPECT_FLOAT_EQ(*s.camera.distance, 1.5f);
    EXPECT_EQ(t.at(0.0).wind, glm::vec3(5.0f, 0.0f, 0.0f)); // its only key, held both ways
    EXPECT_EQ(t.at(2.0).wind, glm::vec3(5.0f, 0.0f, 0.0f));
}

TEST(SceneTimeline, PosedCameraMovesTheFraming)
{
    Bounds head{glm::vec3(-0.2f, -0.1f, -0.1f), glm::vec3(0.2f, 0.3f, 0.1f)};
    OrbitCamera framing = OrbitCamera::framing(head, 1.5f);
    OrbitCamera same = poseCamera(framing, CameraPose{});
    EXPECT_EQ(same.yawDeg, framing.yawDeg);
    EXPECT_EQ(same.distance, framing.distance);
    EXPECT_EQ(same.target, framing.target);
    EXPECT_EQ(same.nearPlane, framing.nearPlane); // the same projection: the same picture, byte for byte
    EXPECT_EQ(same.farPlane, framing.farPlane);
    CameraPose pose{.yawDeg = 180.0f, .pitchDeg = 30.0f, .distance = 3.0f, .target = glm::vec3(0.0f, 0.2f, 0.0f)};
    OrbitCamera c = poseCamera(framing, pose);
    EXPECT_EQ(c.yawDeg, 180.0f);
    EXPECT_EQ(c.pitchDeg, 30.0f);
    EXPECT_FLOAT_EQ(c.distance, 3.0f * framing.distance);
    EXPECT_EQ(c.target, glm::vec3(0.0f, 0.2f, 0.0f));
    // The whole head stays between the planes.
    float radius = 0.5f * glm::length(head.size());
    EXPECT_LT(c.nearPlane, c.distance - radius - glm::length(c.target - head.center()));
    EXPECT_GT(c.farPlane, c.distance + radius + glm::length(c.target - head.center()));
}

TEST(SceneTimeline, ALoopingScenePlaysItsKeysAgain)
{
    SceneKey a = keyAt(0.0), b = keyAt(2.0);
    a.headYawDeg = 0.0f;
    b.headYawDeg = 40.0f;
    SceneTimeline once({a, b}, SceneInterpolation::Linear, SceneState{});
    SceneTimeline looped({a, b}, SceneInterpolation::Linear, SceneState{}, 4.0); // 2 s of keys, 2 s held
    for (double t : {0.0, 0.5, 1.5, 3.0})
        EXPECT_FLOAT_EQ(looped.at(t).headYawDeg, once.at(t).headYawDeg) << t;
    EXPECT_FLOAT_EQ(looped.at(4.5).headYawDeg, 10.0f); // the second time round
    EXPECT_FLOAT_EQ(looped.at(4000.5).headYawDeg, 10.0f);
    EXPECT_FLOAT_EQ(once.at(4.5).headYawDeg, 40.0f); // without the loop: held
}

// An eye: the exact camera, looking from it at the target with its up and field of view; the
// timeline carries the eye, the up and the field of view between keys like any channel.
TEST(SceneTimeline, AnEyeGivesTheExactCamera)
{
    Bounds head{glm::vec3(-0.2f, -0.1f, -0.1f), glm::vec3(0.2f, 0.3f, 0.1f)};
    OrbitCamera framing = OrbitCamera::framing(head, 1.5f);
    CameraPose pose{.target = glm::vec3(0.0f, 0.1f, 0.0f),
                    .eye = glm::vec3(0.3f, 0.2f, -1.2f),
                    .up = glm::vec3(0.2f, 1.0f, 0.0f),
                    .fovDeg = 20.0f};
    OrbitCamera c = poseCamera(framing, pose);
    EXPECT_TRUE(c.exact);
    EXPECT_EQ(c.position(), glm::vec3(0.3f, 0.2f, -1.2f));
    glm::mat4 want =
        glm::lookAtRH(glm::vec3(0.3f, 0.2f, -1.2f), glm::vec3(0.0f, 0.1f, 0.0f), glm::vec3(0.2f, 1.0f, 0.0f));
    EXPECT_EQ(c.view(), want);
    EXPECT_EQ(c.fovYDeg, 20.0f);
    EXPECT_NEAR(1.0f / std::abs(c.projection(1.5f)[1][1]), std::tan(glm::radians(10.0f)), 1e-6f);
    EXPECT_FLOAT_EQ(c.distance, glm::length(glm::vec3(0.3f, 0.1f, -1.2f)));
    // The whole head between the planes.
    float radius = 0.5f * glm::length(head.size());
    float far = glm::length(c.eye - head.center()) + radius;
    EXPECT_LT(c.nearPlane, glm::length(c.eye - head.center()) - radius);
    EXPECT_GT(c.farPlane, far);
    // Saved and posed again: the same camera.
    OrbitCamera again = poseCamera(framing, cameraPoseOf(framing, c));
    EXPECT_EQ(again.view(), c.view());
    EXPECT_EQ(again.fovYDeg, 20.0f);
    // Orbiting it makes it an orbit camera from where it was.
    OrbitCamera orbiting = c;
    orbiting.orbit(0.0f, 0.0f);
    EXPECT_FALSE(orbiting.exact);
    EXPECT_LT(glm::length(orbiting.position() - c.eye), 1e-5f);
    // Between two keys the eye moves like any channel.
    SceneKey a, b;
    a.time = 0.0, b.time = 2.0;
    a.cameraEye = glm::vec3(0.0f, 0.0f, 1.0f), b.cameraEye = glm::vec3(0.0f, 0.0f, 3.0f);
    a.cameraFovDeg = 20.0f, b.cameraFovDeg = 40.0f;
    SceneTimeline t({a, b}, SceneInterpolation::Linear, SceneState{});
    EXPECT_EQ(t.at(1.0).camera.eye, glm::vec3(0.0f, 0.0f, 2.0f));
    EXPECT_EQ(t.at(1.0).camera.fovDeg, 30.0f);
    EXPECT_FALSE(t.at(1.0).camera.up.has_value());
}
