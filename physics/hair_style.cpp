// physics/hair_style.cpp: the styles' parameters. Lengths in metres on an adult head.
#include "physics/hair_style.h"

namespace wisp {

namespace {

std::array<HairStyle, 6> makeStyles()
{
    GrowthSettings bob; // the defaults: a chin-length A-line bob with a side parting

    GrowthSettings longHair;
    longHair.parting = Parting::Centre;
    // Combed down and to the sides from the parting, not back over the top: combed back, the front
    // hairline's strands ran sideways across it and their roots read as a blunt, ragged edge from
    // the front, and the hair at the sides fell sparsely onto the shoulders (streaks of shoulder
    // between strands from above). Down, it falls over the hairline's corners like curtains.
    longHair.fallBack = 0.2f;
    longHair.lengthMetres = 0.5f;
    longHair.lengthVariation = 0.06f;
    longHair.trimLevelMetres = 0.0f;
    longHair.volumeMetres = 0.01f;
    longHair.clumpStrength = 0.5f;
    longHair.globalStiffness = 0.003f;
    longHair.localStiffness = 0.1f;

    GrowthSettings wavy;
    wavy.lengthMetres = 0.36f;
    wavy.trimLevelMetres = 0.27f;
    wavy.trimSlope = 0.0f;
    wavy.trimJitterMetres = 0.006f;
    wavy.waveMetres = 0.02f;
    wavy.waveLengthMetres = 0.09f;
    wavy.volumeMetres = 0.02f;
    wavy.clumpStrength = 0.55f;
    wavy.clumpSizeMetres = 0.016f;
    wavy.frizzMetres = 0.003f;
    wavy.localStiffness = 0.2f;

    // Brushed up and back from a short front: lifted (26 degrees) and combed back hard (fall_back
    // 1.6), short at the hairline over a wide band (a fifth of the length over 2 cm) and lying close
    // (volume 2 mm), so that its front reads from the front as short tufts. Lifted less, combed back
    // less or longer at the hairline (22 degrees, fall_back 1.2, 0.35 of the length over 1.2 cm),
    // the front reads as a cap's rim: a smooth dark band along the forehead.
    GrowthSettings crop;
    crop.parting = Parting::None;
    crop.fallBack = 1.6f;
    crop.lengthMetres = 0.055f;
    crop.lengthVariation = 0.2f;
    crop.trimLevelMetres = 0.0f;
    crop.rootLiftDeg = 26.0f;
    crop.styleGravity = 0.4f;
    crop.volumeMetres = 0.002f;
    crop.hairlineBandMetres = 0.02f;
    crop.hairlineLength = 0.2f;
    crop.clumpSizeMetres = 0.008f;
    crop.clumpStrength = 0.3f;
    crop.frizzMetres = 0.001f;
    crop.flyaways = 0.0f;
    crop.globalStiffness = 0.05f;
    crop.localStiffness = 0.4f;

    GrowthSettings bangs;
    bangs.bangs = 1.0f;
    bangs.bangsLengthMetres = 0.085f;
    bangs.lengthMetres = 0.32f;
    bangs.trimLevelMetres = 0.21f;
    bangs.trimSlope = 0.0f;
    bangs.trimJitterMetres = 0.006f;
    bangs.partingOffsetMetres = 0.035f;
    bangs.globalStiffness = 0.03f; // bangs hold their line over the forehead
    bangs.localStiffness = 0.3f;

    GrowthSettings afro;
    afro.verticesPerStrand = 32;
    afro.guides = 2400;
    afro.parting = Parting::None;
    afro.fallBack = 0.3f;
    afro.crownWhorl = 0.3f;
    afro.rootLiftDeg = 55.0f;
    afro.styleGravity = 0.12f;
    afro.lengthMetres = 0.13f;
    afro.lengthVariation = 0.2f;
    afro.trimLevelMetres = 0.0f;
    afro.volumeMetres = 0.0f;
    afro.hairlineLength = 0.35f;
    afro.clumpSizeMetres = 0.01f;
    afro.clumpStrength = 0.25f;
    afro.curlRadiusMetres = 0.005f;
    afro.curlTurns = 6.0f;
    afro.curlRandomness = 0.35f;
    afro.frizzMetres = 0.004f;
    afro.flyaways = 0.0f;
    afro.globalStiffness = 0.05f;
    afro.localStiffness = 0.5f;
    // Coils of 1 cm a turn, 4 mm across, drawn about the grown 2 cm curls: a guide's 32 vertices
    // over 13 cm are 4 mm apart, too few for them. 96 divisions give a 13 cm strand's 13 turns 7
    // points each. Its 2,400 guides keep 32 strands each (76,800): every strand's 96 divisions
    // cost four times the segments of another style's.
    StyleDrawing afroDrawn{
        .coilRadiusMetres = 0.002f, .coilTurnsPerMetre = 100.0f, .divisions = 96, .strandsPerGuide = 32};

    // Each drawn strand is cut from its tip by up to strand_length_jitter of its guide's length
    // (StyleDrawing's default 0.15: the bob, the bangs, the afro), more where tips should thin out
    // over more of the length: the long and the wavy hair 0.2, the crop 0.35 (its 5 cm strands end
    // in tufts, not in one line along the forehead).
    return {{
        {"bob", "chin-length A-line bob with a side parting (the default)", bob, StyleDrawing{}},
        {"long", "long straight hair with a centre parting, over the shoulders", longHair,
         StyleDrawing{.lengthJitter = 0.2f}},
        {"wavy", "shoulder-length waves with a side parting", wavy, StyleDrawing{.lengthJitter = 0.2f}},
        {"crop", "a short crop combed back", crop, StyleDrawing{.lengthJitter = 0.35f}},
        {"bangs", "shoulder-length with a side parting and bangs over the forehead", bangs, StyleDrawing{}},
        {"afro", "curly, coily afro-textured hair standing out in a rounded shape", afro, afroDrawn},
    }};
}

} // namespace

const std::array<HairStyle, 6>& hairStyles()
{
    static const std::array<HairStyle, 6> styles = makeStyles();
    return styles;
}

const HairStyle* findHairStyle(std::string_view name)
{
    for (const HairStyle& s : hairStyles())
        if (name == s.name)
            return &s;
    return nullptr;
}

void applyHairStyle(GrowthSettings& growth, const HairStyle& style)
{
    uint32_t seed = growth.seed;
    growth = style.growth;
    growth.seed = seed;
}

bool isHairStyle(const GrowthSettings& growth, const HairStyle& style)
{
    GrowthSettings styled = style.growth;
    styled.seed = growth.seed;
    return styled == growth;
}

} // namespace wisp
