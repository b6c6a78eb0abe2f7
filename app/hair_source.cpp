// app/hair_source.cpp: building the scene the head-and-hair source describes, and each part's
// parameters under the settings and the per-part overrides.
#include "app/hair_source.h"

#include "assets/hair_asset.h"
#include "core/error.h"

#include <sstream>
#include <utility>

namespace wisp {

std::filesystem::path HairSource::headPath() const
{
    return headFile.empty() ? defaultHeadPath() : headFile;
}

HairScene HairSource::buildScene(const Settings& settings) const
{
    Head head = loadHead(headPath());
    if (colliders)
        head.description.colliders = *colliders;
    if (noHair) {
        HairScene scene;
        scene.head = std::move(head);
        return scene;
    }
    if (hairFiles.empty()) {
        return buildGrownScene(std::move(head), settings.growth);
    }
    std::vector<HairPartSource> parts;
    for (const std::string& file : hairFiles) {
        HairPartSource part{.file = file, .placement = std::nullopt, .settings = styledPartDefaults()};
        part.settings.name = std::filesystem::path(file).stem().string();
        parts.push_back(part);
    }
    return buildLoadedScene(std::move(head), parts, settings.growth.verticesPerStrand, placementRequest());
}

PlacementRequest HairSource::placementRequest() const
{
    PlacementRequest r;
    if (hairScale > 0.0f)
        r.scale = hairScale;
    if (hairOffset)
        r.offset = *hairOffset;
    r.zUp = zUp;
    r.mirrorZ = mirrorZ;
    return r;
}

std::vector<PartSettings> HairSource::partsFor(const std::vector<PartSettings>& asBuilt, const SimSettings& sim) const
{
    std::vector<PartSettings> parts = asBuilt;
    for (PartSettings& p : parts) {
        p.globalStiffness = sim.globalStiffness.value_or(p.globalStiffness);
        p.localStiffness = sim.localStiffness.value_or(p.localStiffness);
        p.ftlDamping = sim.ftlDamping.value_or(p.ftlDamping);
        p.drag = sim.drag.value_or(p.drag);
    }
    for (const std::string& spec : scenePartOverrides)
        applyPartOverride(parts, spec);
    for (const std::string& spec : partOverrides)
        applyPartOverride(parts, spec);
    return parts;
}

void HairSource::applyPartOverride(std::vector<PartSettings>& parts, const std::string& spec)
{
    auto bad = [&](const std::string& why) { throw UserError("--part " + spec + ": " + why); };
    size_t colon = spec.find(':');
    if (colon == std::string::npos)
        bad("expected PART:key=value[,key=value...] (PART: a part's index or name)");
    std::string which = spec.substr(0, colon);
    PartSettings* part = nullptr;
    std::string names;
    for (size_t i = 0; i < parts.size(); ++i) {
        names += (i ? ", " : "") + std::to_string(i) + " " + parts[i].name;
        if (which == std::to_string(i) || which == parts[i].name)
            part = &parts[i];
    }
    if (!part)
        bad("no part '" + which + "' (parts: " + names + ")");
    // Each key is the every-part setting of the same meaning, with its range.
    const std::pair<const char*, const char*> keys[] = {
        {"global", "global_stiffness"}, {"local", "local_stiffness"}, {"damping", "damping"}, {"drag", "drag"}};
    std::stringstream list(spec.substr(colon + 1));
    for (std::string item; std::getline(list, item, ',');) {
        size_t eq = item.find('=');
        if (eq == std::string::npos)
            bad("'" + item + "' is not key=value");
        std::string key = item.substr(0, eq);
        const char* setting = nullptr;
        for (const auto& [name, settingName] : keys)
            if (key == name)
                setting = settingName;
        if (!setting)
            bad("unknown key '" + key + "' (global, local, damping, drag)");
        const SettingSpec& s = settingSpec(setting);
        SettingValue v = parseSetting(s, item.substr(eq + 1), "--part " + spec + ": " + key);
        if (v.unset)
            bad(key + " needs a number (" + s.allowed() + " without '" + s.unsetText + "')");
        float value = float(v.number);
        if (key == "global")
            part->globalStiffness = value;
        else if (key == "local")
            part->localStiffness = value;
        else if (key == "damping")
            part->ftlDamping = value;
        else
            part->drag = value;
    }
}

} // namespace wisp
