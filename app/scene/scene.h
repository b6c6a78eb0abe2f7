// app/scene/scene.h: scene files: one JSON file naming the head, the hair (grown or loaded in parts),
// the colliders, any settings from `wisp settings`, the physics options, and keyframes over time
// for the camera, the sphere, the light, the wind and the head's turn. The keys that are settings
// (/hair/guides, /physics/wind, ...) are the settings table's names. loadScene() (parseScene()
// for text in memory) checks every value (errors name the file and a JSON pointer), saveScene()
// writes one atomically, and SceneTimeline evaluates the keys at any time. `render`, `record` and
// `view` take `--scene`.
#pragma once

#include "app/settings/hair_source.h"
#include "app/settings/settings_table.h"
#include "assets/head.h"
#include "renderer/camera.h"
#include "renderer/settings.h"

#include <glm/glm.hpp>

#include <filesystem>
#include <optional>
#include <string>
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
    std::optional<glm::vec4> sphere;       // xyz, radius (head units; radius 0: none)
    std::optional<float> lightAzimuthDeg;
    std::optional<float> lightElevationDeg;
    std::optional<float> lightIntensity;
    std::optional<glm::vec3> wind;   // m/s²
    std::optional<float> headYawDeg; // about the vertical axis through the head's centre
    bool operator==(const SceneKey&) const = default;
};

// Settings as NAME=VALUE (the text --set takes), by the settings' own names, in the file's order
// (a later one wins).
using SceneSettings = std::vector<std::pair<std::string, std::string>>;

// A hair file of a loaded groom, with its part's own values of the part settings (kPartKeys of
// app/settings/hair_source.h: global_stiffness, local_stiffness, damping, drag; absent: the groom's or the
// default).
struct SceneHairFile {
    std::string path; // as written: relative to the scene file, absolute, or "shared:REL"
    SceneSettings settings;
    bool operator==(const SceneHairFile&) const = default;
};

// The hair: grown (files empty) or loaded. Absent values keep the defaults (or the command
// line's). Its settings are the growth settings (guides, vertices_per_strand, hair_length, ...:
// group growth of `wisp settings`) and the part settings for every part, each under its setting's
// name (sceneSectionKeys).
struct SceneHair {
    SceneSettings settings;
    std::vector<SceneHairFile> files;
    std::optional<float> scale; // placement of loaded hair (as --hair-scale, ...)
    std::optional<glm::vec3> offset;
    std::optional<bool> zUp, mirrorZ, halfTurn;
    bool operator==(const SceneHair&) const = default;
};

struct Scene {
    std::string description;
    std::string head; // as written; empty: the default head
    SceneHair hair;
    std::optional<std::vector<Ellipsoid>> colliders; // head space; absent: the head's (or fitted)
    // "physics": the sphere, and three settings older scenes wrote here (wind, repulsion,
    // grid_atomics, as "settings" would hold them). The wind and the sphere are the values while no
    // key sets those channels (as --wind and --sphere).
    SceneSettings physics;
    std::optional<glm::vec4> sphere; // head units
    SceneSettings settings;          // "settings": any setting
    SceneInterpolation interpolation = SceneInterpolation::Smooth;
    std::optional<double> duration; // seconds; absent: the last key's time
    bool loop = false;              // the keys repeat every length() seconds (a soak runs for hours)
    std::vector<SceneKey> keys;     // by increasing time
    bool operator==(const Scene&) const = default;

    // The length of the animation: `duration`, else the last key's time (0 without keys).
    double length() const;
};

// The settings a section of a scene file holds under their own names: /hair (every growth setting
// and part setting), /hair/files/N (the part settings), /physics (wind, repulsion, grid_atomics).
// `alias`: the name older scenes used, still read ("vertices" for vertices_per_strand).
struct SceneSectionKey {
    std::string name;
    std::string alias;
    bool grownOnly = false; // shapes grown hair only: refused beside /hair/files
};
enum class SceneSection { Hair, HairFile, Physics };
const std::vector<SceneSectionKey>& sceneSectionKeys(SceneSection section);

// Reads and checks a scene. Throws UserError naming the file and what is wrong: the JSON pointer
// of the value (/keys/2/sphere/3), the allowed range or type, unknown keys with the known ones,
// the line and column of malformed JSON. Files named by the scene are not opened here.
Scene loadScene(const std::filesystem::path& path);
// The same from a scene file's text already in memory; errors name `path` as if it were read.
Scene parseScene(const std::string& content, const std::filesystem::path& path);
// Writes `scene` as JSON (to a temporary file in the same folder, then renamed: never half
// written). Paths are written as the struct holds them (see scenePathText).
void saveScene(const std::filesystem::path& path, const Scene& scene);
// The same JSON text saveScene writes.
std::string sceneJson(const Scene& scene);

// Files a scene names: "shared:REL" is REL inside the shared data folder ($WISP_SHARED_DATA when
// set, else ../shared/data beside the checkout Wisp was built from); any other relative path is
// relative to the scene file's folder. A missing file is a UserError naming the scene and
// `pointer` (/head, /hair/files/0); a missing shared file says the shared data is missing.
std::filesystem::path sharedDataFolder();
std::filesystem::path resolveScenePath(const std::filesystem::path& sceneFile, const std::string& text,
                                       const std::string& pointer);
// How to write `file` into a scene saved at `sceneFile`: "shared:REL" inside the shared data
// folder, else relative to the scene's folder (absolute when on another root).
std::string scenePathText(const std::filesystem::path& sceneFile, const std::filesystem::path& file);

// Writes the scene's values into the settings and the hair's source (before the command line's own
// options are applied over them); files it names are resolved against `sceneFile`.
void applyScene(const Scene& scene, const std::filesystem::path& sceneFile, Settings& settings, HairSource& source);

// A camera relative to the default framing (absent values: the framing's).
struct CameraPose {
    std::optional<float> yawDeg, pitchDeg, distance; // distance: times the framing's
    std::optional<glm::vec3> target;
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
    Track<glm::vec3> cameraTarget_, wind_;
    Track<glm::vec4> sphere_;
};

} // namespace wisp
