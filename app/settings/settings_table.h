// app/settings/settings_table.h: every setting a person can change, in one table: its name, type, unit,
// range or choices, default (the settings structs' own initializers), help, the command-line
// option that also sets it, and what a change needs (it applies live, or rebuilds the renderer or
// the solver, or needs a restart). The command-line options, --set, `wisp settings`, scene files,
// the window's panel, a sweep's --vary and the JSON outputs are all made from this table, so a
// value is refused with the same words everywhere. Adding a setting is one entry in
// settings_table.cpp (and its field in the struct it lives in).
#pragma once

#include "core/range.h"
#include "physics/growth.h"
#include "physics/simulation.h"
#include "renderer/settings.h"

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

#include <functional>
#include <string>
#include <string_view>
#include <vector>

namespace wisp {

// Everything the table reads and writes.
struct Settings {
    GrowthSettings growth;
    SimSettings sim;
    RenderSettings render;
};

enum class SettingType {
    Number,  // a real number within `range`
    Integer, // a whole number within `range`
    OnOff,   // on | off (true | false, 1 | 0 are read too)
    Choice,  // one of `choices`
    Vector,  // x,y,z, each within `range`
    Color,   // r,g,b (linear), each within `range`
};

// What a setting is about: the panel's sections, and which commands take it (simulate draws nothing).
enum class SettingGroup { Growth, Simulation, Strands, Light, Transparency, Look };
const char* groupName(SettingGroup group); // "growth", "simulation", "strands", "light", "transparency", "look"
inline bool drawsOnly(SettingGroup group)
{
    return group != SettingGroup::Growth && group != SettingGroup::Simulation;
}

// What a changed value needs before it shows, cheapest first (the window does the largest needed).
enum class SettingChange {
    Live,     // the next frame uses it
    Renderer, // it sizes the renderer's images or buffers: the renderer is rebuilt
    Solver,   // the solver packs it: the solver is rebuilt (the hair starts again from rest)
    Restart,  // it shapes the hair as it is grown: a new run (`wisp view --set NAME=VALUE`)
};
const char* changeName(SettingChange change); // "live", "renderer", "solver", "restart"

// A value of any setting. Numbers are doubles holding what the field holds (a float field's value
// as the shortest decimal that reads back as the same float).
struct SettingValue {
    double number = 0.0;    // Number, Integer; OnOff 0 or 1; Choice: the index into `choices`
    glm::dvec3 vector{0.0}; // Vector, Color
    bool unset = false;     // an optional setting left to its default (see SettingSpec::unsetText)
    bool operator==(const SettingValue&) const = default;
};

struct SettingSpec {
    std::string name;
    SettingGroup group = SettingGroup::Growth;
    SettingType type = SettingType::Number;
    std::string unit;                 // "" for counts, fractions and choices
    Range range{0.0, 0.0};            // Number and Integer; each component of Vector and Color
    std::vector<std::string> choices; // Choice: the words, as listed (an enum's bound to its values by name)
    std::string help;
    SettingChange change = SettingChange::Live;
    std::string option;    // the command-line option that sets it too ("--step-hz"), or ""
    std::string unsetText; // an optional setting: the word for "left to its default" ("part"); "" otherwise
    bool saved = true;     // false: derived from other settings (hair_preset), not written into scenes
    std::function<SettingValue(const Settings&)> get;
    std::function<void(Settings&, const SettingValue&)> put; // a value checkSetting() accepted

    bool optional() const { return !unsetText.empty(); }
    // "1 .. 4096", "0.01 .. 2 m", "single | multi | mixed", "on | off", "x,y,z in -100 .. 100 m/s^2"
    std::string allowed() const;
};

const std::vector<SettingSpec>& settingSpecs();
// The spec of `name`, or null.
const SettingSpec* findSetting(std::string_view name);
// The spec of `name`; an unknown name throws UserError "WHERE: unknown setting 'NAME' (see 'wisp settings')".
const SettingSpec& settingSpec(std::string_view name, const std::string& where = "--set");
// Every name, comma-separated (for messages that list them).
std::string settingNames();

// Reading and checking values. Every failure throws UserError "WHERE: WHY", WHY the same words for
// every front end: "0 is out of range: allowed 1 .. 4096", "'cubic' is not allowed: single |
// multi | mixed", "'wide' is not a number", "2.5 is not a whole number". Vectors name the value
// ("WHERE: the third value (1e+09) is out of range: ...", or in JSON the element's pointer
// "WHERE/2: 1e+09 is out of range: ...").
SettingValue parseSetting(const SettingSpec& spec, std::string_view text, const std::string& where);
SettingValue settingFromJson(const SettingSpec& spec, const nlohmann::ordered_json& json, const std::string& where);
void checkSetting(const SettingSpec& spec, const SettingValue& value, const std::string& where);
// The value as --set takes it, and as JSON (numbers, true/false, strings, arrays).
std::string settingText(const SettingSpec& spec, const SettingValue& value);
nlohmann::ordered_json settingJson(const SettingSpec& spec, const SettingValue& value);

// Numbers that are not settings (a sphere, a groom's placement), read with the same words: one
// number (`ordinal` 0), or `count` of them comma-separated ("x,y,z"; a failure names "the second
// value (nan)").
double parseNumber(std::string_view text, const Range& range, const std::string& unit, const std::string& where,
                   size_t ordinal = 0);
std::vector<double> parseNumbers(std::string_view text, size_t count, const char* form, const Range& range,
                                 const std::string& unit, const std::string& where);

// Checks `value` and writes it into `settings`.
void setSetting(Settings& settings, const SettingSpec& spec, const SettingValue& value, const std::string& where);
// "NAME=VALUE" as --set takes it; errors read "--set NAME: WHY".
void applySetting(Settings& settings, const std::string& assignment);

// `wisp settings`: one line per setting (name, unit, allowed values, default, what a change
// needs, the option, help), and the same as JSON (`wisp settings --json`).
std::string settingsTable();
nlohmann::ordered_json settingsTableJson();
// Every setting's current value by name: the "settings" object of the commands' JSON outputs.
nlohmann::ordered_json settingsJson(const Settings& settings);
// Every saved setting's value as NAME=VALUE, in the table's order (a window saves its state so).
std::vector<std::pair<std::string, std::string>> currentSettings(const Settings& settings);

// What the window's panel shows for a setting, from its type: a slider (logarithmic over wide
// ranges), a checkbox, a list of choices, a colour or three numbers; disabled when a change needs
// a restart.
struct PanelControl {
    enum class Kind { Slider, IntegerSlider, Checkbox, Combo, Color, Vector } kind = Kind::Slider;
    double min = 0.0, max = 0.0;
    bool logarithmic = false;
    bool enabled = true;
};
PanelControl panelControl(const SettingSpec& spec);
// The panel's edit of one setting: checked as --set checks it and written into `settings`, or the
// one line to show under the control. `change` is what the edit needs.
struct SettingEdit {
    std::string error; // "" when applied
    SettingChange change = SettingChange::Live;
};
SettingEdit editSetting(Settings& settings, const SettingSpec& spec, const SettingValue& value);

} // namespace wisp
