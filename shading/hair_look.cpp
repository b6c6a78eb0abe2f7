// shading/hair_look.cpp: looks to parameters, and the presets.
#include "shading/hair_look.h"

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
    for (const HairPreset& p : kHairPresets) {
        if (name == p.name) {
            look.useColor = false;
            look.eumelanin = p.eumelanin;
            look.pheomelanin = p.pheomelanin;
            return true;
        }
    }
    return false;
}

} // namespace wisp
