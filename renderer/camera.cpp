// renderer/camera.cpp: orbit camera maths.
#include "renderer/camera.h"

#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>

namespace wisp {

glm::vec3 OrbitCamera::position() const
{
    if (exact)
        return eye;
    float yaw = glm::radians(yawDeg);
    float pitch = glm::radians(pitchDeg);
    glm::vec3 offset(std::sin(yaw) * std::cos(pitch), std::sin(pitch), std::cos(yaw) * std::cos(pitch));
    return target + distance * offset;
}

glm::mat4 OrbitCamera::view() const
{
    return glm::lookAtRH(position(), target, exact ? up : glm::vec3(0.0f, 1.0f, 0.0f));
}

glm::mat4 OrbitCamera::projection(float aspect) const
{
    glm::mat4 p = glm::perspectiveRH_ZO(glm::radians(fovYDeg), aspect, nearPlane, farPlane);
    p[1][1] *= -1.0f; // Vulkan clip space has y pointing down
    return p;
}

void OrbitCamera::leaveExact()
{
    if (!exact)
        return;
    exact = false;
    glm::vec3 offset = eye - target;
    distance = std::max(glm::length(offset), 1e-6f);
    pitchDeg = std::clamp(glm::degrees(std::asin(std::clamp(offset.y / distance, -1.0f, 1.0f))), -85.0f, 85.0f);
    yawDeg = glm::degrees(std::atan2(offset.x, offset.z));
}

void OrbitCamera::orbit(float dYawDeg, float dPitchDeg)
{
    leaveExact();
    yawDeg = std::fmod(yawDeg + dYawDeg, 360.0f);
    pitchDeg = std::clamp(pitchDeg + dPitchDeg, -85.0f, 85.0f);
}

void OrbitCamera::zoom(float factor)
{
    leaveExact();
    distance = std::clamp(distance * factor, 0.05f * sceneRadius, 50.0f * sceneRadius);
    fitPlanes();
}

void OrbitCamera::pan(float dxUnits, float dyUnits)
{
    leaveExact();
    glm::mat4 v = view();
    glm::vec3 right(v[0][0], v[1][0], v[2][0]);
    glm::vec3 screenUp(v[0][1], v[1][1], v[2][1]);
    target += right * dxUnits + screenUp * dyUnits;
}

OrbitCamera OrbitCamera::framing(const Bounds& bounds, float aspect)
{
    OrbitCamera c;
    glm::vec3 size = bounds.size();
    float radius = 0.5f * glm::length(size);
    // A head-and-shoulders portrait: the frame's height spans the top kPortraitSpan of the bounds'
    // height (a bust's head, neck and the top of its shoulders) plus kPortraitHeadroom above it, for
    // the hair over the crown; its width at least kPortraitWidth of the bounds' (the shoulders), at
    // the target's depth.
    float top = bounds.max.y + kPortraitHeadroom * size.y;
    float spanY = (kPortraitSpan + kPortraitHeadroom) * size.y;
    c.target = glm::vec3(bounds.center().x, top - 0.5f * spanY, bounds.center().z);
    float tanHalfFov = std::tan(glm::radians(c.fovYDeg) * 0.5f);
    float fitVertical = 0.5f * spanY / tanHalfFov;
    float fitHorizontal = 0.5f * kPortraitWidth * std::max(size.x, size.z) / (tanHalfFov * aspect);
    c.distance = std::max({fitVertical, fitHorizontal, 1e-6f});
    c.sceneRadius = std::max(radius, 1e-6f);
    // The planes as poseCamera fits them for an unmoved target (so a scene's default camera draws
    // the same picture); their reach, radii of the scene, covers the target's offset from its centre.
    c.fitPlanes();
    return c;
}

} // namespace wisp
