// app/hair_options.h: the head-and-hair options every command shares (grown guides or hair files
// as parts, their placement, per-part parameters, the sphere and the wind), and building the
// scene they describe. The command line fills them (cli.cpp); `sweep` copies them per point.
#pragma once

#include "physics/hair_scene.h"
#include "physics/simulation.h"

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace wisp {

struct HairOptions {
    GrowthSettings growth;
    SimSettings sim;
    std::vector<float> sphere;  // x, y, z, r
    std::vector<float> wind;    // x, y, z
    std::vector<std::string> hairFiles;
    float hairScale = 0.0f;          // 0: automatic placement
    std::vector<float> hairOffset;   // x, y, z
    std::optional<float> globalStiffness, localStiffness, damping, drag;
    std::optional<bool> zUp, mirrorZ;            // placement overrides for loaded hair
    std::vector<std::string> partOverrides;      // "PART:key=value,key=value" (PART: index or name)

    // The head with grown guides, or with the hair files as parts (each with its placement and
    // per-part overrides applied).
    HairScene buildScene(const std::filesystem::path& headPath) const;
    void overrideParts(StrandSet& strands) const;
    // "PART:key=value,...", PART a part's index or name; keys global, local, damping, drag.
    static void applyPartOverride(std::vector<PartSettings>& parts, const std::string& spec);
    glm::vec4 sphereOrNone() const;
    void apply();  // values CLI11 cannot check on its own
};


}  // namespace wisp
