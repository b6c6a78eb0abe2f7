// renderer/camera.h: an orbit camera around a target point (y up), with Vulkan's clip conventions
// (y down in clip space, depth 0..1), and a default framing of a bounding box.
#pragma once

#include "core/bounds.h"

#include <glm/glm.hpp>

#include <algorithm>

namespace wisp {

struct OrbitCamera {
    glm::vec3 target{0.0f};
    float yawDeg = 25.0f;   // around +y; 0 looks at the face (+z) from the front
    float pitchDeg = 10.0f; // above the target's horizontal plane
    float distance = 1.0f;  // asset units
    float fovYDeg = 30.0f;
    float nearPlane = 0.01f;
    float farPlane = 100.0f;
    float sceneRadius = 1.0f; // the framed bounds' half diagonal: the planes and the zoom follow it
    // An exact camera (a scene's or the command line's eye, target and up): it looks from `eye` at
    // `target`, `up` giving its roll, and `distance` is |eye - target|. Orbiting, zooming or panning
    // it makes it an orbit camera again, from where it was (the roll dropped).
    bool exact = false;
    glm::vec3 eye{0.0f, 0.0f, 1.0f};
    glm::vec3 up{0.0f, 1.0f, 0.0f};

    glm::vec3 position() const;
    glm::mat4 view() const;
    glm::mat4 projection(float aspect) const;

    void orbit(float dYawDeg, float dPitchDeg);
    void zoom(float factor); // distance *= factor, kept within sensible bounds
    void pan(float dxUnits, float dyUnits);
    void leaveExact(); // an exact camera made an orbit camera with the same eye and target

    // Near and far planes around a scene of sceneRadius whose centre is `targetOffset` from the
    // target: near just short of the scene's front (what depth precision depends on is far / near,
    // so it scales with the scene: a head in centimetres is drawn as one in metres), never nearer
    // than kMinNearFraction of the distance; far past its back.
    // (Inline: scene files pose cameras without linking the renderer.)
    void fitPlanes(float targetOffset = 0.0f)
    {
        nearPlane = std::max(distance - kNearReach * sceneRadius - targetOffset, kMinNearFraction * distance);
        farPlane = distance + kFarReach * sceneRadius + targetOffset;
    }
    static constexpr float kNearReach = 3.0f;        // scene radii in front of the centre kept in view
    static constexpr float kFarReach = 8.0f;         // and behind it
    static constexpr float kMinNearFraction = 0.02f; // of the distance

    // The default camera: a three-quarter portrait of `bounds` (y up; a bust or a head), its head and
    // shoulders filling the frame (renderer/camera.cpp). Scene cameras are relative to it.
    static OrbitCamera framing(const Bounds& bounds, float aspect);
    static constexpr float kPortraitSpan = 0.88f;     // of the bounds' height, from the top down
    static constexpr float kPortraitHeadroom = 0.12f; // of the bounds' height, above the top
    static constexpr float kPortraitWidth = 0.9f;     // of the bounds' width, at least
};

} // namespace wisp
