// app/settings_registry.h: every human-facing setting by name, with its unit, range, default and
// description, over the plain settings structs the CLI (and later the UI and scene files) edit.
// `--set NAME=VALUE` goes through applySetting(); `wisp settings` prints the table.
#pragma once

#include "physics/growth.h"
#include "physics/simulation.h"
#include "renderer/settings.h"

#include <string>
#include <vector>

namespace wisp {

// The structs a setting can live in (any may be null when a command has no use for it).
struct SettingsRefs {
    GrowthSettings* growth = nullptr;
    SimSettings* sim = nullptr;
    RenderSettings* render = nullptr;
};

struct SettingSpec {
    std::string name;
    std::string unit;         // "" for counts and choices
    std::string range;        // human-readable: "1 .. 4096", "single | multi | mixed"
    std::string description;
    std::string (*get)(const SettingsRefs&);             // the current value, as text
    void (*set)(const SettingsRefs&, const std::string&);  // parses and range-checks, or throws
};

const std::vector<SettingSpec>& settingSpecs();
// Applies "NAME=VALUE"; throws UserError naming the setting and its allowed range on bad input.
void applySetting(const SettingsRefs& refs, const std::string& assignment);
// The table `wisp settings` prints (defaults from default-constructed structs).
std::string settingsTable();

}  // namespace wisp
