// app/window/viewer.cpp: the window's interactive state, its keys, and input scripts.
#include "app/window/viewer.h"

#include "app/scene/scene_timeline.h"
#include "app/settings/settings_table.h"
#include "core/error.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

namespace wisp {

namespace {

constexpr float kSphereSpeed = 0.35f; // scene sizes per second, keys held
constexpr float kLightDegreesPerSecond = 60.0f;
constexpr float kHeadTurnDeg = 30.0f; // per press of A or D
constexpr float kHeadTurnLimitDeg = 80.0f;
constexpr float kHeadSpring = 5.0f;  // rad/s: the head's turn settles in about a second
constexpr float kWindDefault = 4.0f; // m/s²
constexpr float kWindStep = 1.25f;

// How high and low the light goes: the light_elevation setting's range.
const Range& elevationRange()
{
    static const Range range = settingSpec("light_elevation").range;
    return range;
}

// The camera's right, up and forward directions in world space.
void cameraAxes(const OrbitCamera& camera, glm::vec3& right, glm::vec3& up, glm::vec3& forward)
{
    glm::mat4 v = camera.view();
    right = glm::vec3(v[0][0], v[1][0], v[2][0]);
    up = glm::vec3(v[0][1], v[1][1], v[2][1]);
    forward = -glm::vec3(v[0][2], v[1][2], v[2][2]);
}

} // namespace

const std::vector<ViewerKeyInfo>& viewerKeys()
{
    static const std::vector<ViewerKeyInfo> keys = {
        {ViewerKey::SphereLeft, "left", "arrows, PgUp/PgDn: sphere"},
        {ViewerKey::SphereRight, "right", ""},
        {ViewerKey::SphereUp, "up", ""},
        {ViewerKey::SphereDown, "down", ""},
        {ViewerKey::SphereNear, "pageup", ""},
        {ViewerKey::SphereFar, "pagedown", ""},
        {ViewerKey::LightLeft, "j", "J/L/I/K: light"},
        {ViewerKey::LightRight, "l", ""},
        {ViewerKey::LightUp, "i", ""},
        {ViewerKey::LightDown, "k", ""},
        {ViewerKey::HeadLeft, "a", "A/D: turn head"},
        {ViewerKey::HeadRight, "d", ""},
        {ViewerKey::Wind, "w", "W: wind, +/-: stronger/weaker"},
        {ViewerKey::WindStronger, "plus", ""},
        {ViewerKey::WindWeaker, "minus", ""},
        {ViewerKey::Pause, "space", "Space: pause"},
        {ViewerKey::Step, "n", "N: step"},
        {ViewerKey::Reset, "r", "R: reset"},
        {ViewerKey::Screenshot, "p", "P: screenshot"},
        {ViewerKey::Reload, "f5", "F5: reload shaders"},
        {ViewerKey::SphereToggle, "o", "O: sphere on/off"},
        {ViewerKey::Help, "h", "H: help"},
        {ViewerKey::Play, "t", "T: play/stop the scene"},
        {ViewerKey::SaveScene, "f2", "F2: save the scene"},
        {ViewerKey::LoadScene, "f3", "F3: load the last saved scene"},
        {ViewerKey::Quit, "escape", "Esc: quit"},
    };
    return keys;
}

std::string viewerHelp()
{
    std::string help = "drag: orbit, wheel: zoom, middle drag: pan, right drag: sphere, shift+right drag: light";
    for (const ViewerKeyInfo& k : viewerKeys())
        if (*k.label)
            help += std::string(" | ") + k.label;
    return help;
}

Viewer::Viewer(const OrbitCamera& camera, const Bounds& scene, const glm::vec4& sphere, const LightSettings& light,
               const glm::vec3& wind)
    : camera_(camera), scene_(scene), centre_(scene.center()), size_(std::max(scene.diagonal(), 1e-6f)), light_(light)
{
    sphereOn_ = sphere.w > 0.0f;
    sphereRadius_ = sphereOn_ ? sphere.w : 0.12f * size_;
    // Parked beside the head, on the camera's right, until it is switched on or moved.
    glm::vec3 right, up, forward;
    cameraAxes(camera_, right, up, forward);
    sphereCentre_ = sphereOn_ ? glm::vec3(sphere) : centre_ + right * (0.55f * size_);
    windOn_ = glm::length(wind) > 0.0f;
    windStrength_ = windOn_ ? glm::length(wind) : kWindDefault;
    windDirection_ = windOn_ ? glm::normalize(wind) : glm::normalize(glm::vec3(-1.0f, 0.0f, -0.4f));
}

void Viewer::press(ViewerKey key)
{
    held_.insert(key);
    switch (key) {
    case ViewerKey::SphereLeft:
    case ViewerKey::SphereRight:
    case ViewerKey::SphereUp:
    case ViewerKey::SphereDown:
    case ViewerKey::SphereNear:
    case ViewerKey::SphereFar:
        sphereOn_ = true; // moving it brings it into play
        break;
    case ViewerKey::HeadLeft:
        headYawTarget_ = std::max(headYawTarget_ - kHeadTurnDeg, -kHeadTurnLimitDeg);
        break;
    case ViewerKey::HeadRight:
        headYawTarget_ = std::min(headYawTarget_ + kHeadTurnDeg, kHeadTurnLimitDeg);
        break;
    case ViewerKey::Wind:
        windOn_ = !windOn_;
        break;
    case ViewerKey::WindStronger:
        windStrength_ = std::min(windStrength_ * kWindStep, 50.0f);
        windOn_ = true;
        break;
    case ViewerKey::WindWeaker:
        windStrength_ = std::max(windStrength_ / kWindStep, 0.1f);
        break;
    case ViewerKey::Pause:
        paused_ = !paused_;
        break;
    case ViewerKey::Step:
        paused_ = true;
        ++steps_;
        break;
    case ViewerKey::Reset:
        reset_ = true;
        break;
    case ViewerKey::Screenshot:
        screenshot_ = true;
        break;
    case ViewerKey::Reload:
        reload_ = true;
        break;
    case ViewerKey::SphereToggle:
        sphereOn_ = !sphereOn_;
        break;
    case ViewerKey::Help:
        help_ = !help_;
        break;
    case ViewerKey::Quit:
        quit_ = true;
        break;
    case ViewerKey::Play:
        playing_ = !playing_;
        break;
    case ViewerKey::SaveScene:
        save_ = true;
        break;
    case ViewerKey::LoadScene:
        load_ = true;
        break;
    default:
        break;
    }
}

void Viewer::release(ViewerKey key)
{
    held_.erase(key);
}

void Viewer::update(float seconds)
{
    glm::vec3 right, up, forward;
    cameraAxes(camera_, right, up, forward);
    glm::vec3 move(0.0f);
    auto heldKey = [&](ViewerKey k) { return held_.count(k) ? 1.0f : 0.0f; };
    move += right * (heldKey(ViewerKey::SphereRight) - heldKey(ViewerKey::SphereLeft));
    move += up * (heldKey(ViewerKey::SphereUp) - heldKey(ViewerKey::SphereDown));
    move += forward * (heldKey(ViewerKey::SphereFar) - heldKey(ViewerKey::SphereNear));
    sphereCentre_ += move * (kSphereSpeed * size_ * seconds);

    light_.azimuthDeg +=
        (heldKey(ViewerKey::LightRight) - heldKey(ViewerKey::LightLeft)) * kLightDegreesPerSecond * seconds;
    light_.azimuthDeg = std::remainder(light_.azimuthDeg, 360.0f);
    light_.elevationDeg +=
        (heldKey(ViewerKey::LightUp) - heldKey(ViewerKey::LightDown)) * kLightDegreesPerSecond * seconds;
    light_.elevationDeg = std::clamp(light_.elevationDeg, float(elevationRange().min), float(elevationRange().max));

    // The head turns toward its target like a critically damped spring: a smooth start and stop,
    // so the hair swings after it.
    float accel = kHeadSpring * kHeadSpring * (headYawTarget_ - headYaw_) - 2.0f * kHeadSpring * headYawRate_;
    headYawRate_ += accel * seconds;
    headYaw_ += headYawRate_ * seconds;
}

void Viewer::dragSphere(float dx, float dy, float viewportHeight)
{
    glm::vec3 right, up, forward;
    cameraAxes(camera_, right, up, forward);
    float depth = std::max(glm::dot(sphereCentre_ - camera_.position(), forward), 0.1f * size_);
    float unitsPerPixel =
        2.0f * depth * std::tan(glm::radians(camera_.fovYDeg) * 0.5f) / std::max(viewportHeight, 1.0f);
    sphereCentre_ += (right * dx - up * dy) * unitsPerPixel;
    sphereOn_ = true;
}

void Viewer::dragLight(float dx, float dy)
{
    light_.azimuthDeg = std::remainder(light_.azimuthDeg + 0.4f * dx, 360.0f);
    light_.elevationDeg =
        std::clamp(light_.elevationDeg - 0.4f * dy, float(elevationRange().min), float(elevationRange().max));
}

void Viewer::pose(const OrbitCamera& camera, const glm::vec4& sphere, const LightSettings& light, const glm::vec3& wind,
                  float headYawDeg)
{
    camera_ = camera;
    sphereOn_ = sphere.w > 0.0f;
    if (sphereOn_) {
        sphereCentre_ = glm::vec3(sphere);
        sphereRadius_ = sphere.w;
    }
    light_ = light;
    windOn_ = glm::length(wind) > 0.0f;
    if (windOn_) {
        windStrength_ = glm::length(wind);
        windDirection_ = wind / windStrength_;
    }
    headYaw_ = headYawTarget_ = headYawDeg;
    headYawRate_ = 0.0f;
}

void Viewer::setWind(const glm::vec3& wind)
{
    windOn_ = glm::length(wind) > 0.0f;
    if (windOn_) {
        windStrength_ = glm::length(wind);
        windDirection_ = wind / windStrength_;
    }
}

glm::vec4 Viewer::sphere() const
{
    return glm::vec4(sphereCentre_, sphereOn_ ? sphereRadius_ : 0.0f);
}

glm::mat4 Viewer::headTransform() const
{
    return headYawTransform(scene_, headYaw_);
}

glm::vec3 Viewer::wind() const
{
    return windOn_ ? windDirection_ * windStrength_ : glm::vec3(0.0f);
}

uint32_t Viewer::takeSteps()
{
    return std::exchange(steps_, 0u);
}

std::string Viewer::status() const
{
    char text[320];
    std::snprintf(
        text, sizeof(text),
        "sphere %s at (%.4f, %.4f, %.4f) r %.4f, light azimuth %.1f elevation %.1f, head yaw %.1f, wind %s %.2f m/s2%s",
        sphereOn_ ? "on" : "off", double(sphereCentre_.x), double(sphereCentre_.y), double(sphereCentre_.z),
        double(sphereRadius_), double(light_.azimuthDeg), double(light_.elevationDeg), double(headYaw_),
        windOn_ ? "on" : "off", double(windStrength_), paused_ ? ", paused" : "");
    return text;
}

std::vector<ScriptEvent> loadScript(const std::filesystem::path& path)
{
    std::ifstream in(path);
    if (!in)
        throw UserError("--script " + path.string() + ": cannot open the file");
    std::vector<ScriptEvent> events;
    std::string line;
    for (int number = 1; std::getline(in, line); ++number) {
        std::string where = path.string() + ":" + std::to_string(number) + ": ";
        if (size_t hash = line.find('#'); hash != std::string::npos)
            line.erase(hash);
        std::istringstream words(line);
        std::string frame, action;
        if (!(words >> frame))
            continue; // blank or comment
        ScriptEvent e;
        auto [end, ec] = std::from_chars(frame.data(), frame.data() + frame.size(), e.frame);
        if (ec != std::errc() || end != frame.data() + frame.size())
            throw UserError(where + "'" + frame + "' is not a frame number");
        if (!(words >> action))
            throw UserError(where + "an action is missing after the frame number");
        if (action == "press" || action == "release" || action == "tap") {
            e.kind = action == "press"     ? ScriptEvent::Kind::Press
                     : action == "release" ? ScriptEvent::Kind::Release
                                           : ScriptEvent::Kind::Tap;
            std::string name;
            words >> name;
            auto found = std::find_if(viewerKeys().begin(), viewerKeys().end(),
                                      [&](const ViewerKeyInfo& k) { return name == k.name; });
            if (found == viewerKeys().end()) {
                std::string names;
                for (const ViewerKeyInfo& k : viewerKeys())
                    names += std::string(names.empty() ? "" : " ") + k.name;
                throw UserError(where + "unknown key '" + name + "' (keys: " + names + ")");
            }
            e.key = found->key;
        } else if (action == "drag-sphere" || action == "drag-light" || action == "orbit") {
            e.kind = action == "drag-sphere"  ? ScriptEvent::Kind::DragSphere
                     : action == "drag-light" ? ScriptEvent::Kind::DragLight
                                              : ScriptEvent::Kind::Orbit;
            if (!(words >> e.dx >> e.dy) || !std::isfinite(e.dx) || !std::isfinite(e.dy) || std::abs(e.dx) > 1e5f ||
                std::abs(e.dy) > 1e5f)
                throw UserError(where + action + " needs two finite pixel distances DX DY");
        } else if (action == "set") {
            e.kind = ScriptEvent::Kind::Set;
            if (!(words >> e.assignment) || e.assignment.find('=') == std::string::npos)
                throw UserError(where + "set needs NAME=VALUE (a setting from 'wisp settings')");
        } else {
            throw UserError(where + "unknown action '" + action +
                            "' (actions: press, release, tap, drag-sphere, drag-light, orbit, set)");
        }
        std::string extra;
        if (words >> extra)
            throw UserError(where + "unexpected '" + extra + "' at the end of the line");
        events.push_back(e);
    }
    std::stable_sort(events.begin(), events.end(),
                     [](const ScriptEvent& a, const ScriptEvent& b) { return a.frame < b.frame; });
    return events;
}

std::vector<std::string> playScript(const std::vector<ScriptEvent>& events, uint32_t frame, Viewer& viewer,
                                    float viewportHeight)
{
    std::vector<std::string> assignments;
    for (const ScriptEvent& e : events) {
        if (e.frame != frame)
            continue;
        switch (e.kind) {
        case ScriptEvent::Kind::Press:
            viewer.press(e.key);
            break;
        case ScriptEvent::Kind::Release:
            viewer.release(e.key);
            break;
        case ScriptEvent::Kind::Tap:
            viewer.press(e.key);
            viewer.release(e.key);
            break;
        case ScriptEvent::Kind::DragSphere:
            viewer.dragSphere(e.dx, e.dy, viewportHeight);
            break;
        case ScriptEvent::Kind::DragLight:
            viewer.dragLight(e.dx, e.dy);
            break;
        case ScriptEvent::Kind::Orbit:
            viewer.orbit(e.dx, e.dy);
            break;
        case ScriptEvent::Kind::Set:
            assignments.push_back(e.assignment);
            break;
        }
    }
    return assignments;
}

} // namespace wisp
