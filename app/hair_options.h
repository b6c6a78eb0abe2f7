// app/hair_options.h: the head-and-hair options every command shares (grown guides or hair files
// as parts, their placement, per-part parameters, the sphere and the wind), and building the
// scene they describe. The command line fills them (cli.cpp); `sweep` copies them per point.
#pragma once

#include "physics/hair_scene.h"
#include "physics/simulation.h"
#include "renderer/settings.h"

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace wisp {

// Ranges of the hair options (the command line and scene files check against these).
inline constexpr Range kGuidesRange{1, 2000000};
inline constexpr Range kHairLengthRange{0.01, 2.0};       // metres
inline constexpr Range kLengthVariationRange{0.0, 0.9};   // relative spread
inline constexpr Range kCurlRange{0.0, 0.1};              // metres (curl radius)
inline constexpr Range kHairScaleRange{1e-6, 1e6};
inline constexpr Range kStiffnessRange{0.0, 1.0};         // global, local stiffness; damping
inline constexpr Range kDragRange{0.0, 100.0};            // 1/s
inline constexpr Range kRepulsionRange{0.0, 1.0};

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
    std::vector<std::string> scenePartOverrides; // the same from a scene file, applied before partOverrides
    std::optional<std::vector<Ellipsoid>> colliders;  // replace the head's (head space)

    // The head with grown guides, or with the hair files as parts (each with its placement and
    // per-part overrides applied).
    HairScene buildScene(const std::filesystem::path& headPath) const;
    // What --hair-scale, --hair-offset, --hair-z-up and --hair-mirror-z fix of the placement.
    PlacementRequest placementRequest() const;
    void overrideParts(StrandSet& strands) const;
    // "PART:key=value,...", PART a part's index or name; keys global, local, damping, drag.
    static void applyPartOverride(std::vector<PartSettings>& parts, const std::string& spec);
    glm::vec4 sphereOrNone() const;
    void apply();  // values CLI11 cannot check on its own
};


}  // namespace wisp
