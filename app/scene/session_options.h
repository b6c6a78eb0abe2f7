// app/scene/session_options.h: the head, hair, scene and settings options that render, record, view,
// simulate and sweep share, registered on a command in one place and resolved after parsing in
// one order: the settings' defaults, then the scene file's values, then the command line's
// options, then --set (a later one wins). Every setting that has an option in the settings table
// gets it here; the hair's source (--head, --hair, placement, --part, --sphere) and --scene are
// the rest.
#pragma once

#include "app/scene/scene_file.h"
#include "app/settings/hair_source.h"
#include "app/settings/settings_table.h"

#include <algorithm>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace CLI {
class App;
class Validator;
} // namespace CLI

namespace wisp {

// A closed range for a floating-point option. CLI::Range lets "nan" through (every comparison with
// NaN is false); this one asks for lo <= value <= hi, which NaN and the infinities fail. Refusals
// read as the settings table's ("--fps: 0 is out of range: allowed 1 .. 1000", "'x' is not a
// number"), checked before CLI11 converts the text, so its own words never show.
CLI::Validator within(double lo, double hi);
// The same for a whole-number option (a value past the type's range, -1 for an unsigned one, is
// out of range, not "could not convert").
CLI::Validator wholeWithin(double lo, double hi);

// What a command runs with, once resolved.
struct SessionOptions {
    Settings settings;
    HairSource source;
    std::optional<Scene> scene;
    std::filesystem::path sceneFile;
    // The scene's keys over the command line's base (its sphere, wind, light and camera); a channel
    // the command line sets explicitly (--wind, --sphere, --light-*, --camera-*, --fov, or --set of
    // those settings) holds the command line's value throughout. Without a scene, the base alone.
    SceneTimeline timeline;
    // The settings the command line or the scene gave a value (the rest are the defaults).
    std::vector<std::string> givenSettings;
    // Those the command line gave (its options and --set), in the order applied: a sweep's style
    // axis applies its style under them, as --style does.
    std::vector<std::string> commandLineSettings;
    bool settingGiven(const std::string& name) const
    {
        return std::find(givenSettings.begin(), givenSettings.end(), name) != givenSettings.end();
    }
    double sceneLength() const { return scene ? scene->length() : 0.0; }
};

// A loaded groom's placement options (--hair-scale, --hair-offset, --hair-z-up, --hair-mirror-z,
// --hair-half-turn), the same on every command that places hair (the session's, and inspect).
class PlacementOptions {
public:
    // Registers the options on `command` (which must outlive this object).
    explicit PlacementOptions(CLI::App* command);
    // After parsing: what was given, checked (UserError names the option), into `source`; what
    // was not given stays as it was (a scene's).
    void apply(HairSource& source) const;

private:
    CLI::App* command_;
    float scale_ = 0.0f;
    std::string offset_, zUp_, mirrorZ_, halfTurn_;
};

class SessionCommandLine {
public:
    struct Uses {
        bool scene = true;  // --scene
        bool noHair = true; // --no-hair
        bool draws = true;  // the image size and the drawing settings (simulate draws nothing)
    };
    // Registers the options on `command` (which must outlive this object; neither moves).
    SessionCommandLine(CLI::App* command, Uses uses);
    SessionCommandLine(const SessionCommandLine&) = delete;
    SessionCommandLine& operator=(const SessionCommandLine&) = delete;

    // After parsing: the options resolved, every value checked (UserError names the option, the
    // scene file and pointer, or the --set). Loads the scene file, not what it names.
    SessionOptions resolve() const;
    bool given(const std::string& option) const; // the option was on the command line

private:
    CLI::App* command_;
    Uses uses_;
    std::map<std::string, std::string> settingOptions_; // option -> its text as given
    std::map<std::string, bool> settingFlags_;          // on/off settings taken as flags (--poisson)
    std::vector<std::string> sets_;                     // --set NAME=VALUE, in order
    std::string sceneFile_, headFile_;
    bool noHair_ = false;
    std::vector<std::string> hairFiles_, partOverrides_;
    std::string sphere_;
    std::string cameraEye_, cameraTarget_, cameraUp_; // --camera-eye, --camera-target, --camera-up
    float fovDeg_ = 0.0f;                             // --fov
    PlacementOptions placement_;
    uint32_t width_ = RenderSettings{}.width, height_ = RenderSettings{}.height;
};

} // namespace wisp
