// shaders/shared/fiber_bsdf.h: the exact fibre BSDF of Chiang et al. 2016 ("A Practical and
// Controllable Hair and Fur Model for Production Path Tracing") as pbrt-v3 implements it (Pharr,
// "The Implementation of a Hair Scattering Model", 2016; PBR 3rd ed. 9.9), for one hit at offset h
// across the fibre: eval, importance sampling (pbrt's HairBSDF::Sample_f) and pdf. One copy for
// GLSL (the path tracer, shaders/reference_trace.comp) and C++ (its CPU twin and the tests, which
// compare it with the CPU ground truth of shading/hair_bsdf.cpp on random inputs).
//
// Conventions (pbrt's local frame, as shading/hair_bsdf.h): x along the fibre (root to tip), y and
// z span its normal plane, z the surface normal's component the ray saw (h = the offset across the
// fibre, in [-1, 1]); sin(theta) = w.x, phi = atan(w.z, w.y). Both directions point away from the
// shading point. fiberFsum is pbrt's lobe sum (f * |wi.z|), fiberF its f = fsum / |wi.z|; a path
// tracer weighs a sampled direction by f * |cos| / pdf = fsum / pdf. sigma_a is per unit fibre radius.
//
// Single precision throughout, as pbrt. The one place where that costs accuracy is d'Eon et al.
// 2011's longitudinal term for narrow lobes (v <= 0.1), whose exponent
// cos_i cos_o / v - sin_i sin_o / v - 1 / v cancels near the lobe's peak (the CPU reference takes
// it in double): here it is written as -(1 - cos(theta_i + theta_o)) / v with
// 1 - cos(x) = sin(x)^2 / (1 + cos(x)), whose error near the peak is eps / sqrt(v), not eps / v.
#ifndef WISP_SHARED_FIBER_BSDF_H
#define WISP_SHARED_FIBER_BSDF_H
#include "prelude.h"

GPU_NAMESPACE_BEGIN

#ifdef __cplusplus
using glm::sinh;
#endif

GPU_CONST float kFiberPi = 3.14159265f;
// Lobes R (p = 0), TT, TRT, then one residual lobe for p >= 3 (pbrt's pMax).
GPU_CONST int kFiberPMax = 3;

// The fibre's material, as the path tracer's uniform block holds it (vec4 members only).
struct FiberMaterial {
    vec4 sigmaA; // xyz absorption per unit fibre radius, w index of refraction eta
    vec4 lobes;  // x v_R (pbrt's longitudinal variance from beta_m), y logistic scale s (from
                 // beta_n), z sin(alpha), w cos(alpha) (alpha the cuticle tilt)
};

// What a lobe evaluation needs, derived from the material once per hit (pbrt's HairBSDF members).
struct FiberBsdf {
    vec3 sigmaA;
    float eta;
    float h;         // offset across the fibre, [-1, 1]
    float gammaO;    // asin(h)
    float s;         // logistic scale
    vec4 v;          // longitudinal variances of R, TT, TRT, residual
    vec3 sin2kAlpha; // sin(alpha), sin(2 alpha), sin(4 alpha)
    vec3 cos2kAlpha;
};

GPU_FN float fiberSafeSqrt(float x)
{
    return sqrt(max(x, 0.0f));
}

// ---- Angles to float precision on every device ------------------------------------------------
// Vulkan lets a device's atan be off by 4096 ULP and its sin and cos by 2^-11 (absolute); lavapipe's
// are off by up to 1e-3 radians, which moves a narrow azimuthal lobe (beta_n = 0.1: logistic scale
// 0.024) by 4%. The BSDF takes its angles from these instead: polynomials after range reduction,
// within a few ULP of the C library's on the CPU and the same on any GPU.

// atan(x) for 0 <= x <= 1: above tan(pi/8), pi/4 + atan((x - 1) / (x + 1)); then the Taylor series
// to x^15 (|x| <= tan(pi/8): the next term is below 2e-8).
GPU_FN float fiberAtanUnit(float x)
{
    bool shifted = x > 0.41421356f;
    float r = shifted ? (x - 1.0f) / (x + 1.0f) : x;
    float r2 = r * r;
    float p = -1.0f / 15.0f;
    p = 1.0f / 13.0f + r2 * p;
    p = -1.0f / 11.0f + r2 * p;
    p = 1.0f / 9.0f + r2 * p;
    p = -1.0f / 7.0f + r2 * p;
    p = 1.0f / 5.0f + r2 * p;
    p = -1.0f / 3.0f + r2 * p;
    p = r + r * r2 * p;
    return shifted ? 0.785398163f + p : p;
}

GPU_FN float fiberAtan2(float y, float x)
{
    float ax = abs(x);
    float ay = abs(y);
    float hi = max(ax, ay);
    float a = hi > 0.0f ? fiberAtanUnit(min(ax, ay) / hi) : 0.0f;
    if (ay > ax)
        a = 1.57079633f - a;
    if (x < 0.0f)
        a = 3.14159265f - a;
    return y < 0.0f ? -a : a;
}

GPU_FN float fiberAsin(float x)
{
    x = clamp(x, -1.0f, 1.0f);
    return fiberAtan2(x, sqrt((1.0f - x) * (1.0f + x)));
}

// (sin(x), cos(x)): x reduced by k pi/2 (Cody and Waite's three-part pi/2, exact products for
// |k| < 2^13), then Taylor polynomials on [-pi/4, pi/4] (errors below 2e-9).
GPU_FN vec2 fiberSinCos(float x)
{
    float k = floor(x * 0.636619772f + 0.5f);
    float r = ((x - k * 1.5703125f) - k * 4.837512969970703e-4f) - k * 7.549790126404332e-8f;
    float r2 = r * r;
    float sp = 1.0f / 362880.0f;
    sp = -1.0f / 5040.0f + r2 * sp;
    sp = 1.0f / 120.0f + r2 * sp;
    sp = -1.0f / 6.0f + r2 * sp;
    float sr = r + r * r2 * sp;
    float cp = -1.0f / 3628800.0f;
    cp = 1.0f / 40320.0f + r2 * cp;
    cp = -1.0f / 720.0f + r2 * cp;
    cp = 1.0f / 24.0f + r2 * cp;
    cp = -0.5f + r2 * cp;
    float cr = 1.0f + r2 * cp;
    int q = int(k) & 3;
    if (q == 0)
        return vec2(sr, cr);
    if (q == 1)
        return vec2(cr, -sr);
    if (q == 2)
        return vec2(-sr, -cr);
    return vec2(-cr, sr);
}

// pbrt's polynomial fits (Chiang 2016 eq. 7 and 8; s scaled by sqrt(pi / 8)).
GPU_FN float fiberLongitudinalVariance(float betaM)
{
    float b = 0.726f * betaM + 0.812f * betaM * betaM + 3.7f * pow(betaM, 20.0f);
    return b * b;
}

GPU_FN float fiberLogisticScale(float betaN)
{
    return 0.626657069f * (0.265f * betaN + 1.194f * betaN * betaN + 5.372f * pow(betaN, 22.0f));
}

// The material block for the reference's parameters (alpha in radians).
GPU_FN FiberMaterial makeFiberMaterial(vec3 sigmaA, float eta, float betaM, float betaN, float alpha)
{
    FiberMaterial m;
    m.sigmaA = vec4(sigmaA, eta);
    float sinAlpha = fiberSinCos(alpha).x;
    m.lobes = vec4(fiberLongitudinalVariance(betaM), fiberLogisticScale(betaN), sinAlpha,
                   fiberSafeSqrt(1.0f - sinAlpha * sinAlpha)); // cos as pbrt takes it
    return m;
}

GPU_FN FiberBsdf makeFiberBsdf(FiberMaterial m, float h)
{
    FiberBsdf b;
    b.sigmaA = vec3(m.sigmaA);
    b.eta = m.sigmaA.w;
    b.h = clamp(h, -1.0f, 1.0f);
    b.gammaO = fiberAsin(b.h);
    b.s = m.lobes.y;
    float vR = m.lobes.x;
    b.v = vec4(vR, 0.25f * vR, 4.0f * vR, 4.0f * vR);
    // sin and cos of alpha, 2 alpha and 4 alpha by the double-angle formulas (as pbrt).
    b.sin2kAlpha.x = m.lobes.z;
    b.cos2kAlpha.x = m.lobes.w;
    b.sin2kAlpha.y = 2.0f * b.cos2kAlpha.x * b.sin2kAlpha.x;
    b.cos2kAlpha.y = b.cos2kAlpha.x * b.cos2kAlpha.x - b.sin2kAlpha.x * b.sin2kAlpha.x;
    b.sin2kAlpha.z = 2.0f * b.cos2kAlpha.y * b.sin2kAlpha.y;
    b.cos2kAlpha.z = b.cos2kAlpha.y * b.cos2kAlpha.y - b.sin2kAlpha.y * b.sin2kAlpha.y;
    return b;
}

// ---- The terms ---------------------------------------------------------------------------------

// Modified Bessel function of the first kind, order 0: sum_i (x^2 / 4)^i / (i!)^2, to convergence
// (used for x <= 12 only; above, the asymptotic form in fiberLogI0MinusX).
GPU_FN float fiberBesselI0(float x)
{
    float q = 0.25f * x * x;
    float term = 1.0f;
    float sum = 1.0f;
    for (int i = 1; i < 64; ++i) {
        term *= q / (float(i) * float(i));
        sum += term;
        if (term < 1e-8f * sum)
            break;
    }
    return sum;
}

// log(I0(x)) - x; above 12 from I0(x) ~ e^x / sqrt(2 pi x) (1 + 1/(8x) + 9/(128x^2)) (Abramowitz &
// Stegun 9.7.1), as the CPU reference.
GPU_FN float fiberLogI0MinusX(float x)
{
    if (x > 12.0f)
        return -0.5f * log(2.0f * kFiberPi * x) + log(1.0f + 1.0f / (8.0f * x) + 9.0f / (128.0f * x * x));
    return log(fiberBesselI0(x)) - x;
}

// d'Eon et al. 2011 eq. 6, M_p = csch(1/v) / (2v) exp(-sin_i sin_o / v) I0(cos_i cos_o / v), for
// theta_o already tilted. For v <= 0.1 in log form (csch(1/v) ~ 2 e^(-1/v), as pbrt and the CPU
// reference): M_p = exp(log I0(a) - a - (1 - cos(theta_i + theta_o)) / v) / v with a = cos_i cos_o / v.
GPU_FN float fiberLongitudinal(float cosI, float cosO, float sinI, float sinO, float v)
{
    float a = cosI * cosO / v;
    if (v > 0.1f)
        return exp(-sinI * sinO / v) * fiberBesselI0(a) / (sinh(1.0f / v) * 2.0f * v);
    float cosSum = cosI * cosO - sinI * sinO; // cos(theta_i + theta_o)
    float sinSum = sinI * cosO + cosI * sinO;
    float oneMinusCos = cosSum > 0.0f ? sinSum * sinSum / (1.0f + cosSum) : 1.0f - cosSum;
    return exp(fiberLogI0MinusX(a) - oneMinusCos / v) / v;
}

// Unpolarised Fresnel reflectance of a dielectric interface (from outside, index eta inside;
// cosThetaI < 0 when leaving).
GPU_FN float fiberFresnel(float cosThetaI, float eta)
{
    cosThetaI = clamp(cosThetaI, -1.0f, 1.0f);
    float etaI = 1.0f;
    float etaT = eta;
    if (cosThetaI < 0.0f) {
        etaI = eta;
        etaT = 1.0f;
        cosThetaI = -cosThetaI;
    }
    float sinThetaT = etaI / etaT * fiberSafeSqrt(1.0f - cosThetaI * cosThetaI);
    if (sinThetaT >= 1.0f)
        return 1.0f; // total internal reflection
    float cosThetaT = fiberSafeSqrt(1.0f - sinThetaT * sinThetaT);
    float parallel = (etaT * cosThetaI - etaI * cosThetaT) / (etaT * cosThetaI + etaI * cosThetaT);
    float perpendicular = (etaI * cosThetaI - etaT * cosThetaT) / (etaI * cosThetaI + etaT * cosThetaT);
    return 0.5f * (parallel * parallel + perpendicular * perpendicular);
}

// The logistic of scale s, its CDF, and the logistic trimmed to [-pi, pi] (Chiang 2016 eq. 11-12).
GPU_FN float fiberLogistic(float x, float s)
{
    x = abs(x);
    if (x > 80.0f * s)
        return 0.0f; // below 1e-34 / s (skips the denormals exp would produce)
    float e = exp(-x / s);
    return e / (s * (1.0f + e) * (1.0f + e));
}

GPU_FN float fiberLogisticCdf(float x, float s)
{
    return 1.0f / (1.0f + exp(-x / s));
}

GPU_FN float fiberTrimmedLogistic(float x, float s)
{
    return fiberLogistic(x, s) / (fiberLogisticCdf(kFiberPi, s) - fiberLogisticCdf(-kFiberPi, s));
}

// Inverts the trimmed logistic's CDF (pbrt's SampleTrimmedLogistic).
GPU_FN float fiberSampleTrimmedLogistic(float u, float s)
{
    float lo = fiberLogisticCdf(-kFiberPi, s);
    float k = fiberLogisticCdf(kFiberPi, s) - lo;
    float x = -s * log(1.0f / (u * k + lo) - 1.0f);
    return clamp(x, -kFiberPi, kFiberPi);
}

// Phi(p, gamma_o, gamma_t) = 2 p gamma_t - 2 gamma_o + p pi: the azimuth where light entering at
// offset h leaves after p internal paths.
GPU_FN float fiberPhiExit(int p, float gammaO, float gammaT)
{
    return 2.0f * float(p) * gammaT - 2.0f * gammaO + float(p) * kFiberPi;
}

// N_p: the trimmed logistic around Phi, phi - Phi wrapped into [-pi, pi].
GPU_FN float fiberAzimuthal(float phi, int p, float s, float gammaO, float gammaT)
{
    float dphi = phi - fiberPhiExit(p, gammaO, gammaT);
    while (dphi > kFiberPi)
        dphi -= 2.0f * kFiberPi;
    while (dphi < -kFiberPi)
        dphi += 2.0f * kFiberPi;
    return fiberTrimmedLogistic(dphi, s);
}

// theta_o tilted by the cuticle for lobe p (R: -2 alpha, TT: +alpha, TRT: +4 alpha, the residual
// none), as (sin, |cos|): pbrt-v3's sign convention for its frame.
GPU_FN vec2 fiberTiltedThetaO(FiberBsdf b, int p, float sinO, float cosO)
{
    vec2 t = vec2(sinO, cosO);
    if (p == 0)
        t = vec2(sinO * b.cos2kAlpha.y - cosO * b.sin2kAlpha.y, cosO * b.cos2kAlpha.y + sinO * b.sin2kAlpha.y);
    else if (p == 1)
        t = vec2(sinO * b.cos2kAlpha.x + cosO * b.sin2kAlpha.x, cosO * b.cos2kAlpha.x - sinO * b.sin2kAlpha.x);
    else if (p == 2)
        t = vec2(sinO * b.cos2kAlpha.z + cosO * b.sin2kAlpha.z, cosO * b.cos2kAlpha.z - sinO * b.sin2kAlpha.z);
    return vec2(t.x, abs(t.y)); // the tilt may carry theta_o past the pole
}

// Everything that depends on wo alone: its angles, gamma_t and the attenuations A_p (Chiang 2016
// eq. 3-4: Fresnel at the entry, one transmittance T = exp(-sigma_a 2 cos(gamma_t) / cos(theta_t))
// per internal path, the residual as the geometric series of the remaining orders).
struct FiberOutgoing {
    float sinTheta;
    float cosTheta;
    float phi;
    float gammaT;
    vec3 ap[kFiberPMax + 1];
    vec4 apPdf; // pbrt's ComputeApPdf: the A_p luminances normalised to sum to 1
};

GPU_FN float fiberLuminance(vec3 c)
{
    return 0.212671f * c.x + 0.715160f * c.y + 0.072169f * c.z;
}

GPU_FN FiberOutgoing fiberOutgoing(FiberBsdf b, vec3 wo)
{
    FiberOutgoing o;
    o.sinTheta = wo.x;
    o.cosTheta = fiberSafeSqrt(1.0f - wo.x * wo.x);
    o.phi = fiberAtan2(wo.z, wo.y);
    // Refraction into the normal plane (Bravais' modified index eta').
    float sinThetaT = o.sinTheta / b.eta;
    float cosThetaT = fiberSafeSqrt(1.0f - sinThetaT * sinThetaT);
    float etap = sqrt(b.eta * b.eta - o.sinTheta * o.sinTheta) / o.cosTheta;
    float sinGammaT = b.h / etap;
    float cosGammaT = fiberSafeSqrt(1.0f - sinGammaT * sinGammaT);
    o.gammaT = fiberAsin(sinGammaT);
    vec3 T = exp(-b.sigmaA * (2.0f * cosGammaT / cosThetaT));

    float f = fiberFresnel(o.cosTheta * fiberSafeSqrt(1.0f - b.h * b.h), b.eta);
    o.ap[0] = vec3(f);
    o.ap[1] = (1.0f - f) * (1.0f - f) * T;
    o.ap[2] = o.ap[1] * T * f;
    o.ap[3] = o.ap[2] * f * T / (vec3(1.0f) - T * f);

    float sum = 0.0f;
    GPU_UNROLL for (int p = 0; p <= kFiberPMax; ++p)
    {
        o.apPdf[p] = fiberLuminance(o.ap[p]);
        sum += o.apPdf[p];
    }
    o.apPdf /= sum;
    return o;
}

// The lobes at the incoming direction (sinI = sin(theta_i), phi = phi_i - phi_o, any turn):
// sum_p M_p N_p A_p (pbrt's fsum) in xyz, the sampling density sum_p M_p N_p apPdf_p (per solid
// angle) in w.
GPU_FN vec4 fiberLobeSumAt(FiberBsdf b, FiberOutgoing o, float sinI, float phi)
{
    float cosI = fiberSafeSqrt(1.0f - sinI * sinI);
    vec3 f = vec3(0.0f);
    float pdf = 0.0f;
    GPU_UNROLL for (int p = 0; p <= kFiberPMax; ++p)
    {
        vec2 op = fiberTiltedThetaO(b, p, o.sinTheta, o.cosTheta);
        float mp = fiberLongitudinal(cosI, op.y, sinI, op.x, b.v[p]);
        float np = p < kFiberPMax ? fiberAzimuthal(phi, p, b.s, b.gammaO, o.gammaT) : 1.0f / (2.0f * kFiberPi);
        f += mp * np * o.ap[p];
        pdf += mp * np * o.apPdf[p];
    }
    return vec4(f, pdf);
}

GPU_FN vec4 fiberLobeSum(FiberBsdf b, FiberOutgoing o, vec3 wi)
{
    return fiberLobeSumAt(b, o, wi.x, fiberAtan2(wi.z, wi.y) - o.phi);
}

// ---- The BSDF ------------------------------------------------------------------------------------

// pbrt's fsum: f * |wi.z|, the radiance toward wo per unit radiance from wi and unit solid angle.
GPU_FN vec3 fiberFsum(FiberBsdf b, vec3 wo, vec3 wi)
{
    return vec3(fiberLobeSum(b, fiberOutgoing(b, wo), wi));
}

// pbrt's HairBSDF::f.
GPU_FN vec3 fiberF(FiberBsdf b, vec3 wo, vec3 wi)
{
    vec3 sum = fiberFsum(b, wo, wi);
    float c = abs(wi.z);
    return c > 0.0f ? sum / c : sum;
}

// The sampling density (per solid angle) of fiberSample.
GPU_FN float fiberPdf(FiberBsdf b, vec3 wo, vec3 wi)
{
    return fiberLobeSum(b, fiberOutgoing(b, wo), wi).w;
}

struct FiberSample {
    vec3 wi;
    float pdf; // per solid angle, of the whole mixture
    vec3 fsum; // f * |wi.z|: the path's weight is fsum / pdf
    int lobe;  // the lobe chosen (0 R, 1 TT, 2 TRT, 3 residual)
};

// pbrt-v3's HairBSDF::Sample_f. u: four uniform numbers in [0, 1): x the lobe (by the A_p
// luminances), y the azimuth (the trimmed logistic around Phi; uniform for the residual), z and w
// for M_p (d'Eon et al. 2011's sampling: the angle to the tilted mirror direction -theta_o' from
// its cosine's exact inverse CDF, then a uniform turn around it).
GPU_FN FiberSample fiberSampleFrom(FiberBsdf b, FiberOutgoing o, vec4 u)
{
    float uLobe = u.x;
    int p = 0;
    for (; p < kFiberPMax; ++p) {
        if (uLobe < o.apPdf[p])
            break;
        uLobe -= o.apPdf[p];
    }

    vec2 op = fiberTiltedThetaO(b, p, o.sinTheta, o.cosTheta);
    float v = b.v[p];
    float u2 = max(u.z, 1e-5f);
    float cosTheta = 1.0f + v * log(u2 + (1.0f - u2) * exp(-2.0f / v));
    float sinTheta = fiberSafeSqrt(1.0f - cosTheta * cosTheta);
    float cosPhi = fiberSinCos(2.0f * kFiberPi * u.w).y;
    float sinThetaI = -cosTheta * op.x + sinTheta * cosPhi * op.y;
    float cosThetaI = fiberSafeSqrt(1.0f - sinThetaI * sinThetaI);

    float dphi = p < kFiberPMax ? fiberPhiExit(p, b.gammaO, o.gammaT) + fiberSampleTrimmedLogistic(u.y, b.s)
                                : 2.0f * kFiberPi * u.y;
    float phiI = o.phi + dphi;

    FiberSample s;
    vec2 sc = fiberSinCos(phiI);
    s.wi = vec3(sinThetaI, cosThetaI * sc.y, cosThetaI * sc.x);
    s.lobe = p;
    s.fsum = vec3(fiberLobeSum(b, o, s.wi));
    s.pdf = fiberLobeSumAt(b, o, sinThetaI, dphi).w; // at the angles sampled (pbrt)
    return s;
}

// The same from wo (fiberSampleFrom takes what depends on wo alone, computed once for a hit's
// light samples and its bounce).
GPU_FN FiberSample fiberSample(FiberBsdf b, vec3 wo, vec4 u)
{
    return fiberSampleFrom(b, fiberOutgoing(b, wo), u);
}

// ---- The fibre's frame at a hit ------------------------------------------------------------------

// The world -> local rotation for a hit on a fibre of unit tangent t, seen by a ray of direction d
// (pbrt's curve frame: x = t, z toward the ray's origin across the fibre, y = z x x completes it):
// rows x, y, z. The offset h across the fibre is then the hit's signed distance from the axis,
// along y, in radii (pbrt: h = -1 + 2 v on the ribbon facing the ray).
struct FiberFrame {
    vec3 x;
    vec3 y;
    vec3 z;
};

GPU_FN FiberFrame makeFiberFrame(vec3 t, vec3 d)
{
    FiberFrame f;
    f.x = t;
    vec3 z = -d - t * dot(t, -d);
    float len2 = dot(z, z);
    if (len2 < 1e-12f) { // the ray runs along the fibre: any normal will do
        vec3 a = abs(t.x) < 0.9f ? vec3(1.0f, 0.0f, 0.0f) : vec3(0.0f, 1.0f, 0.0f);
        z = cross(t, a);
        len2 = dot(z, z);
    }
    f.z = z / sqrt(len2);
    f.y = cross(f.z, f.x);
    return f;
}

GPU_FN vec3 fiberToLocal(FiberFrame f, vec3 w)
{
    return vec3(dot(w, f.x), dot(w, f.y), dot(w, f.z));
}

GPU_FN vec3 fiberToWorld(FiberFrame f, vec3 w)
{
    return w.x * f.x + w.y * f.y + w.z * f.z;
}

GPU_NAMESPACE_END

#ifdef __cplusplus
static_assert(sizeof(gpu::FiberMaterial) == 32);
#endif

#endif
