// app/settings/hair_source.cpp: building the scene the head-and-hair source describes, and each part's
// parameters under the settings and the per-part overrides.
#include "app/settings/hair_source.h"

#include "assets/hair_asset.h"
#include "core/error.h"

#include <algorithm>
#include <utility>

namespace wisp {

std::filesystem::path HairSource::headPath() const
{
    return headFile.empty() ? defaultHeadPath() : headFile;
}

GroomedHead HairSource::buildGroomedHead(const Settings& settings) const
{
    Head head = loadHead(headPath());
    if (colliders)
        head.description.colliders = *colliders;
    if (noHair) {
        GroomedHead scene;
        scene.head = std::move(head);
        return scene;
    }
    if (hairFiles.empty()) {
        return buildGrownHead(std::move(head), settings.growth);
    }
    std::vector<HairPartSource> parts;
    for (const std::string& file : hairFiles) {
        HairPartSource part{.file = file, .placement = std::nullopt, .settings = styledPartDefaults()};
        part.settings.name = std::filesystem::path(file).stem().string();
        parts.push_back(part);
    }
    return buildLoadedHead(std::move(head), parts, settings.growth.verticesPerStrand, placementRequest());
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
    r.halfTurn = halfTurn;
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
        applyPartOverride(parts, spec, hairFiles);
    for (const std::string& spec : partOverrides)
        applyPartOverride(parts, spec, hairFiles);
    return parts;
}

void HairSource::applyPartOverride(std::vector<PartSettings>& parts, const std::string& spec,
                                   const std::vector<std::string>& files)
{
    auto bad = [&](const std::string& why) { throw UserError("--part " + spec + ": " + why); };
    size_t colon = spec.find(':');
    if (colon == std::string::npos)
        bad("expected PART:key=value[,key=value...] (PART: a part's index, name or file name)");
    std::string which = spec.substr(0, colon);
    std::vector<size_t> matches;
    std::string names;
    for (size_t i = 0; i < parts.size(); ++i) {
        names += (i ? ", " : "") + std::to_string(i) + " " + parts[i].name;
        bool named = which == std::to_string(i) || which == parts[i].name;
        if (i < files.size() && parts.size() == files.size())
            named = named || which == files[i] || which == std::filesystem::path(files[i]).filename().string();
        if (named)
            matches.push_back(i);
    }
    if (matches.empty())
        bad("no part '" + which + "' (parts: " + names + ")");
    if (matches.size() > 1)
        bad("'" + which + "' names parts " + std::to_string(matches[0]) + " and " + std::to_string(matches[1]) +
            ": give the index");
    PartSettings* part = &parts[matches.front()];
    if (colon + 1 == spec.size())
        bad("no key=value after '" + which + ":' (keys global, local, damping, drag)");
    // Each key is the every-part setting of the same meaning, with its range.
    std::vector<std::string> given;
    for (size_t at = colon + 1;;) {
        size_t comma = spec.find(',', at);
        std::string item = spec.substr(at, comma == std::string::npos ? std::string::npos : comma - at);
        at = comma + 1;
        if (item.empty())
            bad("an empty key=value (a comma too many)");
        size_t eq = item.find('=');
        if (eq == std::string::npos)
            bad("'" + item + "' is not key=value");
        std::string key = item.substr(0, eq);
        if (std::find(given.begin(), given.end(), key) != given.end())
            bad(key + " is given twice");
        given.push_back(key);
        const char* setting = nullptr;
        for (const auto& [name, settingName] : kPartKeys)
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
        if (comma == std::string::npos)
            break;
    }
}

} // namespace wisp
