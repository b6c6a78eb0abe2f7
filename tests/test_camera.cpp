// tests/test_camera.cpp: the orbit camera (renderer/camera.h) without a GPU: its near and far planes
// scale with the scene and keep the depth precise.
#include "renderer/camera.h"

#include <gtest/gtest.h>

using namespace wisp;

TEST(OrbitCamera, ThePlanesScaleWithTheScene)
{
    // Depth precision depends on far / near: the planes of a head in centimetres are those of the
    // same head in metres times 100, and a step of 1e-4 of the head's size at its front is many
    // steps of 32-bit float depth.
    Bounds metres{glm::vec3(-0.2f, -0.1f, -0.1f), glm::vec3(0.2f, 0.3f, 0.1f)};
    Bounds centimetres{100.0f * metres.min, 100.0f * metres.max};
    OrbitCamera m = OrbitCamera::framing(metres, 1.5f);
    OrbitCamera c = OrbitCamera::framing(centimetres, 1.5f);
    EXPECT_NEAR(c.nearPlane / m.nearPlane, 100.0f, 0.01f);
    EXPECT_NEAR(c.farPlane / m.farPlane, 100.0f, 0.01f);
    EXPECT_LT(m.farPlane / m.nearPlane, 1000.0f);
    for (const OrbitCamera& cam : {m, c}) {
        float radius = cam.sceneRadius;
        glm::mat4 p = cam.projection(1.5f);
        auto depth = [&](float z) { // z: distance in front of the camera
            glm::vec4 clip = p * glm::vec4(0.0f, 0.0f, -z, 1.0f);
            return clip.z / clip.w;
        };
        float front = cam.distance - radius;
        float step = depth(front + 1e-4f * radius) - depth(front);
        EXPECT_GT(step, 16.0f * 6e-8f) << "a 1e-4 step spans at least 16 float depth steps near 1";
        EXPECT_GT(depth(front), 0.0f);
        EXPECT_LT(depth(cam.distance + radius), 1.0f);
    }
    // Zooming keeps the planes around the scene.
    OrbitCamera z = m;
    z.zoom(0.1f);
    EXPECT_LT(z.nearPlane, z.distance);
    EXPECT_GT(z.nearPlane, 0.0f);
    EXPECT_GT(z.farPlane, z.distance + m.sceneRadius);
}
