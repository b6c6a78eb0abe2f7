// app/hair_options.cpp: building the scene the shared head-and-hair options describe, and the
// per-part parameter overrides.
#include "app/hair_options.h"

#include "core/error.h"
#include "assets/hair_asset.h"

#include <cmath>
#include <sstream>
#include <utility>

namespace wisp {

HairScene HairOptions::buildScene(const std::filesystem::path& headPath) const
{
    Head head = loadHead(headPath);
    if (colliders)
        head.description.colliders = *colliders;
    if (hairFiles.empty()) {
        HairScene scene = buildGrownScene(std::move(head), growth);
        overrideParts(scene.strands);
        return scene;
    }
    std::vector<HairPartSource> parts;
    for (const std::string& file : hairFiles) {
        HairPartSource part{.file = file, .placement = std::nullopt, .settings = styledPartDefaults()};
        part.settings.name = std::filesystem::path(file).stem().string();
        parts.push_back(part);
    }
    HairScene scene = buildLoadedScene(std::move(head), parts, growth.verticesPerStrand, placementRequest());
    overrideParts(scene.strands);
    return scene;
}
PlacementRequest HairOptions::placementRequest() const
{
    PlacementRequest r;
    if (hairScale > 0.0f)
        r.scale = hairScale;
    if (!hairOffset.empty())
        r.offset = glm::vec3(hairOffset[0], hairOffset[1], hairOffset[2]);
    r.zUp = zUp;
    r.mirrorZ = mirrorZ;
    return r;
}

void HairOptions::overrideParts(StrandSet& strands) const
{
    for (PartSettings& p : strands.parts) {
        p.globalStiffness = globalStiffness.value_or(p.globalStiffness);
        p.localStiffness = localStiffness.value_or(p.localStiffness);
        p.ftlDamping = damping.value_or(p.ftlDamping);
        p.drag = drag.value_or(p.drag);
    }
    for (const std::string& spec : scenePartOverrides)
        applyPartOverride(strands.parts, spec);
    for (const std::string& spec : partOverrides)
        applyPartOverride(strands.parts, spec);
}
void HairOptions::applyPartOverride(std::vector<PartSettings>& parts, const std::string& spec)
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
    std::stringstream list(spec.substr(colon + 1));
    for (std::string item; std::getline(list, item, ',');) {
        size_t eq = item.find('=');
        if (eq == std::string::npos)
            bad("'" + item + "' is not key=value");
        std::string key = item.substr(0, eq);
        float value = 0.0f;
        try {
            size_t used = 0;
            value = std::stof(item.substr(eq + 1), &used);
            if (used != item.size() - eq - 1)
                throw std::invalid_argument(item);
        } catch (const std::exception&) {
            bad("'" + item.substr(eq + 1) + "' is not a number");
        }
        float limit = key == "drag" ? 100.0f : 1.0f;
        if (!(value >= 0.0f && value <= limit))
            bad(key + " must be in [0, " + (key == "drag" ? std::string("100") : std::string("1")) + "]");
        if (key == "global")
            part->globalStiffness = value;
        else if (key == "local")
            part->localStiffness = value;
        else if (key == "damping")
            part->ftlDamping = value;
        else if (key == "drag")
            part->drag = value;
        else
            bad("unknown key '" + key + "' (global, local, damping, drag)");
    }
}

glm::vec4 HairOptions::sphereOrNone() const
{
    return sphere.empty() ? glm::vec4(0.0f) : glm::vec4(sphere[0], sphere[1], sphere[2], sphere[3]);
}
void HairOptions::apply()
{
    // CLI11 reads "nan" and "inf" as numbers: every value of these lists must be finite.
    auto requireFinite = [](const char* option, const std::vector<float>& values, const char* form) {
        // "the first value", not "value 1" (which reads as the number 1).
        static const char* const kOrdinals[] = {"first", "second", "third", "fourth"};
        for (size_t i = 0; i < values.size(); ++i)
            if (!std::isfinite(values[i]))
                throw UserError(std::string(option) + ": the " +
                                (i < 4 ? std::string(kOrdinals[i]) : std::to_string(i + 1) + "th") + " value (" +
                                std::to_string(values[i]) + ") is not a finite number (" + form + ")");
    };
    requireFinite("--sphere", sphere, "x,y,z,r in the head's units");
    requireFinite("--wind", wind, "x,y,z in m/s^2");
    requireFinite("--hair-offset", hairOffset, "x,y,z in the head's units");
    if (!sphere.empty() && !(sphere[3] > 0.0f))
        throw UserError("--sphere: the radius (4th value) must be > 0, got " + std::to_string(sphere[3]));
    for (float w : wind)
        if (std::abs(w) > kMaxWind) {
            std::ostringstream why;
            why << "--wind: " << w << " is out of range: each component within " << -kMaxWind << " .. " << kMaxWind
                << " m/s^2";
            throw UserError(why.str());
        }
    if (!wind.empty())
        sim.wind = glm::vec3(wind[0], wind[1], wind[2]);
}

}  // namespace wisp
