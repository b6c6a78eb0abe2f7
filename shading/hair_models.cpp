// shading/hair_models.cpp: packing HairMaterial, evaluating the shared header's models in C++, and
// measuring them against the reference.
#include "shading/hair_models.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <numbers>

namespace wisp::shading {

const char* modelName(HairModel m)
{
    switch (m) {
    case HairModel::Karis:
        return "karis";
    case HairModel::KajiyaKay:
        return "kajiya";
    case HairModel::Lut:
        return "lut";
    }
    return "?";
}

HairParams typicalHair()
{
    HairParams p;
    p.sigmaA = sigmaAFromMelanin(1.3f, 0.0f);
    p.betaM = 0.3f;
    p.betaN = 0.3f;
    p.alphaDeg = 2.0f;
    p.eta = 1.55f;
    return p;
}

gpu::HairMaterial packHairMaterial(const HairParams& p)
{
    validate(p);
    float alpha = p.alphaDeg * std::numbers::pi_v<float> / 180.0f;
    glm::vec3 color = colorFromSigmaA(p.sigmaA, p.betaN);
    HairLobes lobes(p);
    FiberAverage normal(p, 0.0f, 64);
    float lumColor = std::max(luminance(color), 1e-6f);
    gpu::HairMaterial m{};
    m.sigmaA = glm::vec4(p.sigmaA, p.eta);
    m.roughness = glm::vec4(p.betaM, p.betaN, alpha, 0.0f);
    m.baseColor = glm::vec4(color, 0.0f);
    m.kajiya = glm::vec4(alpha, -2.0f * alpha, 4.0f / lobes.v[0], 4.0f / lobes.v[2]);
    m.kajiyaWeights =
        glm::vec4(luminance(normal.meanAttenuation(1) + normal.meanAttenuation(kPMax)) / lumColor,
                  luminance(normal.meanAttenuation(0)), luminance(normal.meanAttenuation(2)) / lumColor, 0.0f);
    return m;
}

glm::vec3 evaluateModel(HairModel model, const gpu::HairMaterial& m, const HairLut& lut, glm::vec3 wo, glm::vec3 wi)
{
    const glm::vec3 t(1.0f, 0.0f, 0.0f);
    switch (model) {
    case HairModel::Karis:
        return gpu::hairKaris(t, wi, wo, m);
    case HairModel::KajiyaKay:
        return gpu::hairKajiyaKay(t, wi, wo, m);
    case HairModel::Lut:
        return evaluateHairLut(lut, t, wi, wo);
    }
    return glm::vec3(0.0f);
}

std::vector<glm::vec3> fibonacciSphere(int n)
{
    std::vector<glm::vec3> dirs;
    dirs.reserve(size_t(n));
    const double golden = std::numbers::pi * (3.0 - std::sqrt(5.0));
    for (int i = 0; i < n; ++i) {
        double z = 1.0 - (2.0 * i + 1.0) / n;
        double r = std::sqrt(std::max(0.0, 1.0 - z * z));
        double a = golden * i;
        dirs.emplace_back(float(z), float(r * std::cos(a)), float(r * std::sin(a))); // x (fibre) varies slowest
    }
    return dirs;
}

std::vector<ModelError> compareModels(const HairParams& p, const CompareOptions& o)
{
    validate(p);
    gpu::HairMaterial material = packHairMaterial(p);
    HairLut lut = buildHairLut(p);
    HairLobes lobes(p);
    std::vector<glm::vec3> outgoing = fibonacciSphere(o.outgoing), incoming = fibonacciSphere(o.incoming);

    struct Sums {
        double err2 = 0, lum = 0;
        bool ok = true;
    };
    Sums sums[std::size(kHairModels)];
    double ref2 = 0.0, refLum = 0.0;
    for (glm::vec3 wo : outgoing) {
        FiberAverage average(p, wo.x, o.hSamples);
        for (glm::vec3 wi : incoming) {
            glm::vec3 ref = fiberAveragedFsum(lobes, average, wo, wi);
            ref2 += double(glm::dot(ref, ref));
            refLum += double(luminance(ref));
            for (size_t k = 0; k < std::size(kHairModels); ++k) {
                glm::vec3 s = evaluateModel(kHairModels[k], material, lut, wo, wi);
                for (int c = 0; c < 3; ++c)
                    sums[k].ok = sums[k].ok && std::isfinite(s[c]) && s[c] >= 0.0f;
                glm::vec3 d = s - ref;
                sums[k].err2 += double(glm::dot(d, d));
                sums[k].lum += double(luminance(s));
            }
        }
    }
    std::vector<ModelError> errors;
    for (size_t k = 0; k < std::size(kHairModels); ++k)
        errors.push_back({kHairModels[k], std::sqrt(sums[k].err2 / ref2), sums[k].lum / refLum, sums[k].ok});
    return errors;
}

} // namespace wisp::shading
