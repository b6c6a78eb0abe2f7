// app/scene/scene_timeline.h: a scene's keyframes over time: the camera, the sphere, the light, the
// wind and the head's turn, each key setting any of them, and SceneTimeline, which evaluates them at
// any time (linearly or by smoothstep, looping or not). The scene file (app/scene/scene_file.h)
// reads and writes the keys; the hair session poses every frame by the timeline.
#pragma once

#include "core/bounds.h"
#include "core/range.h"
#include "renderer/camera.h"
#include "renderer/settings.h"

#include <glm/glm.hpp>

#include <optional>
#include <utility>
#include <vector>

namespace wisp {

// Allowed values of the channels that are not settings (the light's and the wind's are the
// settings table's light_azimuth, light_elevation, light_intensity and wind; positions and radii
// are kPositionRange and kRadiusRange of app/settings/hair_source.h).
inline constexpr Range kSceneTimeRange{0.0, 3600.0};          // seconds
inline constexpr Range kSceneCameraYawRange{-3600.0, 3600.0}; // degrees (no wrapping: 0 -> 360 is one turn)
inline constexpr Range kSceneCameraPitchRange{-85.0, 85.0};   // degrees, OrbitCamera's limits
inline constexpr Range kSceneCameraDistanceRange{0.1, 10.0};  // times the default framing's distance
inline constexpr Range kSceneHeadYawRange{-80.0, 80.0};       // degrees, as far as the window turns it
inline constexpr Range kSceneCameraFovRange{1.0, 170.0};      // degrees, the vertical field of view

// How a channel moves between two keys that set it: straight (linear) or easing out of one key
// and into the next (smoothstep: every key is a moment of rest).
enum class SceneInterpolation { Linear, Smooth };

// One keyframe: its time and whichever channels it sets (every channel is optional).
struct SceneKey {
    double time = 0.0;                     // seconds
    std::optional<float> cameraYawDeg;     // around +y; 0 looks at the face
    std::optional<float> cameraPitchDeg;   // above the target's horizontal plane
    std::optional<float> cameraDistance;   // times the default framing's distance
    std::optional<glm::vec3> cameraTarget; // head units (default: the framing's target)
    std::optional<glm::vec3> cameraEye;    // head units: an exact camera (yaw, pitch, distance unused)
    std::optional<glm::vec3> cameraUp;     // the exact camera's up (default +y)
    std::optional<float> cameraFovDeg;     // vertical field of view, degrees (default: the framing's)
    std::optional<glm::vec4> sphere;       // xyz, radius (head units; radius 0: none)
    std::optional<float> lightAzimuthDeg;
    std::optional<float> lightElevationDeg;
    std::optional<float> lightIntensity;
    std::optional<glm::vec3> wind;   // m/s²
    std::optional<float> headYawDeg; // about the vertical axis through the head's centre
    bool operator==(const SceneKey&) const = default;
};

// A camera relative to the default framing (absent values: the framing's).
struct CameraPose {
    std::optional<float> yawDeg, pitchDeg, distance; // distance: times the framing's
    std::optional<glm::vec3> target;
    std::optional<glm::vec3> eye, up; // an eye: the exact camera from it to the target, up its roll
    std::optional<float> fovDeg;      // vertical
};
// `framing` (OrbitCamera::framing) moved to `pose`; near and far planes follow the distance.
OrbitCamera poseCamera(const OrbitCamera& framing, const CameraPose& pose);
// The pose that gives `camera` from `framing` (what a window saves for its orbit camera), within
// the ranges a scene file allows.
CameraPose cameraPoseOf(const OrbitCamera& framing, const OrbitCamera& camera);
// The head turned by `yawDeg` about the vertical axis through the centre of `head` (the head
// mesh's bounds), as the window's Viewer::headTransform() does.
glm::mat4 headYawTransform(const Bounds& head, float yawDeg);

// Every channel at one time.
struct SceneState {
    CameraPose camera;
    glm::vec4 sphere{0.0f}; // xyz, radius; 0: none
    LightSettings light;
    glm::vec3 wind{0.0f}; // m/s²
    float headYawDeg = 0.0f;
};

// A key at `time` that sets every channel to `state` (saving what a window shows as one key).
SceneKey sceneKey(double time, const SceneState& state);

// The keys as functions of time. A channel moves between the keys that set it (linearly or by
// smoothstep, angles too, without wrapping), holds its first key's value before it and its last
// key's after; a channel no key sets keeps the base value. With a `loopPeriod` (> 0), time runs
// modulo the period: the keys play again and again.
class SceneTimeline {
public:
    SceneTimeline() = default;
    SceneTimeline(const std::vector<SceneKey>& keys, SceneInterpolation interpolation, const SceneState& base,
                  double loopPeriod = 0.0);
    SceneState at(double seconds) const;
    const SceneState& base() const { return base_; }

private:
    template <typename T> using Track = std::vector<std::pair<double, T>>;
    template <typename T> T sample(const Track<T>& track, double t, const T& fallback) const;

    SceneInterpolation interpolation_ = SceneInterpolation::Smooth;
    SceneState base_;
    double loopPeriod_ = 0.0;
    Track<float> cameraYaw_, cameraPitch_, cameraDistance_, lightAzimuth_, lightElevation_, lightIntensity_, headYaw_;
    Track<glm::vec3> cameraTarget_, cameraEye_, cameraUp_, wind_;
    Track<float> cameraFov_;
    Track<glm::vec4> sphere_;
};

} // namespace wisp
