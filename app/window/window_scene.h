// app/window/window_scene.h: F2 and F3 in the window. F2 saves what the window shows as a scene of one
// key (the head and hair as given: grown hair as every growth setting, the style first; every other
// setting; and
// the camera, sphere, light, wind and head turn now); F3 brings a saved scene's settings and keys
// back (the head and hair stay: another groom is `wisp view --scene FILE`).
#pragma once

#include "app/scene/scene_file.h"
#include "app/settings/hair_source.h"
#include "app/settings/settings_table.h"

#include <filesystem>
#include <functional>
#include <string>

namespace wisp {

// The scene the window's state makes, to be saved at `path` (its paths are written relative to it).
Scene windowScene(const std::filesystem::path& path, const HairSource& source, const Settings& settings,
                  const SceneState& now);
// Saves it as wisp-scene-NNN.json (NNN = `number`) in the working folder; returns the file.
std::filesystem::path saveWindowScene(uint32_t number, const HairSource& source, const Settings& settings,
                                      const SceneState& now);
// The scene at `path`: each of its settings but the growth ones goes through `apply` (the panel's
// edit; a refusal is reported on stderr and the rest still apply), and its keys become a timeline
// over `now` (what no key sets stays as it is).
using ApplySetting = std::function<std::string(const SettingSpec&, const SettingValue&)>;
SceneTimeline loadWindowScene(const std::filesystem::path& path, const SceneState& now, const ApplySetting& apply);

} // namespace wisp
