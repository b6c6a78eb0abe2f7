// app/settings/hair_source.h: where the head and its hair come from, apart from the settings: the head
// file, grown guides or hair files as parts with their placement, each part's own parameters, a
// scene's colliders and the user's sphere. buildGroomedHead() makes the GroomedHead they describe with the
// growth settings; partsFor() gives each part's simulation parameters under the settings.
#pragma once

#include "app/settings/settings_table.h"
#include "physics/groomed_head.h"

#include <glm/glm.hpp>

#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace wisp {

// Limits of a loaded groom's placement and of the user's sphere (head units).
inline constexpr Range kHairScaleRange{1e-6, 1e6};
inline constexpr Range kPositionRange{-1e4, 1e4}; // every coordinate
inline constexpr Range kRadiusRange{0.0, 1e4};    // 0: no sphere

// The keys of a per-part override ("PART:global=0.2,drag=3") and the every-part setting each
// stands for, whose range it takes (scene files name a part's own values by the settings' names).
inline constexpr std::pair<const char*, const char*> kPartKeys[] = {
    {"global", "global_stiffness"}, {"local", "local_stiffness"}, {"damping", "damping"}, {"drag", "drag"}};

struct HairSource {
    std::filesystem::path headFile;      // empty: the default head (models/head.json)
    bool noHair = false;                 // the head alone
    std::vector<std::string> hairFiles;  // none: guides grown with the growth settings
    float hairScale = 0.0f;              // 0: automatic placement
    std::optional<glm::vec3> hairOffset; // head units, after scaling
    std::optional<bool> zUp, mirrorZ;    // placement overrides for loaded hair
    std::optional<bool> halfTurn;        // turned round about the up axis (unset: chosen by the fit)
    // "PART:key=value,..." (PART: a part's index or name; keys global, local, damping, drag): a
    // scene file's per-file values, then the command line's --part, each over the one before.
    std::vector<std::string> scenePartOverrides, partOverrides;
    std::optional<std::vector<Ellipsoid>> colliders; // replace the head's (head space)
    glm::vec4 sphere{0.0f};                          // the user's sphere: xyz, radius (0: none)

    std::filesystem::path headPath() const; // headFile, or the default head
    // The head with grown guides (or none with noHair), or with the hair files as parts, each
    // placed; each part's parameters as grown or loaded (a HairSession applies partsFor()).
    GroomedHead buildGroomedHead(const Settings& settings) const;
    // What --hair-scale, --hair-offset, --hair-z-up, --hair-mirror-z and --hair-half-turn fix of
    // the placement.
    PlacementRequest placementRequest() const;
    // Each part's simulation parameters: as grown or loaded (`asBuilt`), then every part's values
    // from the settings (global_stiffness ...), then the per-part overrides.
    std::vector<PartSettings> partsFor(const std::vector<PartSettings>& asBuilt, const SimSettings& sim) const;
    // "PART:key=value,...", PART a part's index, name (its file's stem), or its file's name or path
    // as given in `files` (one per part; empty: grown hair): throws UserError "--part SPEC: ..." on
    // bad input (no such part, a name two parts share, no key, a key given twice).
    static void applyPartOverride(std::vector<PartSettings>& parts, const std::string& spec,
                                  const std::vector<std::string>& files = {});
};

} // namespace wisp
