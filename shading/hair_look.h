// shading/hair_look.h: the hair's look as a user sets it (model, melanin or colour, roughness,
// variation), turned into the reference model's parameters
// (the GPU material and the lookup tables are both made from those), and the named presets.
#pragma once

#include "core/range.h"
#include "shading/hair_bsdf.h"

#include <glm/glm.hpp>

#include <string>

namespace wisp {

enum class ShadingModel { Karis, Kajiya, Lut };

inline constexpr Range kMelaninRange{0.0, 20.0};        // concentration (Chiang 2016: ~8 black, ~1.3 brown, ~0.3 blonde)
inline constexpr Range kRoughnessRange{0.01, 1.0};      // beta_m, beta_n
inline constexpr Range kCuticleTiltRange{-10.0, 10.0};  // degrees
inline constexpr Range kEtaRange{1.0, 4.0};
inline constexpr Range kVariationRange{0.0, 1.0};

// What the hair is made of and how it is shaded (shading/, shaders/shared/hair_shading.h). Its
// colour is absorption: from melanin concentrations (Chiang et al. 2016) or from an RGB colour
// the hair should look (sigmaAFromColor); strands vary around it, with streaks along them.
struct HairLook {
    ShadingModel model = ShadingModel::Karis;
    float eumelanin = 1.3f;          // brown
    float pheomelanin = 0.2f;
    bool useColor = false;           // colour below instead of melanin
    glm::vec3 color{0.3f, 0.2f, 0.12f};
    float betaM = 0.3f;              // longitudinal roughness
    float betaN = 0.3f;              // azimuthal roughness
    float cuticleTiltDeg = 2.0f;
    float eta = 1.55f;
    float variation = 0.3f;          // per-strand spread of absorption (0: every strand alike)
    float streaks = 0.35f;           // strength of lighter and darker streaks along strands
};

// Named looks: black, brown, auburn, blonde (melanin pairs). Returns false for an unknown name.
bool applyHairPreset(HairLook& look, const std::string& name);
inline constexpr const char* kHairPresets = "black | brown | auburn | blonde";

// The reference BSDF's parameters for a look (h = 0; the models average across the fibre).
shading::HairParams hairParams(const HairLook& look);

}  // namespace wisp
