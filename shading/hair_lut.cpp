// shading/hair_lut.cpp: building the lookup-mode tables from the reference and reading them back
// the way a Vulkan linear sampler does.
#include "shading/hair_lut.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace wisp::shading {

namespace {

size_t texelIndex(uint32_t size, uint32_t layer, uint32_t x, uint32_t y)
{
    return ((size_t(layer) * size + y) * size + x) * 4;
}

void store(HairLut& lut, uint32_t layer, uint32_t x, uint32_t y, glm::vec4 value)
{
    size_t i = texelIndex(lut.size, layer, x, y);
    lut.texels[i + 0] = value.x;
    lut.texels[i + 1] = value.y;
    lut.texels[i + 2] = value.z;
    lut.texels[i + 3] = value.w;
}

// The texel centre of index i as the table's coordinate in [0, 1].
float centre(uint32_t i, uint32_t size)
{
    return (float(i) + 0.5f) / float(size);
}

} // namespace

glm::vec4 HairLut::texel(uint32_t layer, uint32_t x, uint32_t y) const
{
    size_t i = texelIndex(size, layer, x, y);
    return {texels[i], texels[i + 1], texels[i + 2], texels[i + 3]};
}

HairLut buildHairLut(const HairParams& params, uint32_t size, int hSamples)
{
    validate(params);
    HairLut lut;
    lut.size = size;
    lut.texels.assign(size_t(gpu::kHairLutLayers) * size * size * 4, 0.0f);
    HairLobes lobes(params);

    // Layer 0: M_p(sin theta_i = 2u - 1, sin theta_o = 2v - 1).
    for (uint32_t y = 0; y < size; ++y) {
        float sinThetaO = 2.0f * centre(y, size) - 1.0f;
        for (uint32_t x = 0; x < size; ++x) {
            std::array<float, kPMax + 1> m = lobes.longitudinal(2.0f * centre(x, size) - 1.0f, sinThetaO);
            store(lut, gpu::kHairLutLayerM, x, y, {m[0], m[1], m[2], m[3]});
        }
    }

    // Layers 1..4: the h-averaged A_p N_p(phi = pi u) at |sin theta_o| = v, and the residual.
    for (uint32_t y = 0; y < size; ++y) {
        FiberAverage average(params, centre(y, size), hSamples);
        glm::vec3 residual = average.residual();
        for (uint32_t x = 0; x < size; ++x) {
            std::array<glm::vec3, kPMax> n = average.azimuthalAll(std::numbers::pi_v<float> * centre(x, size));
            store(lut, gpu::kHairLutLayerNR, x, y, glm::vec4(n[0], 0.0f));
            store(lut, gpu::kHairLutLayerNTT, x, y, glm::vec4(n[1], 0.0f));
            store(lut, gpu::kHairLutLayerNTRT, x, y, glm::vec4(n[2], 0.0f));
            store(lut, gpu::kHairLutLayerNResidual, x, y, glm::vec4(residual, 0.0f));
        }
    }
    return lut;
}

glm::vec4 sampleHairLut(const HairLut& lut, uint32_t layer, glm::vec2 uv)
{
    int n = int(lut.size);
    float u = uv.x * float(n) - 0.5f;
    float v = uv.y * float(n) - 0.5f;
    float fu = std::floor(u), fv = std::floor(v);
    float a = u - fu, b = v - fv;
    auto clampIndex = [n](float i) { return uint32_t(std::clamp(int(i), 0, n - 1)); };
    uint32_t x0 = clampIndex(fu), x1 = clampIndex(fu + 1.0f);
    uint32_t y0 = clampIndex(fv), y1 = clampIndex(fv + 1.0f);
    return (1.0f - a) * (1.0f - b) * lut.texel(layer, x0, y0) + a * (1.0f - b) * lut.texel(layer, x1, y0) +
           (1.0f - a) * b * lut.texel(layer, x0, y1) + a * b * lut.texel(layer, x1, y1);
}

glm::vec3 evaluateHairLut(const HairLut& lut, glm::vec3 t, glm::vec3 wi, glm::vec3 wo)
{
    gpu::HairAngles a = gpu::hairAngles(t, wi, wo);
    glm::vec2 uvM = gpu::hairLutUvM(a);
    glm::vec2 uvN = gpu::hairLutUvN(a);
    return gpu::hairLutCombine(
        sampleHairLut(lut, gpu::kHairLutLayerM, uvM), sampleHairLut(lut, gpu::kHairLutLayerNR, uvN),
        sampleHairLut(lut, gpu::kHairLutLayerNTT, uvN), sampleHairLut(lut, gpu::kHairLutLayerNTRT, uvN),
        sampleHairLut(lut, gpu::kHairLutLayerNResidual, uvN));
}

} // namespace wisp::shading
