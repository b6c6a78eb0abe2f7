// shading/hair_bsdf.h: the reference hair BSDF, on the CPU: the model of Chiang et al. 2016 ("A
// Practical and Controllable Hair and Fur Model for Production Path Tracing") as pbrt-v3 defines it
// (Pharr, "The Implementation of a Hair Scattering Model", and Physically Based Rendering 3rd ed.
// 9.9): lobes R, TT, TRT and the residual TRRT+, importance sampling, the melanin and colour
// mappings to the absorption sigma_a, and the BSDF averaged across the fibre's width (what the
// real-time models and the lookup tables approximate). No Vulkan; it is the ground truth.
//
// Local frame (pbrt's): x along the fibre, y and z span its normal plane (z the ribbon's normal);
// sin(theta) = w.x, phi = atan2(w.z, w.y). Both directions point away from the shading point.
#pragma once

#include "core/range.h"

#include <glm/glm.hpp>

#include <array>
#include <vector>

namespace wisp::shading {

inline constexpr int kPMax = 3; // lobes R, TT, TRT, then one residual lobe for p >= 3
using Attenuations = std::array<glm::vec3, kPMax + 1>;

// What the parameters may be (anything else throws UserError naming the parameter and range).
// beta_m and beta_n stop at 0.01: at 0 the longitudinal variance and the logistic scale are 0
// and the lobes become Dirac deltas, which this (non-delta) BSDF cannot represent.
// The look's settings (app/settings/settings_table.cpp) take the same ranges.
inline constexpr Range kHRange{-1.0, 1.0};
inline constexpr Range kEtaRange{1.0, 4.0};
inline constexpr Range kBetaRange{0.01, 1.0};
inline constexpr Range kAlphaDegRange{-10.0, 10.0};
inline constexpr Range kSigmaARange{0.0, 1000.0}; // per component, per unit fibre radius
inline constexpr Range kMelaninRange{0.0, 50.0};  // concentrations (pbrt: 1.3 brown, 8 black)
inline constexpr Range kColorRange{1e-4, 1.0};    // per component, for sigmaAFromColor

// Chiang 2016 (after d'Eon et al. 2011): absorption per unit concentration of the two melanins.
inline constexpr glm::vec3 kEumelaninSigmaA{0.419f, 0.697f, 1.37f};
inline constexpr glm::vec3 kPheomelaninSigmaA{0.187f, 0.4f, 1.05f};

// sigma_a = eumelanin * (0.419, 0.697, 1.37) + pheomelanin * (0.187, 0.4, 1.05).
glm::vec3 sigmaAFromMelanin(float eumelanin, float pheomelanin = 0.0f);
// Chiang 2016 eq. 9: the absorption that renders (after multiple scattering in a head of hair) as
// the colour c, for azimuthal roughness beta_n:
// sigma_a = (ln c / (5.969 - 0.215 bn + 2.532 bn^2 - 10.73 bn^3 + 5.574 bn^4 + 0.245 bn^5))^2.
glm::vec3 sigmaAFromColor(glm::vec3 color, float betaN);
// Its inverse: c = exp(-sqrt(sigma_a) * polynomial(beta_n)).
glm::vec3 colorFromSigmaA(glm::vec3 sigmaA, float betaN);

struct HairParams {
    float h = 0.0f;                             // offset across the fibre, [-1, 1]
    float eta = 1.55f;                          // index of refraction of the fibre
    glm::vec3 sigmaA = sigmaAFromMelanin(1.3f); // absorption per unit radius (brown by default)
    float betaM = 0.3f;                         // longitudinal roughness, [0.01, 1]
    float betaN = 0.3f;                         // azimuthal roughness, [0.01, 1]
    float alphaDeg = 2.0f;                      // cuticle scale tilt, degrees
};

// Throws wisp::UserError naming the first parameter outside its range.
void validate(const HairParams& p);

// pbrt's I0 (modified Bessel function of the first kind, order 0) and log I0 (asymptotic above 12).
double besselI0(double x);
double logBesselI0(double x);
// d'Eon et al. 2011's longitudinal scattering M_p with variance v (pbrt's Mp; the log form for
// v <= 0.1 avoids overflow). Normalised: its integral over theta_i with weight cos(theta_i) is 1.
float longitudinalScattering(float cosThetaI, float cosThetaO, float sinThetaI, float sinThetaO, float v);
// Chiang 2016's azimuthal term: the logistic of scale s trimmed to [-pi, pi], centred on
// Phi(p, gamma_o, gamma_t) = 2 p gamma_t - 2 gamma_o + p pi.
float azimuthalScattering(float phi, int p, float s, float gammaO, float gammaT);
// Unpolarised Fresnel reflectance of a dielectric interface (from outside, index eta inside).
float fresnelDielectric(float cosThetaI, float eta);
// A_p for p = 0..pMax (pbrt's Ap): f, (1-f)^2 T, (1-f)^2 f T^2 and the geometric-series residual.
Attenuations attenuation(float cosThetaO, float eta, float h, glm::vec3 transmittance);

// The per-parameter constants of the lobes: longitudinal variances (pbrt's polynomial mapping from
// beta_m, v_TT = v_R / 4, v_TRT = v_residual = 4 v_R), the logistic scale s from beta_n, and the
// cuticle tilt as sin/cos of alpha, 2 alpha, 4 alpha.
struct HairLobes {
    std::array<float, kPMax + 1> v{};
    float s = 0.0f;
    std::array<float, 3> sin2kAlpha{};
    std::array<float, 3> cos2kAlpha{};

    explicit HairLobes(const HairParams& p);
    // theta_o rotated by the scale tilt for lobe p (R: -2 alpha, TT: +alpha, TRT: +4 alpha, as pbrt
    // does), as sin and |cos|.
    void tiltedThetaO(int p, float sinThetaO, float cosThetaO, float& sinThetaOp, float& cosThetaOp) const;
    // M_p for every lobe (tilts applied to R, TT, TRT; none for the residual).
    std::array<float, kPMax + 1> longitudinal(float sinThetaI, float sinThetaO) const;
};

float longitudinalVariance(float betaM); // v_R
float logisticScale(float betaN);        // s

class HairBsdf {
public:
    explicit HairBsdf(const HairParams& p); // validates

    // pbrt-v3's HairBSDF::f: the lobe sum divided by |wi.z|.
    glm::vec3 f(glm::vec3 wo, glm::vec3 wi) const;
    // The lobe sum itself (pbrt's fsum) = f * |wi.z|: outgoing radiance per unit incoming radiance
    // and solid angle, the quantity the real-time models return.
    glm::vec3 fsum(glm::vec3 wo, glm::vec3 wi) const;
    // Importance sampling as pbrt-v3's Sample_f: a lobe chosen by the A_p luminance weights, then
    // M_p sampled exactly and the trimmed logistic N_p (uniform phi for the residual). u: four
    // uniform numbers in [0, 1) (lobe, azimuth, two for M_p). Returns f; *pdf per solid angle.
    glm::vec3 sampleF(glm::vec3 wo, const std::array<float, 4>& u, glm::vec3* wi, float* pdf) const;
    float pdf(glm::vec3 wo, glm::vec3 wi) const;
    // pbrt's ComputeApPdf: the A_p luminances normalised to sum to 1.
    std::array<float, kPMax + 1> lobePdf(float cosThetaO) const;

    const HairParams& params() const { return params_; }
    const HairLobes& lobes() const { return lobes_; }

private:
    HairParams params_;
    HairLobes lobes_;
    float gammaO_;
};

// The fibre as a whole: the BSDF averaged over the offset h across its width,
// S(wo, wi) = 1/2 Integral_{-1}^{1} fsum_h(wo, wi) dh, which is what a strand thinner than a pixel
// shows and what the real-time models and the lookup tables approximate. Integrated with the
// midpoint rule in gamma = asin(h) (dh = cos(gamma) dgamma, so the samples are uniform in the
// angle the azimuthal lobes move with), weights normalised to sum to 1.
inline constexpr int kReferenceHSamples = 128;

class FiberAverage {
public:
    // Everything that depends on theta_o alone (A_p, gamma_o, gamma_t per h sample).
    FiberAverage(const HairParams& p, float sinThetaO, int hSamples = kReferenceHSamples);
    // The h-average of A_p(h) N_p(phi; h) for p < kPMax; phi = phi_i - phi_o in radians.
    glm::vec3 azimuthal(int p, float phi) const;
    // The same for all of p < kPMax at once (shares the wrap of phi).
    std::array<glm::vec3, kPMax> azimuthalAll(float phi) const;
    // The h-average of A_pMax / (2 pi) (the residual lobe is uniform in phi).
    glm::vec3 residual() const { return residual_; }
    // The h-average of A_p alone (the lobe's albedo for this theta_o), p <= kPMax.
    glm::vec3 meanAttenuation(int p) const;

private:
    struct Sample {
        float weight;
        float gammaO;
        float gammaT;
        std::array<glm::vec3, kPMax> ap;
    };
    std::vector<Sample> samples_;
    float s_;
    glm::vec3 residual_{0.0f};
};

// S averaged over h for one direction pair (builds a FiberAverage; for many wi with one wo, build
// the FiberAverage once and use fiberAveragedFsum below).
glm::vec3 fiberAveragedFsum(const HairParams& p, glm::vec3 wo, glm::vec3 wi, int hSamples = kReferenceHSamples);
glm::vec3 fiberAveragedFsum(const HairLobes& lobes, const FiberAverage& average, glm::vec3 wo, glm::vec3 wi);

// Luminance as pbrt's RGBSpectrum::y() (Rec. 709 weights).
float luminance(glm::vec3 c);

} // namespace wisp::shading
