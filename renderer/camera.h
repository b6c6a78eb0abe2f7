// renderer/camera.h: an orbit camera around a target point (y up), with Vulkan's clip conventions
// (y down in clip space, depth 0..1), and a default framing of a bounding box.
#pragma once

#include "core/bounds.h"

#include <glm/glm.hpp>

namespace wisp {

struct OrbitCamera {
    glm::vec3 target{0.0f};
    float yawDeg = 25.0f;    // around +y; 0 looks at the face (+z) from the front
    float pitchDeg = 10.0f;  // above the target's horizontal plane
    float distance = 1.0f;   // asset units
    float fovYDeg = 30.0f;
    float nearPlane = 0.01f;
    float farPlane = 100.0f;

    glm::vec3 position() const;
    glm::mat4 view() const;
    glm::mat4 projection(float aspect) const;

    void orbit(float dYawDeg, float dPitchDeg);
    void zoom(float factor);  // distance *= factor, kept within sensible bounds
    void pan(float dxUnits, float dyUnits);

    // A three-quarter view that fits `bounds` in the frame with a margin.
    static OrbitCamera framing(const Bounds& bounds, float aspect);
};

}  // namespace wisp
