// assets/hair_writer.h: grooms written for other tools, the inverse of assets/hair_asset.h's readers:
// cyHair `.hair` (Cem Yuksel's format, written z-up as its known files are, so loadHairAsset's
// z-up-to-y-up turn brings it back the right way up) and TressFX 4 binary `.tfx` (y-up, right-handed,
// w = inverse mass: 0 on pinned vertices). The format comes from the extension; files are written
// atomically (core/atomic_file.h), so a refused or failed write leaves nothing behind.
#pragma once

#include "assets/hair_asset.h"

#include <filesystem>
#include <string>
#include <vector>

namespace wisp {

// The format a groom is written in, from the output's extension (case-insensitive): `.hair` ->
// cyHair, `.tfx` -> TressFX 4. Anything else throws UserError naming the file and the extensions.
HairFormat hairFormatForOutput(const std::filesystem::path& path);

// What a writer takes: strands in Wisp's head space (y up, face toward +z, right-handed, head
// units), root first, at least 2 points each, every coordinate finite. `pinnedRoot` and `pinnedTip`
// as HairStrand has them; `points` of HairStrand hold head-space points here, not file points.
struct GroomToWrite {
    std::vector<HairStrand> strands;
    float thickness = 0.0f; // cyHair d_thickness (head units); TressFX 4 has no field for it
    std::string info;       // cyHair's 88-byte info text (cut to 87 characters)
};

// The file's bytes. cyHair: header, no segments array when every strand has the same number of
// points (d_segments), else a segments array (at most 65,535 segments a strand), points as
// (x, -z, y): Wisp's y-up turned z-up; pinned vertices are not kept (the format has no field for
// them; Wisp pins each strand's root when it reads one). TressFX 4: every strand must have the same
// number of points (2 .. 1024); w = 0 on the leading pinnedRoot vertices and on a pinned tip, 1
// elsewhere; no UVs, thicknesses or colours. Bad input (no strands, a strand of one point, a
// non-finite point, counts the format cannot hold) throws UserError naming the strand and point.
std::string encodeCyHair(const GroomToWrite& groom);
std::string encodeTfx4(const GroomToWrite& groom);

// Encodes `groom` in the format of `path`'s extension and writes it atomically.
void writeHairFile(const std::filesystem::path& path, const GroomToWrite& groom);

} // namespace wisp
