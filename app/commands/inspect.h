// app/commands/inspect.h: `wisp inspect`: what a hair or mesh file holds, as one JSON object; for a groom
// also its units, the up axis it is taken to have, its pinned tips and its strands too short to
// simulate; with --head, the placement Wisp would use on that head and the roots' distance to
// its surface (--hair-scale, --hair-offset, --hair-z-up and --hair-mirror-z as render takes them).
#pragma once

#include <CLI/CLI.hpp>

#include <functional>
#include <nlohmann/json_fwd.hpp>
#include <string>
#include <vector>

namespace wisp {

struct HairAsset;

struct InspectOptions {
    std::string file;                // a hair file or a mesh
    std::vector<std::string> hair;   // --hair (repeatable): a groom in parts
    std::string head;                // --head: place the groom on it
    uint32_t verticesPerStrand = 16; // --vertices: what the strands are resampled to (short strands depend on it)
};

// Registers the command; the returned function runs it when it was given (-1 otherwise).
std::function<int()> addInspectCommand(CLI::App& app);

// The groom summary `wisp inspect` prints for one hair file (no head): counts, bounds, units,
// up axis, pinned tips, lengths and short strands (against the groom's own size).
nlohmann::json describeGroom(const HairAsset& asset, uint32_t verticesPerStrand);

} // namespace wisp
