// app/window/window_scene.cpp: the window's state as a scene, and a saved scene's settings and keys
// applied as the panel applies them.
#include "app/window/window_scene.h"

#include <algorithm>
#include <cstdio>

namespace wisp {

Scene windowScene(const std::filesystem::path& path, const HairSource& source, const Settings& settings,
                  const SceneState& now)
{
    Scene saved;
    saved.description = "saved by wisp view";
    if (!source.headFile.empty())
        saved.head = scenePathText(path, std::filesystem::absolute(source.headFile));
    if (source.hairFiles.empty()) {
        // The grown hair: every setting that shapes it as it grows, in the table's order (the style
        // first: it sets the others again, and a shape stiffness that is no setting of its own), so
        // that the scene grows the same groom (a subset would lose a style's parameters).
        const std::vector<SceneSectionKey>& keys = sceneSectionKeys(SceneSection::Hair);
        // (The pair whole, not a structured binding: clang, which builds the sanitizer round, does
        // not let a lambda capture a binding.)
        for (const auto& setting : currentSettings(settings)) {
            const std::string& name = setting.first;
            if (settingSpec(name).change == SettingChange::Restart &&
                std::any_of(keys.begin(), keys.end(), [&](const SceneSectionKey& k) { return k.name == name; }))
                saved.hair.settings.push_back(setting);
        }
    } else {
        for (const std::string& f : source.hairFiles)
            saved.hair.files.push_back({.path = scenePathText(path, std::filesystem::absolute(f))});
    }
    // Every setting but the growth ones, which the hair above holds.
    for (const auto& setting : currentSettings(settings))
        if (settingSpec(setting.first).change != SettingChange::Restart)
            saved.settings.push_back(setting);
    saved.keys.push_back(sceneKey(0.0, now));
    return saved;
}

std::filesystem::path saveWindowScene(uint32_t number, const HairSource& source, const Settings& settings,
                                      const SceneState& now)
{
    char name[64];
    std::snprintf(name, sizeof(name), "wisp-scene-%03u.json", number);
    std::filesystem::path path = std::filesystem::absolute(name);
    saveScene(path, windowScene(path, source, settings, now));
    return path;
}

SceneTimeline loadWindowScene(const std::filesystem::path& path, const SceneState& now, const ApplySetting& apply)
{
    Scene loaded = loadScene(path);
    for (const auto& [name, value] : loaded.settings) {
        const SettingSpec& spec = settingSpec(name);
        if (spec.change == SettingChange::Restart)
            continue; // the hair stays
        if (std::string error = apply(spec, parseSetting(spec, value, name)); !error.empty())
            std::fprintf(stderr, "wisp: %s: %s=%s: %s\n", path.string().c_str(), name.c_str(), value.c_str(),
                         error.c_str());
    }
    return SceneTimeline(loaded.keys, loaded.interpolation, now);
}

} // namespace wisp
