// shading/hair_bsdf.cpp: the reference hair BSDF (Chiang et al. 2016 as pbrt-v3 defines it),
// written from the formulas of the papers and of Pharr's "The Implementation of a Hair Scattering
// Model" (2016). Single precision as pbrt, except the Bessel function (double).
#include "shading/hair_bsdf.h"

#include "core/error.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>

namespace wisp::shading {

namespace {

constexpr float kPi = std::numbers::pi_v<float>;

float sqr(float x)
{
    return x * x;
}

float safeSqrt(float x)
{
    return std::sqrt(std::max(0.0f, x));
}

float safeAsin(float x)
{
    return std::asin(std::clamp(x, -1.0f, 1.0f));
}

glm::vec3 expv(glm::vec3 x)
{
    return {std::exp(x.x), std::exp(x.y), std::exp(x.z)};
}

// The chosen direction's angles in the hair frame.
struct FrameAngles {
    float sinTheta;
    float cosTheta;
    float phi;
};

FrameAngles frameAngles(glm::vec3 w)
{
    return {w.x, safeSqrt(1.0f - sqr(w.x)), std::atan2(w.z, w.y)};
}

// Chiang 2016 eq. 9's polynomial in beta_n.
float colorPolynomial(float bn)
{
    float b2 = bn * bn, b3 = b2 * bn, b4 = b3 * bn, b5 = b4 * bn;
    return 5.969f - 0.215f * bn + 2.532f * b2 - 10.73f * b3 + 5.574f * b4 + 0.245f * b5;
}

// Compared as floats: 0.01f is a little below the double 0.01, and must pass as the range's end.
void checkRange(const char* name, float value, Range r)
{
    if (!(value >= float(r.min) && value <= float(r.max))) { // also rejects NaN
        char buf[160];
        std::snprintf(buf, sizeof buf, "hair parameter %s = %g is outside [%g, %g]", name, double(value), double(r.min),
                      double(r.max));
        throw UserError(buf);
    }
}

float logistic(float x, float s)
{
    x = std::abs(x);
    if (x > 80.0f * s)
        return 0.0f; // below 1e-34 / s: skip the denormals exp would produce (they are slow)
    float e = std::exp(-x / s);
    return e / (s * sqr(1.0f + e));
}

float logisticCdf(float x, float s)
{
    return 1.0f / (1.0f + std::exp(-x / s));
}

float trimmedLogistic(float x, float s, float a, float b)
{
    return logistic(x, s) / (logisticCdf(b, s) - logisticCdf(a, s));
}

float sampleTrimmedLogistic(float u, float s, float a, float b)
{
    float k = logisticCdf(b, s) - logisticCdf(a, s);
    float x = -s * std::log(1.0f / (u * k + logisticCdf(a, s)) - 1.0f);
    return std::clamp(x, a, b);
}

// Phi(p, gamma_o, gamma_t): the azimuth where a ray entering at offset h leaves after p internal
// paths (Chiang 2016, after d'Eon et al. 2011).
float phiExit(int p, float gammaO, float gammaT)
{
    return 2.0f * float(p) * gammaT - 2.0f * gammaO + float(p) * kPi;
}

// The modified index eta' for the projection into the normal plane (Bravais), gamma_t and the
// transmittance of one pass through the cylinder, T = exp(-sigma_a * 2 cos(gamma_t) / cos(theta_t)).
struct Refraction {
    float gammaT;
    glm::vec3 transmittance;
};

Refraction refract(float sinThetaO, float cosThetaO, float eta, float h, glm::vec3 sigmaA)
{
    float sinThetaT = sinThetaO / eta;
    float cosThetaT = safeSqrt(1.0f - sqr(sinThetaT));
    float etap = std::sqrt(eta * eta - sqr(sinThetaO)) / cosThetaO;
    float sinGammaT = h / etap;
    float cosGammaT = safeSqrt(1.0f - sqr(sinGammaT));
    return {safeAsin(sinGammaT), expv(-sigmaA * (2.0f * cosGammaT / cosThetaT))};
}

} // namespace

glm::vec3 sigmaAFromMelanin(float eumelanin, float pheomelanin)
{
    return eumelanin * kEumelaninSigmaA + pheomelanin * kPheomelaninSigmaA;
}

glm::vec3 sigmaAFromColor(glm::vec3 color, float betaN)
{
    checkRange("beta_n", betaN, kBetaRange);
    for (int i = 0; i < 3; ++i)
        checkRange("color", color[i], kColorRange);
    float d = colorPolynomial(betaN);
    glm::vec3 l{std::log(color.x) / d, std::log(color.y) / d, std::log(color.z) / d};
    return l * l;
}

glm::vec3 colorFromSigmaA(glm::vec3 sigmaA, float betaN)
{
    float d = colorPolynomial(betaN);
    return expv(-glm::vec3(std::sqrt(sigmaA.x), std::sqrt(sigmaA.y), std::sqrt(sigmaA.z)) * d);
}

void validate(const HairParams& p)
{
    checkRange("h", p.h, kHRange);
    checkRange("eta", p.eta, kEtaRange);
    checkRange("beta_m", p.betaM, kBetaRange);
    checkRange("beta_n", p.betaN, kBetaRange);
    checkRange("alpha (degrees)", p.alphaDeg, kAlphaDegRange);
    for (int i = 0; i < 3; ++i)
        checkRange("sigma_a", p.sigmaA[i], kSigmaARange);
}

// I0(x) = sum_i (x^2 / 4)^i / (i!)^2, summed until it converges. (pbrt-v3's I0 stops after 10
// terms and computes 4^i (i!)^2 in int, which overflows from i = 7; the true series is used here.)
double besselI0(double x)
{
    double term = 1.0, sum = 1.0, q = 0.25 * x * x;
    for (int i = 1; i < 100 && term > 1e-17 * sum; ++i) {
        term *= q / (double(i) * double(i));
        sum += term;
    }
    return sum;
}

// Above 12, the asymptotic expansion I0(x) ~ e^x / sqrt(2 pi x) (1 + 1/(8x) + 9/(128x^2)) (Abramowitz
// & Stegun 9.7.1), relative error below 1e-5 there. (pbrt-v3 writes the 1/(8x) inside the factor 1/2,
// i.e. 1/(16x): 0.5% low at 12.)
double logBesselI0(double x)
{
    if (x > 12.0)
        return x - 0.5 * std::log(2.0 * std::numbers::pi * x) + std::log1p(1.0 / (8.0 * x) + 9.0 / (128.0 * x * x));
    return std::log(besselI0(x));
}

// d'Eon et al. 2011 eq. 6: M_p = csch(1/v) / (2v) * exp(-sin_i sin_o / v) * I0(cos_i cos_o / v);
// for v <= 0.1 in log form (as pbrt), with log(csch(1/v)) = -1/v + ln 2 + log(1 / (1 - e^(-2/v))),
// the last term below 5e-9 there.
float longitudinalScattering(float cosThetaI, float cosThetaO, float sinThetaI, float sinThetaO, float v)
{
    double a = double(cosThetaI) * double(cosThetaO) / double(v);
    double b = double(sinThetaI) * double(sinThetaO) / double(v);
    double dv = v;
    double mp = v <= 0.1f ? std::exp(logBesselI0(a) - b - 1.0 / dv + std::numbers::ln2 + std::log(1.0 / (2.0 * dv)))
                          : std::exp(-b) * besselI0(a) / (std::sinh(1.0 / dv) * 2.0 * dv);
    return float(mp);
}

float azimuthalScattering(float phi, int p, float s, float gammaO, float gammaT)
{
    float dphi = phi - phiExit(p, gammaO, gammaT);
    while (dphi > kPi)
        dphi -= 2.0f * kPi;
    while (dphi < -kPi)
        dphi += 2.0f * kPi;
    return trimmedLogistic(dphi, s, -kPi, kPi);
}

float fresnelDielectric(float cosThetaI, float eta)
{
    cosThetaI = std::clamp(cosThetaI, -1.0f, 1.0f);
    float etaI = 1.0f, etaT = eta;
    if (cosThetaI < 0.0f) { // leaving the fibre
        std::swap(etaI, etaT);
        cosThetaI = -cosThetaI;
    }
    float sinThetaI = safeSqrt(1.0f - cosThetaI * cosThetaI);
    float sinThetaT = etaI / etaT * sinThetaI;
    if (sinThetaT >= 1.0f)
        return 1.0f; // total internal reflection
    float cosThetaT = safeSqrt(1.0f - sinThetaT * sinThetaT);
    float parallel = (etaT * cosThetaI - etaI * cosThetaT) / (etaT * cosThetaI + etaI * cosThetaT);
    float perpendicular = (etaI * cosThetaI - etaT * cosThetaT) / (etaI * cosThetaI + etaT * cosThetaT);
    return 0.5f * (parallel * parallel + perpendicular * perpendicular);
}

// Chiang 2016 eq. 3-4 (pbrt's Ap): Fresnel at the entry point (cos = cos(theta_o) cos(gamma_o)),
// one T per internal path, and the residual as the geometric series of the remaining orders.
Attenuations attenuation(float cosThetaO, float eta, float h, glm::vec3 transmittance)
{
    Attenuations ap;
    float cosGammaO = safeSqrt(1.0f - h * h);
    float f = fresnelDielectric(cosThetaO * cosGammaO, eta);
    ap[0] = glm::vec3(f);
    ap[1] = sqr(1.0f - f) * transmittance;
    for (int p = 2; p < kPMax; ++p)
        ap[size_t(p)] = ap[size_t(p - 1)] * transmittance * f;
    ap[kPMax] = ap[kPMax - 1] * f * transmittance / (glm::vec3(1.0f) - transmittance * f);
    return ap;
}

// pbrt's polynomial fits (Chiang 2016 eq. 7 and 8, with s scaled by sqrt(pi / 8)).
float longitudinalVariance(float betaM)
{
    return sqr(0.726f * betaM + 0.812f * sqr(betaM) + 3.7f * std::pow(betaM, 20.0f));
}

float logisticScale(float betaN)
{
    return 0.626657069f * (0.265f * betaN + 1.194f * sqr(betaN) + 5.372f * std::pow(betaN, 22.0f));
}

HairLobes::HairLobes(const HairParams& p)
{
    v[0] = longitudinalVariance(p.betaM);
    v[1] = 0.25f * v[0];
    v[2] = 4.0f * v[0];
    for (size_t i = 3; i <= kPMax; ++i)
        v[i] = v[2];
    s = logisticScale(p.betaN);
    sin2kAlpha[0] = std::sin(p.alphaDeg * kPi / 180.0f);
    cos2kAlpha[0] = safeSqrt(1.0f - sqr(sin2kAlpha[0]));
    for (size_t i = 1; i < 3; ++i) {
        sin2kAlpha[i] = 2.0f * cos2kAlpha[i - 1] * sin2kAlpha[i - 1];
        cos2kAlpha[i] = sqr(cos2kAlpha[i - 1]) - sqr(sin2kAlpha[i - 1]);
    }
}

// R: theta_o - 2 alpha; TT: theta_o + alpha; TRT: theta_o + 4 alpha (Marschner 2003's shifts, in
// pbrt-v3's sign convention for its frame).
void HairLobes::tiltedThetaO(int p, float sinThetaO, float cosThetaO, float& sinThetaOp, float& cosThetaOp) const
{
    if (p == 0) {
        sinThetaOp = sinThetaO * cos2kAlpha[1] - cosThetaO * sin2kAlpha[1];
        cosThetaOp = cosThetaO * cos2kAlpha[1] + sinThetaO * sin2kAlpha[1];
    } else if (p == 1) {
        sinThetaOp = sinThetaO * cos2kAlpha[0] + cosThetaO * sin2kAlpha[0];
        cosThetaOp = cosThetaO * cos2kAlpha[0] - sinThetaO * sin2kAlpha[0];
    } else if (p == 2) {
        sinThetaOp = sinThetaO * cos2kAlpha[2] + cosThetaO * sin2kAlpha[2];
        cosThetaOp = cosThetaO * cos2kAlpha[2] - sinThetaO * sin2kAlpha[2];
    } else {
        sinThetaOp = sinThetaO;
        cosThetaOp = cosThetaO;
    }
    cosThetaOp = std::abs(cosThetaOp); // the tilt may carry theta_o past the pole
}

std::array<float, kPMax + 1> HairLobes::longitudinal(float sinThetaI, float sinThetaO) const
{
    float cosThetaI = safeSqrt(1.0f - sqr(sinThetaI));
    float cosThetaO = safeSqrt(1.0f - sqr(sinThetaO));
    std::array<float, kPMax + 1> m{};
    for (int p = 0; p <= kPMax; ++p) {
        float sinOp, cosOp;
        tiltedThetaO(p, sinThetaO, cosThetaO, sinOp, cosOp);
        m[size_t(p)] = longitudinalScattering(cosThetaI, cosOp, sinThetaI, sinOp, v[size_t(p)]);
    }
    return m;
}

HairBsdf::HairBsdf(const HairParams& p) : params_((validate(p), p)), lobes_(p), gammaO_(safeAsin(p.h)) {}

glm::vec3 HairBsdf::fsum(glm::vec3 wo, glm::vec3 wi) const
{
    FrameAngles o = frameAngles(wo), i = frameAngles(wi);
    Refraction r = refract(o.sinTheta, o.cosTheta, params_.eta, params_.h, params_.sigmaA);
    Attenuations ap = attenuation(o.cosTheta, params_.eta, params_.h, r.transmittance);
    float phi = i.phi - o.phi;
    std::array<float, kPMax + 1> m = lobes_.longitudinal(i.sinTheta, o.sinTheta);
    glm::vec3 sum(0.0f);
    for (int p = 0; p < kPMax; ++p)
        sum += m[size_t(p)] * ap[size_t(p)] * azimuthalScattering(phi, p, lobes_.s, gammaO_, r.gammaT);
    sum += m[kPMax] * ap[kPMax] / (2.0f * kPi);
    return sum;
}

glm::vec3 HairBsdf::f(glm::vec3 wo, glm::vec3 wi) const
{
    glm::vec3 sum = fsum(wo, wi);
    float cosWi = std::abs(wi.z);
    return cosWi > 0.0f ? sum / cosWi : sum;
}

std::array<float, kPMax + 1> HairBsdf::lobePdf(float cosThetaO) const
{
    float sinThetaO = safeSqrt(1.0f - cosThetaO * cosThetaO);
    Refraction r = refract(sinThetaO, cosThetaO, params_.eta, params_.h, params_.sigmaA);
    Attenuations ap = attenuation(cosThetaO, params_.eta, params_.h, r.transmittance);
    std::array<float, kPMax + 1> pdf{};
    float sum = 0.0f;
    for (size_t p = 0; p <= kPMax; ++p)
        sum += luminance(ap[p]);
    for (size_t p = 0; p <= kPMax; ++p)
        pdf[p] = luminance(ap[p]) / sum;
    return pdf;
}

glm::vec3 HairBsdf::sampleF(glm::vec3 wo, const std::array<float, 4>& u, glm::vec3* wi, float* pdfOut) const
{
    FrameAngles o = frameAngles(wo);
    std::array<float, kPMax + 1> apPdf = lobePdf(o.cosTheta);

    // The lobe, by the A_p luminances.
    float uLobe = u[0];
    int p = 0;
    for (; p < kPMax; ++p) {
        if (uLobe < apPdf[size_t(p)])
            break;
        uLobe -= apPdf[size_t(p)];
    }

    // theta_i from M_p around the tilted mirror direction -theta_o' (d'Eon et al. 2011's sampling:
    // the angle to that direction from its cosine's exact inverse CDF, then a uniform turn around it).
    float sinOp, cosOp;
    lobes_.tiltedThetaO(p, o.sinTheta, o.cosTheta, sinOp, cosOp);
    float v = lobes_.v[size_t(p)];
    float u2 = std::max(u[2], 1e-5f);
    float cosTheta = 1.0f + v * std::log(u2 + (1.0f - u2) * std::exp(-2.0f / v));
    float sinTheta = safeSqrt(1.0f - sqr(cosTheta));
    float cosPhi = std::cos(2.0f * kPi * u[3]);
    float sinThetaI = -cosTheta * sinOp + sinTheta * cosPhi * cosOp;
    float cosThetaI = safeSqrt(1.0f - sqr(sinThetaI));

    // The azimuth from the trimmed logistic around Phi (uniform for the residual).
    Refraction r = refract(o.sinTheta, o.cosTheta, params_.eta, params_.h, params_.sigmaA);
    float dphi = p < kPMax ? phiExit(p, gammaO_, r.gammaT) + sampleTrimmedLogistic(u[1], lobes_.s, -kPi, kPi)
                           : 2.0f * kPi * u[1];
    float phiI = o.phi + dphi;
    *wi = glm::vec3(sinThetaI, cosThetaI * std::cos(phiI), cosThetaI * std::sin(phiI));

    // The pdf of the whole mixture at the sampled direction.
    std::array<float, kPMax + 1> m = lobes_.longitudinal(sinThetaI, o.sinTheta);
    float pdf = 0.0f;
    for (int q = 0; q < kPMax; ++q)
        pdf += m[size_t(q)] * apPdf[size_t(q)] * azimuthalScattering(dphi, q, lobes_.s, gammaO_, r.gammaT);
    pdf += m[kPMax] * apPdf[kPMax] / (2.0f * kPi);
    *pdfOut = pdf;
    return f(wo, *wi);
}

float HairBsdf::pdf(glm::vec3 wo, glm::vec3 wi) const
{
    FrameAngles o = frameAngles(wo), i = frameAngles(wi);
    Refraction r = refract(o.sinTheta, o.cosTheta, params_.eta, params_.h, params_.sigmaA);
    std::array<float, kPMax + 1> apPdf = lobePdf(o.cosTheta);
    std::array<float, kPMax + 1> m = lobes_.longitudinal(i.sinTheta, o.sinTheta);
    float phi = i.phi - o.phi;
    float pdf = 0.0f;
    for (int p = 0; p < kPMax; ++p)
        pdf += m[size_t(p)] * apPdf[size_t(p)] * azimuthalScattering(phi, p, lobes_.s, gammaO_, r.gammaT);
    pdf += m[kPMax] * apPdf[kPMax] / (2.0f * kPi);
    return pdf;
}

FiberAverage::FiberAverage(const HairParams& p, float sinThetaO, int hSamples) : s_(logisticScale(p.betaN))
{
    validate(p);
    float cosThetaO = safeSqrt(1.0f - sqr(sinThetaO));
    samples_.reserve(size_t(hSamples));
    double total = 0.0;
    for (int k = 0; k < hSamples; ++k) {
        float gamma = -0.5f * kPi + (float(k) + 0.5f) * kPi / float(hSamples);
        float h = std::sin(gamma);
        Refraction r = refract(sinThetaO, cosThetaO, p.eta, h, p.sigmaA);
        Attenuations ap = attenuation(cosThetaO, p.eta, h, r.transmittance);
        Sample s{std::cos(gamma), gamma, r.gammaT, {ap[0], ap[1], ap[2]}};
        residual_ += s.weight * ap[kPMax];
        total += double(s.weight);
        samples_.push_back(s);
    }
    float norm = float(1.0 / total);
    for (Sample& s : samples_)
        s.weight *= norm;
    residual_ *= norm / (2.0f * kPi);
}

// The same sum as azimuthalScattering over the samples, with the logistic's trim factor taken out
// of the loop (this is the lookup tables' inner loop).
std::array<glm::vec3, kPMax> FiberAverage::azimuthalAll(float phi) const
{
    std::array<glm::vec3, kPMax> n{};
    for (const Sample& s : samples_) {
        for (int p = 0; p < kPMax; ++p) {
            float dphi = std::remainder(phi - phiExit(p, s.gammaO, s.gammaT), 2.0f * kPi); // in [-pi, pi]
            n[size_t(p)] += (s.weight * logistic(dphi, s_)) * s.ap[size_t(p)];
        }
    }
    float trim = 1.0f / (logisticCdf(kPi, s_) - logisticCdf(-kPi, s_));
    for (glm::vec3& v : n)
        v *= trim;
    return n;
}

glm::vec3 FiberAverage::azimuthal(int p, float phi) const
{
    glm::vec3 n(0.0f);
    for (const Sample& s : samples_)
        n += s.weight * s.ap[size_t(p)] * azimuthalScattering(phi, p, s_, s.gammaO, s.gammaT);
    return n;
}

glm::vec3 FiberAverage::meanAttenuation(int p) const
{
    if (p >= kPMax)
        return residual_ * (2.0f * kPi);
    glm::vec3 a(0.0f);
    for (const Sample& s : samples_)
        a += s.weight * s.ap[size_t(p)];
    return a;
}

glm::vec3 fiberAveragedFsum(const HairLobes& lobes, const FiberAverage& average, glm::vec3 wo, glm::vec3 wi)
{
    FrameAngles o = frameAngles(wo), i = frameAngles(wi);
    std::array<float, kPMax + 1> m = lobes.longitudinal(i.sinTheta, o.sinTheta);
    std::array<glm::vec3, kPMax> n = average.azimuthalAll(i.phi - o.phi);
    glm::vec3 sum = m[kPMax] * average.residual();
    for (size_t p = 0; p < kPMax; ++p)
        sum += m[p] * n[p];
    return sum;
}

glm::vec3 fiberAveragedFsum(const HairParams& p, glm::vec3 wo, glm::vec3 wi, int hSamples)
{
    return fiberAveragedFsum(HairLobes(p), FiberAverage(p, wo.x, hSamples), wo, wi);
}

float luminance(glm::vec3 c)
{
    return 0.212671f * c.x + 0.715160f * c.y + 0.072169f * c.z;
}

} // namespace wisp::shading
