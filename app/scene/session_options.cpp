// app/scene/session_options.cpp: the shared options on a CLI11 command (settings' options from the
// table, the hair's source, --scene, --set) and their resolution, scene first.
#include "app/scene/session_options.h"

#include "app/settings/value_text.h"
#include "core/error.h"

#include <CLI/CLI.hpp>

#include <algorithm>
#include <cmath>

namespace wisp {

namespace {

CLI::Validator numberWithin(double lo, double hi, bool whole)
{
    return CLI::Validator(
        [lo, hi, whole](std::string& input) {
            try {
                double v = parseNumber(input, Range{lo, hi}, "", "-");
                if (whole && v != std::floor(v))
                    return input + " is not a whole number";
            } catch (const UserError& e) {
                return std::string(e.what()).substr(3); // past parseNumber's "-: "
            }
            return std::string();
        },
        (whole ? "INT in " : "in ") + rangeText(Range{lo, hi}, ""));
}

} // namespace

CLI::Validator within(double lo, double hi)
{
    return numberWithin(lo, hi, false);
}

CLI::Validator wholeWithin(double lo, double hi)
{
    return numberWithin(lo, hi, true);
}

namespace {

// true | false (or on | off, 1 | 0), as on/off settings take them.
bool parseYesNo(const std::string& text, const std::string& option)
{
    if (text == "true" || text == "on" || text == "1")
        return true;
    if (text == "false" || text == "off" || text == "0")
        return false;
    throw UserError(option + ": '" + text + "' is not allowed: true | false (or on | off, 1 | 0)");
}

} // namespace

PlacementOptions::PlacementOptions(CLI::App* cmd) : command_(cmd)
{
    cmd->add_option("--hair-scale", scale_, "scale loaded hair by this (default: automatic when units clearly differ)")
        ->check(CLI::Validator(
            [](std::string& text) {
                try {
                    parseNumber(text, kHairScaleRange, "", "value");
                } catch (const UserError& e) {
                    return std::string(e.what());
                }
                return std::string();
            },
            "SCALE"));
    cmd->add_option("--hair-offset", offset_, "move loaded hair by x,y,z (head units) after scaling");
    cmd->add_option("--hair-z-up", zUp_,
                    "loaded hair is z-up: turn it y-up, true | false (default: automatic, true for cyHair)");
    cmd->add_option("--hair-mirror-z", mirrorZ_,
                    "mirror loaded hair's z, true | false (default: automatic, true for TressFX 3)");
    cmd->add_option("--hair-half-turn", halfTurn_,
                    "turn loaded hair round about the up axis (its front to the back), true | false (default: "
                    "automatic: a groom fitted to the scalp faces the way the head faces)");
}

void PlacementOptions::apply(HairSource& source) const
{
    auto given = [&](const char* option) {
        const CLI::Option* o = command_->get_option_no_throw(option);
        return o && o->count() > 0;
    };
    if (given("--hair-scale"))
        source.hairScale = scale_;
    if (given("--hair-offset")) {
        std::vector<double> v = parseNumbers(offset_, 3, "x,y,z", kPositionRange, "head units", "--hair-offset");
        source.hairOffset = glm::vec3(float(v[0]), float(v[1]), float(v[2]));
    }
    if (given("--hair-z-up"))
        source.zUp = parseYesNo(zUp_, "--hair-z-up");
    if (given("--hair-mirror-z"))
        source.mirrorZ = parseYesNo(mirrorZ_, "--hair-mirror-z");
    if (given("--hair-half-turn"))
        source.halfTurn = parseYesNo(halfTurn_, "--hair-half-turn");
}

SessionCommandLine::SessionCommandLine(CLI::App* cmd, Uses uses) : command_(cmd), uses_(uses), placement_(cmd)
{
    Settings defaults;
    for (const SettingSpec& spec : settingSpecs()) {
        if (spec.option.empty() || (!uses.draws && drawsOnly(spec.group)))
            continue;
        std::string help =
            spec.help + " (" + spec.allowed() + "; default " + settingText(spec, spec.get(defaults)) + ")";
        if (spec.type == SettingType::OnOff)
            cmd->add_flag(spec.option, settingFlags_[spec.option], spec.help);
        else
            cmd->add_option(spec.option, settingOptions_[spec.option], help);
    }
    cmd->add_option("--set", sets_, "NAME=VALUE for any setting in 'wisp settings' (repeatable; over the options)");
    if (uses.scene)
        cmd->add_option("--scene", sceneFile_,
                        "scene file (.json, see scenes/): head, hair, colliders, settings, physics and keyframes over "
                        "time; options given on the command line override the scene's values (and replace the keys "
                        "of --wind, --sphere, --light-*)");
    cmd->add_option("--head", headFile_,
                    "head: a description (.json) or a mesh (.obj, .fbx, .gltf, .ply, ...); default models/head.json");
    if (uses.noHair)
        cmd->add_flag("--no-hair", noHair_, "the head alone");
    if (uses.draws) {
        auto size = wholeWithin(kImageSizeRange.min, kImageSizeRange.max);
        cmd->add_option("--width", width_, "image width in pixels")->check(size)->capture_default_str();
        cmd->add_option("--height", height_, "image height in pixels")->check(size)->capture_default_str();
        cmd->add_option("--camera-eye", cameraEye_,
                        "the camera exactly: its eye x,y,z in the head's units, looking at --camera-target (default "
                        "the framing's target) with --camera-up (default 0,1,0); without it the default framing");
        cmd->add_option("--camera-target", cameraTarget_, "the point the camera looks at, x,y,z in the head's units");
        cmd->add_option("--camera-up", cameraUp_, "the exact camera's up direction x,y,z (its roll)");
        cmd->add_option("--fov", fovDeg_, "the camera's vertical field of view in degrees (default 30)")
            ->check(CLI::Range(float(kSceneCameraFovRange.min), float(kSceneCameraFovRange.max)));
    }
    cmd->add_option("--hair", hairFiles_,
                    "hair file to load instead of growing guides (TressFX .tfx 2/3/4, cyHair .hair); repeat for a "
                    "groom in parts")
        ->check(CLI::ExistingFile);
    cmd->add_option("--part", partOverrides_,
                    "one part's parameters: PART:key=value,... with PART its index or file name, keys global, local, "
                    "damping, drag");
    cmd->add_option("--sphere", sphere_, "collision sphere x,y,z,r in the head's units");
}

bool SessionCommandLine::given(const std::string& option) const
{
    const CLI::Option* o = command_->get_option_no_throw(option);
    return o && o->count() > 0;
}

SessionOptions SessionCommandLine::resolve() const
{
    SessionOptions o;
    if (!sceneFile_.empty()) {
        o.sceneFile = sceneFile_;
        o.scene = loadScene(sceneFile_);
        applyScene(*o.scene, o.sceneFile, o.settings, o.source);
    }

    // The hair's source: the command line's over the scene's.
    if (given("--head"))
        o.source.headFile = headFile_;
    o.source.noHair = noHair_;
    if (given("--hair")) {
        o.source.hairFiles = hairFiles_;
        o.source.scenePartOverrides.clear(); // other files: the scene's per-file values do not apply
    }
    placement_.apply(o.source);
    o.source.partOverrides = partOverrides_;
    if (given("--sphere")) {
        std::vector<double> v = parseNumbers(sphere_, 4, "x,y,z,r", kPositionRange, "head units", "--sphere");
        if (!(v[3] > 0.0 && v[3] <= kRadiusRange.max))
            throw UserError("--sphere: the fourth value, the radius (" + sphere_.substr(sphere_.rfind(',') + 1) +
                            "), must be > 0 and at most " + std::to_string(int(kRadiusRange.max)) + " head units");
        o.source.sphere = glm::vec4(float(v[0]), float(v[1]), float(v[2]), float(v[3]));
    }
    if (uses_.draws) {
        o.settings.render.width = width_;
        o.settings.render.height = height_;
    }

    // The settings: a style first, however it is given (--style, --set hair_style=), since it sets
    // every growth parameter; then the other options, then the other --set values: whatever is given
    // explicitly wins over the style (--set hair_style=afro --guides 60 grows 60 guides).
    std::vector<std::string> explicitSettings;
    std::vector<std::string> sets = sets_;
    std::stable_partition(sets.begin(), sets.end(),
                          [](const std::string& a) { return a.substr(0, a.find('=')) == "hair_style"; });
    auto applySet = [&](const std::string& assignment) {
        std::string name = assignment.substr(0, assignment.find('='));
        if (const SettingSpec* spec = findSetting(name); spec && !uses_.draws && drawsOnly(spec->group))
            throw UserError("--set " + name + ": this command does not use it (it draws nothing)");
        applySetting(o.settings, assignment);
        explicitSettings.push_back(name);
    };
    auto applyOptions = [&](bool styles) {
        for (const SettingSpec& spec : settingSpecs()) {
            if (spec.option.empty() || !given(spec.option) || (spec.name == "hair_style") != styles)
                continue;
            SettingValue v = spec.type == SettingType::OnOff
                                 ? SettingValue{.number = settingFlags_.at(spec.option) ? 1.0 : 0.0}
                                 : parseSetting(spec, settingOptions_.at(spec.option), spec.option);
            setSetting(o.settings, spec, v, spec.option);
            explicitSettings.push_back(spec.name);
        }
    };
    applyOptions(true);
    size_t styleSets = 0;
    for (; styleSets < sets.size() && sets[styleSets].substr(0, sets[styleSets].find('=')) == "hair_style"; ++styleSets)
        applySet(sets[styleSets]);
    applyOptions(false);
    for (size_t i = styleSets; i < sets.size(); ++i)
        applySet(sets[i]);

    o.givenSettings = explicitSettings;
    o.commandLineSettings = explicitSettings;
    if (o.scene)
        for (const auto& [name, value] : o.scene->settings)
            o.givenSettings.push_back(name);

    // The timeline: the scene's keys over the command line's base.
    SceneState base;
    auto point = [&](const std::string& text, const char* option, const char* unit) {
        std::vector<double> v = parseNumbers(text, 3, "x,y,z", kPositionRange, unit, option);
        return glm::vec3(float(v[0]), float(v[1]), float(v[2]));
    };
    if (given("--camera-eye"))
        base.camera.eye = point(cameraEye_, "--camera-eye", "head units");
    if (given("--camera-target"))
        base.camera.target = point(cameraTarget_, "--camera-target", "head units");
    if (given("--camera-up")) {
        if (!given("--camera-eye"))
            throw UserError("--camera-up: it rolls the exact camera: give --camera-eye too");
        base.camera.up = point(cameraUp_, "--camera-up", "");
        if (glm::length(*base.camera.up) == 0.0f)
            throw UserError("--camera-up: 0,0,0 is no direction");
    }
    if (base.camera.eye && base.camera.target && *base.camera.eye == *base.camera.target)
        throw UserError("--camera-eye: it is the target: the camera needs a direction to look in");
    if (base.camera.eye && base.camera.target && base.camera.up &&
        glm::length(glm::cross(*base.camera.up, *base.camera.target - *base.camera.eye)) == 0.0f)
        throw UserError("--camera-up: it is along the line of sight, so it gives the camera no roll");
    if (given("--fov"))
        base.camera.fovDeg = fovDeg_;
    base.sphere = o.source.sphere;
    base.wind = o.settings.sim.wind;
    base.light = o.settings.render.light;
    if (!o.scene) {
        o.timeline = SceneTimeline({}, SceneInterpolation::Smooth, base);
        return o;
    }
    auto explicitly = [&](const char* setting) {
        return std::find(explicitSettings.begin(), explicitSettings.end(), setting) != explicitSettings.end();
    };
    std::vector<SceneKey> keys = o.scene->keys;
    for (SceneKey& k : keys) {
        if (explicitly("wind"))
            k.wind.reset();
        if (given("--sphere"))
            k.sphere.reset();
        if (explicitly("light_azimuth"))
            k.lightAzimuthDeg.reset();
        if (explicitly("light_elevation"))
            k.lightElevationDeg.reset();
        if (explicitly("light_intensity"))
            k.lightIntensity.reset();
        if (given("--camera-eye")) // the command line's exact camera replaces the scene's camera
            k.cameraYawDeg.reset(), k.cameraPitchDeg.reset(), k.cameraDistance.reset(), k.cameraEye.reset(),
                k.cameraUp.reset();
        if (given("--camera-eye") || given("--camera-target"))
            k.cameraTarget.reset();
        if (given("--fov"))
            k.cameraFovDeg.reset();
    }
    o.timeline = SceneTimeline(keys, o.scene->interpolation, base, o.scene->loop ? o.scene->length() : 0.0);
    return o;
}

} // namespace wisp
