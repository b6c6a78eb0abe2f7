// physics/groomed_head.h: a head with its hair, ready to simulate: the head and its colliders (from
// its description, or fitted to the mesh), the scalp rule, the guide strands (grown, or loaded from
// hair files in parts) and the scene's scale. Every command builds one (app/settings/hair_source.h) and
// runs it in a hair session (app/session/hair_session.h).
#pragma once

#include "assets/hair_asset.h"
#include "assets/head.h"
#include "assets/placement.h"
#include "physics/growth.h"
#include "physics/strand_set.h"

#include <nlohmann/json_fwd.hpp>

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace wisp {

// What loading a groom did with its strands; of grown hair, only its rigid strands (shorter than
// kRigidStrandMetres, physics/growth.h) and that threshold.
struct LoadedStrands {
    size_t dropped = 0;          // of no length at all: nothing to draw or simulate
    size_t rigid = 0;            // shorter than shortThreshold: kept rigid (assets/hair_asset.h)
    float shortThreshold = 0.0f; // head units
    size_t pinnedTips = 0;       // both ends pinned (TressFX bothEndsImmovable)
};

struct GroomedHead {
    Head head;
    std::vector<Ellipsoid> colliders;         // head space
    std::vector<gpu::Ellipsoid> gpuColliders; // the same, as the solver takes them
    ScalpRule scalp;
    bool collidersFitted = false; // true when the head came without colliders
    float unitsPerMetre = 1.0f;
    StrandSet strands;
    std::optional<GroomPlacement> placement; // loaded hair: how it was placed, the roots against the head
    std::optional<GroomTransfer> transfer;   // loaded hair: the strands moved onto the scalp after the fit
    LoadedStrands loaded;
    // Warnings for the person (roots off the head under a placement given by hand), one line each.
    std::vector<std::string> warnings;
    // What was chosen for the loaded hair that the person did not give (strands_per_guide), one
    // line each; describeLoadedHair ends with them.
    std::vector<std::string> notes;
};

// Loads the head and grows guides on it.
GroomedHead buildGrownHead(const std::filesystem::path& headFile, const GrowthSettings& growth);
// The same on a head already loaded (its description's colliders may have been replaced).
GroomedHead buildGrownHead(Head head, const GrowthSettings& growth);

// One hair file of a groom, with how to place it and its own simulation parameters.
struct HairPartSource {
    std::filesystem::path file;
    std::optional<HairPlacement> placement; // none: the groom's placement (all parts together)
    PartSettings settings;                  // name defaults to the file's stem
};

// Loads the head and the hair files (each a part), resampled to `verticesPerStrand`, placed
// together on the head (assets/placement.h: `request` fixes what the user gave), then the strands
// whose roots the placement leaves off the surface moved onto the scalp (transferStrands:
// `transfer`). An automatic placement that leaves most roots off the head is refused (UserError
// naming the options that place a groom by hand: that is no groom for this head, or a misread
// file), and so is a groom to move onto a head whose scalp rule selects nothing; a placement by
// hand that leaves most roots off is kept as given, with a warning. Strands of no length are
// dropped and strands too short to simulate kept rigid, both counted (`loaded`).
GroomedHead buildLoadedHead(const std::filesystem::path& headFile, const std::vector<HairPartSource>& parts,
                            uint32_t verticesPerStrand, const PlacementRequest& request = {});
GroomedHead buildLoadedHead(Head head, const std::vector<HairPartSource>& parts, uint32_t verticesPerStrand,
                            const PlacementRequest& request = {});

// What loading did, for a person, one line each (grown hair: a line only when some of its guides
// are rigid, "hair strands: 120 of 400 grown guides rigid (shorter than 4 cm: ...)"): "hair placement: fitted to
// the scalp: scale 0.4, offset (...), y-up; roots: median 0.3% of the head's size from its
// surface, 98.2% within 2%", "hair transfer: 312 of 3000 roots moved onto the scalp ..." (when
// any was) and "hair strands: 12 kept rigid (shorter than 0.9 head units), ...".
std::vector<std::string> describeLoadedHair(const GroomedHead& scene);
// The same as JSON (null for grown hair).
nlohmann::json loadedHairJson(const GroomedHead& scene);
// The guides kept rigid and why, as JSON, grown or loaded: {"count", "shorter_than" (head units)}.
nlohmann::json rigidStrandsJson(const GroomedHead& scene);

// The default parameters of a loaded (styled) part: it keeps its shape more than grown hair.
PartSettings styledPartDefaults();

} // namespace wisp
