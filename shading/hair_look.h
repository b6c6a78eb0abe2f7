// shading/hair_look.h: the hair's look as a user sets it (model, melanin or colour, roughness,
// variation), turned into the reference model's parameters
// (the GPU material and the lookup tables are both made from those), and the named presets.
#pragma once

#include "shading/hair_bsdf.h"

#include <glm/glm.hpp>

#include <array>
#include <string>

namespace wisp {

enum class ShadingModel { Karis, Kajiya, Lut };

// What the hair is made of and how it is shaded (shading/, shaders/shared/hair_shading.h). Its
// colour is absorption: from melanin concentrations (Chiang et al. 2016) or from an RGB colour
// the hair should look (sigmaAFromColor); strands vary around it, with streaks along them.
struct HairLook {
    ShadingModel model = ShadingModel::Karis;
    float eumelanin = 1.3f; // brown
    float pheomelanin = 0.2f;
    bool useColor = false; // colour below instead of melanin
    glm::vec3 color{0.3f, 0.2f, 0.12f};
    float betaM = 0.3f; // longitudinal roughness
    float betaN = 0.3f; // azimuthal roughness
    float cuticleTiltDeg = 2.0f;
    float eta = 1.55f;
    float variation = 0.3f;         // per-strand spread of absorption (0: every strand alike)
    float streaks = 0.35f;          // strength of lighter and darker streaks along strands
    float along = 1.0f;             // the absorption's fall from root to tip: 1 from 1.25 to 0.75 times, 0 none
    bool multipleScattering = true; // karis and lut add Karis's multiple scattering (kajiya has none)
};

// Named looks: melanin pairs in the range Chiang et al. 2016 show for these colours (their figure
// of eumelanin 0..8 and pheomelanin mixes), chosen by looking at Wisp's own renders.
struct HairPreset {
    const char* name;
    float eumelanin;
    float pheomelanin;
};
inline constexpr std::array<HairPreset, 4> kHairPresets = {
    {{"black", 8.0f, 0.0f}, {"brown", 1.3f, 0.2f}, {"auburn", 0.35f, 2.2f}, {"blonde", 0.15f, 0.12f}}};
// Sets the look's melanin to the preset `name` (and drops a colour); false for an unknown name.
bool applyHairPreset(HairLook& look, const std::string& name);

// The reference BSDF's parameters for a look (h = 0; the models average across the fibre).
shading::HairParams hairParams(const HairLook& look);

} // namespace wisp
