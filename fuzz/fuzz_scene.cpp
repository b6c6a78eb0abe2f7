// fuzz/fuzz_scene.cpp: libFuzzer target of the scene parser (parseScene: the JSON, then every
// value checked): the input is the whole file. A scene it returns must hold only finite values
// within the ranges app/scene/scene_file.h, app/scene/scene_timeline.h and the settings table
// document, agree with itself (increasing key times, grown or loaded hair), give finite channels
// at any time, and save and read back the same.
#include "fuzz_support.h"

#include "app/scene/scene_file.h"
#include "app/settings/settings_table.h"
#include "core/error.h"
#include "physics/strand_set.h"

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace {

using wisp::Range;
using wisp::fuzz::broken;

// The range of a setting in the settings table.
const Range& range(const char* setting)
{
    return wisp::settingSpec(setting).range;
}

// A value read from a checked double: finite and within `r` (a float's bounds rounded to float,
// as the value itself was).
void inRange(double v, const Range& r, const std::string& what)
{
    if (!std::isfinite(v) || !r.contains(v))
        broken(what + " = " + std::to_string(v) + " is outside " + std::to_string(r.min) + " .. " +
               std::to_string(r.max));
}
void inRange(float v, const Range& r, const std::string& what)
{
    if (!std::isfinite(v) || v < float(r.min) || v > float(r.max))
        broken(what + " = " + std::to_string(v) + " is outside " + std::to_string(r.min) + " .. " +
               std::to_string(r.max));
}
template <glm::length_t N> void inRange(const glm::vec<N, float>& v, const Range& r, const std::string& what)
{
    for (glm::length_t i = 0; i < N; ++i)
        inRange(v[i], r, what + "[" + std::to_string(i) + "]");
}
template <typename T> void inRange(const std::optional<T>& v, const Range& r, const std::string& what)
{
    if (v)
        inRange(*v, r, what);
}

void checkSphere(const glm::vec4& s, const std::string& what)
{
    inRange(glm::vec3(s), wisp::kPositionRange, what + ".xyz");
    inRange(s.w, wisp::kRadiusRange, what + ".radius");
}

// Each setting a section holds is a setting of the table, and its value reads back through it
// (its range, its words).
void checkSettings(const wisp::SceneSettings& settings, const std::string& what)
{
    for (const auto& [name, value] : settings) {
        const wisp::SettingSpec* spec = wisp::findSetting(name);
        if (!spec)
            broken(what + " holds '" + name + "', which is no setting");
        try {
            wisp::parseSetting(*spec, value, what + "." + name);
        } catch (const wisp::UserError& e) {
            broken(what + "." + name + " = " + value + " does not read back: " + e.what());
        }
    }
}

void checkHair(const wisp::SceneHair& h)
{
    checkSettings(h.settings, "hair");
    inRange(h.scale, wisp::kHairScaleRange, "hair.scale");
    inRange(h.offset, wisp::kPositionRange, "hair.offset");
    if (h.files.size() > gpu::kSimMaxParts)
        broken(std::to_string(h.files.size()) + " hair files");
    for (const wisp::SceneHairFile& f : h.files) {
        if (f.path.empty())
            broken("an empty hair file name");
        checkSettings(f.settings, "hair file");
    }
    const std::vector<wisp::SceneSectionKey>& keys = wisp::sceneSectionKeys(wisp::SceneSection::Hair);
    bool grown = false;
    for (const auto& [name, value] : h.settings)
        for (const wisp::SceneSectionKey& k : keys)
            grown = grown || (k.grownOnly && k.name == name);
    bool placed = h.scale || h.offset || h.zUp || h.mirrorZ || h.halfTurn;
    if (!h.files.empty() && grown)
        broken("loaded hair with growth values");
    if (h.files.empty() && placed)
        broken("grown hair with placement values");
}

void checkKey(const wisp::SceneKey& k, const std::string& at)
{
    inRange(k.time, wisp::kSceneTimeRange, at + ".time");
    inRange(k.cameraYawDeg, wisp::kSceneCameraYawRange, at + ".camera.yaw");
    inRange(k.cameraPitchDeg, wisp::kSceneCameraPitchRange, at + ".camera.pitch");
    inRange(k.cameraDistance, wisp::kSceneCameraDistanceRange, at + ".camera.distance");
    inRange(k.cameraTarget, wisp::kPositionRange, at + ".camera.target");
    if (k.sphere)
        checkSphere(*k.sphere, at + ".sphere");
    inRange(k.lightAzimuthDeg, range("light_azimuth"), at + ".light.azimuth");
    inRange(k.lightElevationDeg, range("light_elevation"), at + ".light.elevation");
    inRange(k.lightIntensity, range("light_intensity"), at + ".light.intensity");
    inRange(k.wind, range("wind"), at + ".wind");
    inRange(k.headYawDeg, wisp::kSceneHeadYawRange, at + ".head_yaw");
}

// Every channel of the timeline at `t` is finite.
void checkState(const wisp::SceneState& s, double t)
{
    const wisp::CameraPose& c = s.camera;
    bool finite = std::isfinite(c.yawDeg.value_or(0.0f)) && std::isfinite(c.pitchDeg.value_or(0.0f)) &&
                  std::isfinite(c.distance.value_or(1.0f)) && wisp::fuzz::finite(c.target.value_or(glm::vec3(0.0f))) &&
                  wisp::fuzz::finite(glm::vec3(s.sphere)) && std::isfinite(s.sphere.w) &&
                  std::isfinite(s.light.azimuthDeg) && std::isfinite(s.light.elevationDeg) &&
                  std::isfinite(s.light.intensity) && wisp::fuzz::finite(s.wind) && std::isfinite(s.headYawDeg);
    if (!finite)
        broken("the timeline has a non-finite channel at t = " + std::to_string(t));
}

void checkScene(const wisp::Scene& s)
{
    checkHair(s.hair);
    if (s.colliders) {
        if (s.colliders->empty())
            broken("an empty collider list");
        for (const wisp::Ellipsoid& e : *s.colliders) {
            inRange(e.center, wisp::kPositionRange, "collider center");
            inRange(e.radii, wisp::kRadiusRange, "collider radii");
            if (!(e.radii.x > 0.0f && e.radii.y > 0.0f && e.radii.z > 0.0f))
                broken("a collider radius is not > 0");
            inRange(e.rotationDeg, Range{-360.0, 360.0}, "collider rotation");
        }
    }
    checkSettings(s.physics, "physics");
    if (s.sphere)
        checkSphere(*s.sphere, "physics.sphere");
    inRange(s.duration, wisp::kSceneTimeRange, "duration");
    for (size_t i = 0; i < s.keys.size(); ++i) {
        checkKey(s.keys[i], "keys[" + std::to_string(i) + "]");
        if (i > 0 && !(s.keys[i].time > s.keys[i - 1].time))
            broken("key times do not increase at " + std::to_string(i));
    }
    inRange(s.length(), wisp::kSceneTimeRange, "length()");

    wisp::SceneTimeline timeline(s.keys, s.interpolation, wisp::SceneState{});
    checkState(timeline.at(0.0), 0.0);
    for (size_t i = 0; i < s.keys.size(); ++i) {
        checkState(timeline.at(s.keys[i].time), s.keys[i].time);
        if (i > 0) {
            double middle = 0.5 * (s.keys[i - 1].time + s.keys[i].time);
            checkState(timeline.at(middle), middle);
        }
    }

    // What the parser accepted, the settings table and the saved file accept as well.
    try {
        wisp::Settings settings;
        for (const auto& [name, value] : s.settings)
            wisp::applySetting(settings, name + "=" + value);
        if (!(wisp::parseScene(wisp::sceneJson(s), "saved.json") == s))
            broken("the scene saved and read back differs");
    } catch (const wisp::UserError& e) {
        broken(std::string("an accepted scene is refused once saved or applied: ") + e.what());
    }
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
    std::string text(reinterpret_cast<const char*>(data), size);
    wisp::fuzz::run([&] { return wisp::parseScene(text, "fuzz.json"); }, checkScene);
    return 0;
}
