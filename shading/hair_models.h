// shading/hair_models.h: the real-time hair models of shaders/shared/hair_shading.h on the CPU:
// the material block packed from the reference's parameters, one entry point per model, and their
// error against the reference (averaged across the fibre) over a sphere of directions.
#pragma once

#include "shaders/shared/hair_shading.h"
#include "shading/hair_bsdf.h"
#include "shading/hair_lut.h"

#include <string>
#include <vector>

namespace wisp::shading {

enum class HairModel { Karis, KajiyaKay, Lut };
inline constexpr HairModel kHairModels[] = {HairModel::Karis, HairModel::KajiyaKay, HairModel::Lut};
const char* modelName(HairModel m); // "karis", "kajiya", "lut"

// The GPU block for these parameters: sigma_a and eta, beta_m, beta_n, alpha in radians, the base
// colour (colorFromSigmaA), Kajiya-Kay lobes placed and sized like the reference's R and TRT
// (shifts alpha and -2 alpha, exponents 4 / v_R and 4 / v_TRT, so the lobes' widths in
// theta_i + theta_o match) and albedos from the reference's h-averaged A_p at normal incidence
// (primary = A_R; secondary and diffuse luminance-matched to A_TRT and A_TT + A_residual once
// multiplied by the base colour).
gpu::HairMaterial packHairMaterial(const HairParams& p);

// The models' S for the local frame's directions (fibre along x). `lut` is used by HairModel::Lut.
glm::vec3 evaluateModel(HairModel model, const gpu::HairMaterial& m, const HairLut& lut, glm::vec3 wo, glm::vec3 wi);

// n unit directions spread evenly over the sphere (Fibonacci lattice; no two at a pole).
std::vector<glm::vec3> fibonacciSphere(int n);

struct CompareOptions {
    int outgoing = 32;                 // directions wo (Fibonacci sphere)
    int incoming = 1024;               // directions wi for each wo (Fibonacci sphere)
    int hSamples = kReferenceHSamples; // the reference's average across the fibre
};

struct ModelError {
    HairModel model;
    // sqrt(sum (S_model - S_ref)^2 / sum S_ref^2) over every (wo, wi) pair and RGB channel.
    double relativeRms;
    // sum lum(S_model) / sum lum(S_ref): how bright the model is on average, relative to the reference.
    double brightness;
    bool finiteNonNegative; // every value of the model finite and >= 0
};

// Each model against the reference averaged over h (fiberAveragedFsum). Validates.
std::vector<ModelError> compareModels(const HairParams& p, const CompareOptions& o = {});

// The typical parameters docs/shading.md and the tests quote: brown hair (eumelanin 1.3), beta_m 0.3,
// beta_n 0.3, alpha 2 degrees, eta 1.55.
HairParams typicalHair();

} // namespace wisp::shading
