// app/scene/scene_timeline.cpp: the keys as functions of time (see the header), the camera posed
// from the default framing, and the head's turn.
#include "app/scene/scene_timeline.h"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>

namespace wisp {

OrbitCamera poseCamera(const OrbitCamera& framing, const CameraPose& pose)
{
    OrbitCamera c = framing;
    c.yawDeg = pose.yawDeg.value_or(framing.yawDeg);
    c.pitchDeg = pose.pitchDeg.value_or(framing.pitchDeg);
    c.distance = framing.distance * pose.distance.value_or(1.0f);
    c.target = pose.target.value_or(framing.target);
    c.fovYDeg = pose.fovDeg.value_or(framing.fovYDeg);
    if (pose.eye) {
        c.exact = true;
        c.eye = *pose.eye;
        c.up = pose.up.value_or(glm::vec3(0.0f, 1.0f, 0.0f));
        c.distance = std::max(glm::length(c.eye - c.target), 1e-6f);
    }
    c.fitPlanes(glm::length(c.target - framing.target));
    return c;
}

CameraPose cameraPoseOf(const OrbitCamera& framing, const OrbitCamera& camera)
{
    auto clamp = [](float v, const Range& r) { return std::clamp(v, float(r.min), float(r.max)); };
    return {.yawDeg = clamp(camera.yawDeg, kSceneCameraYawRange),
            .pitchDeg = clamp(camera.pitchDeg, kSceneCameraPitchRange),
            .distance = clamp(camera.distance / std::max(framing.distance, 1e-12f), kSceneCameraDistanceRange),
            .target = camera.target,
            .eye = camera.exact ? std::optional<glm::vec3>(camera.eye) : std::nullopt,
            .up = camera.exact ? std::optional<glm::vec3>(camera.up) : std::nullopt,
            .fovDeg = camera.fovYDeg != framing.fovYDeg ? std::optional<float>(camera.fovYDeg) : std::nullopt};
}

SceneKey sceneKey(double time, const SceneState& state)
{
    SceneKey k;
    k.time = time;
    k.cameraYawDeg = state.camera.yawDeg;
    k.cameraPitchDeg = state.camera.pitchDeg;
    k.cameraDistance = state.camera.distance;
    k.cameraTarget = state.camera.target;
    k.cameraEye = state.camera.eye;
    k.cameraUp = state.camera.up;
    k.cameraFovDeg = state.camera.fovDeg;
    k.sphere = state.sphere;
    k.lightAzimuthDeg = state.light.azimuthDeg;
    k.lightElevationDeg = state.light.elevationDeg;
    k.lightIntensity = state.light.intensity;
    k.wind = state.wind;
    k.headYawDeg = state.headYawDeg;
    return k;
}

glm::mat4 headYawTransform(const Bounds& head, float yawDeg)
{
    glm::vec3 centre = head.center();
    glm::mat4 m = glm::translate(glm::mat4(1.0f), centre);
    m = glm::rotate(m, glm::radians(yawDeg), glm::vec3(0.0f, 1.0f, 0.0f));
    return glm::translate(m, -centre);
}

SceneTimeline::SceneTimeline(const std::vector<SceneKey>& keys, SceneInterpolation interpolation,
                             const SceneState& base, double loopPeriod)
    : interpolation_(interpolation), base_(base), loopPeriod_(loopPeriod)
{
    for (const SceneKey& k : keys) {
        if (k.cameraYawDeg)
            cameraYaw_.emplace_back(k.time, *k.cameraYawDeg);
        if (k.cameraPitchDeg)
            cameraPitch_.emplace_back(k.time, *k.cameraPitchDeg);
        if (k.cameraDistance)
            cameraDistance_.emplace_back(k.time, *k.cameraDistance);
        if (k.cameraTarget)
            cameraTarget_.emplace_back(k.time, *k.cameraTarget);
        if (k.cameraEye)
            cameraEye_.emplace_back(k.time, *k.cameraEye);
        if (k.cameraUp)
            cameraUp_.emplace_back(k.time, *k.cameraUp);
        if (k.cameraFovDeg)
            cameraFov_.emplace_back(k.time, *k.cameraFovDeg);
        if (k.sphere)
            sphere_.emplace_back(k.time, *k.sphere);
        if (k.lightAzimuthDeg)
            lightAzimuth_.emplace_back(k.time, *k.lightAzimuthDeg);
        if (k.lightElevationDeg)
            lightElevation_.emplace_back(k.time, *k.lightElevationDeg);
        if (k.lightIntensity)
            lightIntensity_.emplace_back(k.time, *k.lightIntensity);
        if (k.wind)
            wind_.emplace_back(k.time, *k.wind);
        if (k.headYawDeg)
            headYaw_.emplace_back(k.time, *k.headYawDeg);
    }
}

template <typename T> T SceneTimeline::sample(const Track<T>& track, double t, const T& fallback) const
{
    if (track.empty())
        return fallback;
    if (t <= track.front().first)
        return track.front().second;
    if (t >= track.back().first)
        return track.back().second;
    auto next =
        std::upper_bound(track.begin(), track.end(), t, [](double time, const auto& key) { return time < key.first; });
    auto previous = next - 1;
    double u = (t - previous->first) / (next->first - previous->first);
    if (interpolation_ == SceneInterpolation::Smooth)
        u = u * u * (3.0 - 2.0 * u);
    return previous->second + (next->second - previous->second) * float(u);
}

SceneState SceneTimeline::at(double seconds) const
{
    if (loopPeriod_ > 0.0)
        seconds = std::fmod(std::max(seconds, 0.0), loopPeriod_);
    SceneState s = base_;
    auto optional = [&](const auto& track, auto fallback) -> decltype(fallback) {
        if (track.empty())
            return fallback;
        return sample(track, seconds, track.front().second);
    };
    s.camera.yawDeg = optional(cameraYaw_, base_.camera.yawDeg);
    s.camera.pitchDeg = optional(cameraPitch_, base_.camera.pitchDeg);
    s.camera.distance = optional(cameraDistance_, base_.camera.distance);
    s.camera.target = optional(cameraTarget_, base_.camera.target);
    s.camera.eye = optional(cameraEye_, base_.camera.eye);
    s.camera.up = optional(cameraUp_, base_.camera.up);
    s.camera.fovDeg = optional(cameraFov_, base_.camera.fovDeg);
    s.sphere = sample(sphere_, seconds, base_.sphere);
    s.light.azimuthDeg = sample(lightAzimuth_, seconds, base_.light.azimuthDeg);
    s.light.elevationDeg = sample(lightElevation_, seconds, base_.light.elevationDeg);
    s.light.intensity = sample(lightIntensity_, seconds, base_.light.intensity);
    s.wind = sample(wind_, seconds, base_.wind);
    s.headYawDeg = sample(headYaw_, seconds, base_.headYawDeg);
    return s;
}

} // namespace wisp
