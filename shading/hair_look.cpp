// shading/hair_look.cpp: looks to parameters, and the presets.
#include "shading/hair_look.h"

#include <array>

namespace wisp {

shading::HairParams hairParams(const HairLook& look)
{
    shading::HairParams p;
    p.eta = look.eta;
    p.betaM = look.betaM;
    p.betaN = look.betaN;
    p.alphaDeg = look.cuticleTiltDeg;
    p.sigmaA = look.useColor ? shading::sigmaAFromColor(look.color, look.betaN)
                             : shading::sigmaAFromMelanin(look.eumelanin, look.pheomelanin);
    return p;
}

bool applyHairPreset(HairLook& look, const std::string& name)
{
    // Melanin concentrations in the range Chiang et al. 2016 show for these colours (their figure
    // of eumelanin 0..8 and pheomelanin mixes), chosen by looking at Wisp's own renders.
    struct Preset {
        const char* name;
        float eumelanin;
        float pheomelanin;
    };
    constexpr std::array<Preset, 4> kPresets = {{{"black", 8.0f, 0.0f},
                                                 {"brown", 1.3f, 0.2f},
                                                 {"auburn", 0.35f, 2.2f},
                                                 {"blonde", 0.15f, 0.12f}}};
    for (const Preset& p : kPresets) {
        if (name == p.name) {
            look.useColor = false;
            look.eumelanin = p.eumelanin;
            look.pheomelanin = p.pheomelanin;
            return true;
        }
    }
    return false;
}

}  // namespace wisp
