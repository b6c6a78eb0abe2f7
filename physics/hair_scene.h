// physics/hair_scene.h: a head with its hair, ready to simulate: the head and its colliders (from
// its description, or fitted to the mesh), the scalp rule, the guide strands (grown, or loaded from
// hair files later) and the scene's scale. `wisp render` and `wisp simulate` both build one.
#pragma once

#include "physics/growth.h"
#include "physics/head.h"
#include "physics/strands.h"

#include <filesystem>
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

}  // namespace wisp
