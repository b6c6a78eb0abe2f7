// renderer/hair_look.h: the hair look's settings turned into the reference model's parameters
// (the GPU material and the lookup tables are both made from those), and the named presets.
#pragma once

#include "renderer/settings.h"
#include "shading/hair_bsdf.h"

namespace wisp {

// The reference BSDF's parameters for a look (h = 0; the models average across the fibre).
shading::HairParams hairParams(const HairLook& look);

}  // namespace wisp
