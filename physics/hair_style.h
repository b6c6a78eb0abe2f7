// physics/hair_style.h: named hair styles, each nothing but a set of the groom generator's
// parameters (physics/growth.h) and the shape constraints that keep it (how stiffly the grown part
// holds its rest pose). `hair_style` in the settings table applies one; changing any of its
// parameters afterwards makes the style "custom".
#pragma once

#include "physics/growth.h"

#include <array>
#include <cstdint>
#include <string_view>

namespace wisp {

// What a style asks of the drawing (the settings coil_radius, coil_frequency, divisions,
// strands_per_guide and strand_length_jitter, which `hair_style` sets with the growth): coils finer
// than the guides' vertices are drawn, not grown (shaders/shared/strands.h coilAt), and need the
// divisions to draw them.
struct StyleDrawing {
    float coilRadiusMetres = 0.0f;
    float coilTurnsPerMetre = 0.0f;
    uint32_t divisions = 24;       // the renderer's default (renderer/settings.h StrandSettings)
    uint32_t strandsPerGuide = 46; // likewise: about 100,000 strands from 2,200 guides
    float lengthJitter = 0.15f;    // strand_length_jitter: drawn strands cut from the tip by up to this share
};

struct HairStyle {
    const char* name;
    const char* description;
    GrowthSettings growth; // every parameter but the seed
    StyleDrawing drawn;
};

// bob (the default: GrowthSettings{}), long, wavy, crop, bangs, afro.
const std::array<HairStyle, 6>& hairStyles();
// The style of that name, or nullptr.
const HairStyle* findHairStyle(std::string_view name);
// Sets every parameter of the style, keeping the seed.
void applyHairStyle(GrowthSettings& growth, const HairStyle& style);
// Whether the settings are the style's (the seed aside).
bool isHairStyle(const GrowthSettings& growth, const HairStyle& style);

} // namespace wisp
