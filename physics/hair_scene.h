// physics/hair_scene.h: a head with its hair, ready to simulate: the head and its colliders (from
// its description, or fitted to the mesh), the scalp rule, the guide strands (grown, or loaded from
// hair files in parts) and the scene's scale. Every command builds one (app/hair_source.h) and
// runs it in a hair session (app/hair_session.h).
#pragma once

#include "physics/growth.h"
#include "assets/hair_asset.h"
#include "assets/head.h"
#include "physics/strands.h"

#include <filesystem>
#include <optional>
#include <vector>

namespace wisp {

struct HairScene {
    Head head;
    std::vector<Ellipsoid> colliders;          // head space
    std::vector<gpu::Ellipsoid> gpuColliders;  // the same, as the solver takes them
    ScalpRule scalp;
    bool collidersFitted = false;              // true when the head came without colliders
    float unitsPerMetre = 1.0f;
    StrandSet strands;
};

// Loads the head and grows guides on it.
HairScene buildGrownScene(const std::filesystem::path& headFile, const GrowthSettings& growth);
// The same on a head already loaded (its description's colliders may have been replaced).
HairScene buildGrownScene(Head head, const GrowthSettings& growth);

// One hair file of a groom, with how to place it and its own simulation parameters.
struct HairPartSource {
    std::filesystem::path file;
    std::optional<HairPlacement> placement;  // none: autoPlacement against the head
    PartSettings settings;                    // name defaults to the file's stem
};

// Loads the head and the hair files (each a part), resampled to `verticesPerStrand`.
HairScene buildLoadedScene(const std::filesystem::path& headFile, const std::vector<HairPartSource>& parts,
                           uint32_t verticesPerStrand);
HairScene buildLoadedScene(Head head, const std::vector<HairPartSource>& parts, uint32_t verticesPerStrand);

// The default parameters of a loaded (styled) part: it keeps its shape more than grown hair.
PartSettings styledPartDefaults();

}  // namespace wisp
