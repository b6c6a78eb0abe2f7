// shading/hair_lut.h: the lookup-table mode's tables (Nguyen & Donnelly 2005, GPU Gems 2 ch. 23:
// M and N precomputed), built on the CPU from the reference BSDF for one set of parameters, in the
// layout shaders/shared/hair_shading.h documents (kHairLutLayers RGBA32F layers of kHairLutSize^2),
// and their evaluation in C++ with the same bilinear, clamp-to-edge filtering a Vulkan linear
// sampler applies, so the CPU and the GPU read the same values.
#pragma once

#include "shaders/shared/hair_shading.h"
#include "shading/hair_bsdf.h"

#include <cstdint>
#include <vector>

namespace wisp::shading {

// Samples across the fibre for the N tables' average over h (midpoint rule in gamma = asin(h)).
inline constexpr int kHairLutHSamples = 64;

struct HairLut {
    uint32_t size = 0;
    // kHairLutLayers x size x size texels of 4 floats: layer-major, then rows (v), then columns (u).
    std::vector<float> texels;

    glm::vec4 texel(uint32_t layer, uint32_t x, uint32_t y) const;
    size_t bytes() const { return texels.size() * sizeof(float); }
};

// The tables for these parameters (params.h is ignored: the tables average over h). Validates.
// About 9 ms for the default 64^2 x 5 with 64 h samples on one core (docs/shading.md).
HairLut buildHairLut(const HairParams& p, uint32_t size = gpu::kHairLutSize, int hSamples = kHairLutHSamples);

// One layer read at normalised uv as VK_FILTER_LINEAR with VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE
// and unnormalizedCoordinates = false does: texel space u * size - 0.5, the two neighbours each
// clamped to [0, size - 1], weights from the fraction (exact here; a GPU rounds them to its
// subTexelPrecisionBits, usually 8).
glm::vec4 sampleHairLut(const HairLut& lut, uint32_t layer, glm::vec2 uv);

// The lookup mode's S for these directions: hairAngles, hairLutUvM/N and hairLutCombine from the
// shared header around sampleHairLut, as hairShadeLut does in GLSL.
glm::vec3 evaluateHairLut(const HairLut& lut, glm::vec3 t, glm::vec3 wi, glm::vec3 wo);

} // namespace wisp::shading
