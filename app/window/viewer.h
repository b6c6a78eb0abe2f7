// app/window/viewer.h: what the interactive window controls, apart from GLFW (so a script and the tests
// drive the same code as the keyboard and mouse): the collision sphere and the light moved
// relative to the camera, the head turned (the hair follows through the physics, with inertia),
// wind on and off and its strength, pause, single step, reset, screenshot, shader reload.
// Also `--script FILE`: timed input events, one per line, replayed by frame number.
#pragma once

#include "renderer/camera.h"
#include "renderer/settings.h"

#include <glm/glm.hpp>

#include <filesystem>
#include <set>
#include <string>
#include <utility>
#include <vector>

namespace wisp {

enum class ViewerKey {
    SphereLeft,
    SphereRight,
    SphereUp,
    SphereDown,
    SphereNear,
    SphereFar, // arrows, Page Up / Down
    LightLeft,
    LightRight,
    LightUp,
    LightDown, // J L I K
    HeadLeft,
    HeadRight, // A D
    Wind,
    WindStronger,
    WindWeaker, // W + -
    Pause,
    Step,
    Reset,
    Screenshot,
    Reload,
    SphereToggle,
    Help,
    Quit, // Space N R P F5 O H Esc
    Play,
    SaveScene,
    LoadScene, // T F2 F3
};

struct ViewerKeyInfo {
    ViewerKey key;
    const char* name;  // in scripts
    const char* label; // on screen
};
const std::vector<ViewerKeyInfo>& viewerKeys();
// The help line: every key and what it does.
std::string viewerHelp();

class Viewer {
public:
    // `sceneSize`: the head's bounding-box diagonal (speeds scale with it); `sphere`: the user's
    // sphere from the command line (radius 0: none yet, one is parked beside the head, off).
    Viewer(const OrbitCamera& camera, const Bounds& scene, const glm::vec4& sphere, const LightSettings& light,
           const glm::vec3& wind);

    void press(ViewerKey key); // one-shot actions, and held keys start moving things
    void release(ViewerKey key);
    // Advances held-key motion and the head's turn by `seconds`.
    void update(float seconds);
    // Mouse drags in pixels (viewport height for the scale): the sphere in the camera's plane,
    // the light around the head, the camera around its target.
    void dragSphere(float dx, float dy, float viewportHeight);
    void dragLight(float dx, float dy);
    void orbit(float dx, float dy) { camera_.orbit(-0.3f * dx, 0.3f * dy); }
    // Puts every animated thing where a scene's timeline has it (the head's turn at once).
    void pose(const OrbitCamera& camera, const glm::vec4& sphere, const LightSettings& light, const glm::vec3& wind,
              float headYawDeg);
    // The light and the wind as the panel sets them.
    void setLight(const LightSettings& light) { light_ = light; }
    void setWind(const glm::vec3& wind);
    bool playing() const { return playing_; }
    void setPlaying(bool playing) { playing_ = playing; }

    OrbitCamera& camera() { return camera_; }
    const LightSettings& light() const { return light_; }
    glm::vec4 sphere() const;        // xyz, radius; radius 0 when off
    glm::mat4 headTransform() const; // a turn about the vertical axis through the head's centre
    float headYawDeg() const { return headYaw_; }
    glm::vec3 wind() const; // m/s², zero when off
    bool paused() const { return paused_; }
    bool helpShown() const { return help_; }
    // One-shot requests, each returned once (true) and then cleared.
    uint32_t takeSteps(); // single steps asked for while paused
    bool takeReset() { return std::exchange(reset_, false); }
    bool takeScreenshot() { return std::exchange(screenshot_, false); }
    bool takeReload() { return std::exchange(reload_, false); }
    bool takeSave() { return std::exchange(save_, false); }
    bool takeLoad() { return std::exchange(load_, false); }
    bool quit() const { return quit_; }
    // A one-line summary for the title bar and the exit message.
    std::string status() const;

private:
    OrbitCamera camera_;
    Bounds scene_;
    glm::vec3 centre_;
    float size_;
    glm::vec3 sphereCentre_;
    float sphereRadius_;
    bool sphereOn_;
    LightSettings light_;
    glm::vec3 windDirection_;
    float windStrength_;
    bool windOn_;
    float headYaw_ = 0.0f, headYawTarget_ = 0.0f, headYawRate_ = 0.0f;
    bool paused_ = false;
    uint32_t steps_ = 0;
    bool reset_ = false, screenshot_ = false, reload_ = false, quit_ = false, help_ = true;
    bool playing_ = false, save_ = false, load_ = false;
    std::set<ViewerKey> held_;
};

// A script of timed input events for `wisp view --script FILE` (frames counted from 0):
//   FRAME press KEY | release KEY | tap KEY | drag-sphere DX DY | drag-light DX DY | orbit DX DY
//   FRAME set NAME=VALUE   (a setting changed as in the panel)
// KEY is a name from viewerKeys(); '#' starts a comment. Errors name the file and line.
struct ScriptEvent {
    enum class Kind { Press, Release, Tap, DragSphere, DragLight, Orbit, Set };
    uint32_t frame = 0;
    Kind kind = Kind::Tap;
    ViewerKey key = ViewerKey::Help;
    float dx = 0.0f, dy = 0.0f;
    std::string assignment; // Set: NAME=VALUE
};
std::vector<ScriptEvent> loadScript(const std::filesystem::path& path);
// Applies the events of `frame` to the viewer; returns that frame's setting assignments.
std::vector<std::string> playScript(const std::vector<ScriptEvent>& events, uint32_t frame, Viewer& viewer,
                                    float viewportHeight);

} // namespace wisp
