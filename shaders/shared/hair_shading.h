// shaders/shared/hair_shading.h: the real-time hair shading models, one copy for GLSL and C++:
// Karis 2016 (R, TT, TRT and his multiple-scattering approximation), Kajiya-Kay with Scheuermann
// 2004's two shifted specular lobes, and the lookup-table mode of Nguyen & Donnelly 2005 (Nalu,
// GPU Gems 2 ch. 23) whose tables shading/hair_lut.cpp builds from the reference BSDF
// (shading/hair_bsdf.h: Chiang et al. 2016 as pbrt-v3 defines it). The C++ tests measure every
// model against that reference (tests/test_hair_shading.cpp).
//
// Conventions, for every function here:
//   t   unit fibre tangent (the reference's x axis; pbrt's dp/du, root to tip on Wisp's strands),
//   wi  unit direction to the light, wo unit direction to the viewer, both away from the point;
//   theta: the angle of a direction to the fibre's normal plane, sin(theta) = dot(t, w);
//   phi = phi_i - phi_o: the angle between wi and wo projected into the normal plane.
// Every model returns S = f(wo, wi) * |cos| with the projection cosine folded in (pbrt's `fsum`:
// its f is S / |wi.z|): the radiance leaving toward wo per unit radiance arriving from wi and unit
// solid angle. For a light of radiance-like intensity E from wi: L_o = S * E, no extra cosine.
// S depends on the fibre as a whole: all models are averaged across the fibre's width (over the
// offset h), so they are even in phi.
#ifndef WISP_SHARED_HAIR_SHADING_H
#define WISP_SHARED_HAIR_SHADING_H
#include "prelude.h"

GPU_NAMESPACE_BEGIN

GPU_CONST float kHairPi = 3.14159265f;

// The hair material, as a uniform/push block (vec4 members only, std140 = std430 = C++ layout).
// shading/hair_models.cpp's packHairMaterial() fills it from the reference's parameters.
struct HairMaterial {
    vec4 sigmaA;        // xyz absorption per unit fibre radius (Chiang 2016), w index of refraction eta
    vec4 roughness;     // x beta_m (longitudinal), y beta_n (azimuthal), z cuticle tilt alpha (radians), w unused
    vec4 baseColor;     // xyz the colour sigmaA renders as (Chiang 2016 eq. 9 inverted, for beta_n), w unused
    vec4 kajiya;        // Kajiya-Kay lobes: x shift1, y shift2 (radians: where each lobe peaks in
                        // theta_h = (theta_i + theta_o) / 2), z exponent1, w exponent2
    vec4 kajiyaWeights; // Kajiya-Kay albedos: x diffuse, y primary specular (white), z secondary
                        // specular (both x and z multiply baseColor), w unused
};

// ---- Angles ------------------------------------------------------------------------------------

struct HairAngles {
    float sinThetaI; // dot(t, wi)
    float sinThetaO; // dot(t, wo)
    float cosPhi;    // cos(phi_i - phi_o); 1 where either direction runs along the fibre
    float cosThetaD; // cos((theta_o - theta_i) / 2), theta_d of Marschner et al. 2003
};

GPU_FN HairAngles hairAngles(vec3 t, vec3 wi, vec3 wo)
{
    HairAngles a;
    a.sinThetaI = clamp(dot(t, wi), -1.0f, 1.0f);
    a.sinThetaO = clamp(dot(t, wo), -1.0f, 1.0f);
    vec3 pi = wi - t * a.sinThetaI;
    vec3 po = wo - t * a.sinThetaO;
    float d = dot(pi, pi) * dot(po, po);
    a.cosPhi = d > 1e-12f ? clamp(dot(pi, po) / sqrt(d), -1.0f, 1.0f) : 1.0f;
    // cos((theta_o - theta_i) / 2) = sqrt((1 + cos(theta_o - theta_i)) / 2), the half angle within
    // [-pi/2, pi/2]; cos(theta_o - theta_i) = cos(theta_o) cos(theta_i) + sin(theta_o) sin(theta_i),
    // each cosine sqrt(1 - sin^2) (theta within [-pi/2, pi/2]): no arcsine, no cosine.
    float cosI = sqrt(max(1.0f - a.sinThetaI * a.sinThetaI, 0.0f));
    float cosO = sqrt(max(1.0f - a.sinThetaO * a.sinThetaO, 0.0f));
    a.cosThetaD = sqrt(clamp(0.5f * (1.0f + cosO * cosI + a.sinThetaO * a.sinThetaI), 0.0f, 1.0f));
    return a;
}

// The reference's longitudinal lobe width for R (sqrt of pbrt's variance v_R, Chiang 2016 eq. 7):
// 0.726 beta_m + 0.812 beta_m^2 + 3.7 beta_m^20 radians. TT is half as wide, TRT twice.
GPU_FN float hairLongitudinalWidth(float betaM)
{
    float b4 = betaM * betaM * (betaM * betaM);
    float b16 = b4 * b4 * (b4 * b4);
    return 0.726f * betaM + 0.812f * betaM * betaM + 3.7f * (b16 * b4); // (beta_m^20 by products, not pow)
}

// ---- Karis 2016 ("Physically Based Hair Shading in Unreal", SIGGRAPH course) --------------------

// Unit-area Gaussian of standard deviation b (Karis's g).
GPU_FN float hairGaussian(float b, float x)
{
    return exp(-0.5f * x * x / (b * b)) / (2.50662827f * b);
}

// Schlick's Fresnel with F0 from eta (Karis's F).
GPU_FN float hairFresnelSchlick(float eta, float cosTheta)
{
    float f0 = (1.0f - eta) / (1.0f + eta);
    f0 *= f0;
    float c = 1.0f - clamp(cosTheta, 0.0f, 1.0f);
    float c2 = c * c;
    return f0 + (1.0f - f0) * c2 * c2 * c;
}

// R + TT + TRT, Karis's approximations (no multiple scattering: add hairKarisMultiple):
//   M_p = g(B_p; sin(theta_i) + sin(theta_o) - alpha_p), a Gaussian in the sum of sines. Widths from
//     the reference's beta_m (B_R = sqrt(v_R), B_TT = B_R / 2, B_TRT = 2 B_R, as Karis's beta^2,
//     beta^2 / 2, 2 beta^2), shifts from the cuticle tilt alpha in the reference's sign convention:
//     R peaks at theta_i + theta_o = 2 alpha, TT at -alpha, TRT at -4 alpha.
//   R:   N = cos(phi / 2) / 4, A = F(eta, sqrt((1 + dot(wi, wo)) / 2)).
//   TT:  N = exp(-3.65 cos(phi) - 3.98) (Karis's fit of the forward lobe),
//        A = (1 - f)^2 T, f = F(eta, cos(theta_d) sqrt(1 - h^2)), his fitted entry offset
//        h = cos(phi / 2) (1 + a (0.6 - 0.8 cos(phi))), a = 1 / eta' (eta' the Bravais index for
//        theta_d, exactly; Karis fits 1.19 / cos + 0.36 cos for eta = 1.55). Absorption: Karis writes
//        T = C^(sqrt(1 - h^2 a^2) / (2 cos(theta_d))) with a colour C; with C = exp(-4 sigma_a) that is
//        exactly T = exp(-2 sigma_a sqrt(1 - h^2 a^2) / cos(theta_d)), one pass at the reference's
//        sigma_a, which is what is used here.
//   TRT: N = exp(17 cos(phi) - 16.78), A = (1 - f)^2 f T^2 with f = F(eta, cos(theta_d) / 2) and
//        T^2 = C^(0.8 / cos(theta_d)) = exp(-3.2 sigma_a / cos(theta_d)) (h = sqrt(3) / 2).
GPU_FN vec3 hairKaris(vec3 t, vec3 wi, vec3 wo, HairMaterial m)
{
    HairAngles a = hairAngles(t, wi, wo);
    float eta = m.sigmaA.w;
    float alpha = m.roughness.z;
    float bR = hairLongitudinalWidth(m.roughness.x);
    float sumSin = a.sinThetaI + a.sinThetaO;
    float cosHalfPhi = sqrt(clamp(0.5f + 0.5f * a.cosPhi, 0.0f, 1.0f));
    float cosD = max(a.cosThetaD, 1e-4f);

    float mR = hairGaussian(bR, sumSin - 2.0f * alpha);
    float fR = hairFresnelSchlick(eta, sqrt(clamp(0.5f + 0.5f * dot(wi, wo), 0.0f, 1.0f)));
    vec3 s = vec3(mR * 0.25f * cosHalfPhi * fR);

    float mTT = hairGaussian(0.5f * bR, sumSin + alpha);
    float etaPrime = sqrt(max(eta * eta - 1.0f + cosD * cosD, 0.0f)) / cosD;
    float ai = 1.0f / etaPrime;
    float hTT = cosHalfPhi * (1.0f + ai * (0.6f - 0.8f * a.cosPhi));
    float fTT = hairFresnelSchlick(eta, cosD * sqrt(max(1.0f - hTT * hTT, 0.0f)));
    vec3 tTT = exp(-vec3(m.sigmaA) * (2.0f * sqrt(max(1.0f - hTT * hTT * ai * ai, 0.0f)) / cosD));
    float nTT = exp(-3.65f * a.cosPhi - 3.98f);
    s += mTT * nTT * (1.0f - fTT) * (1.0f - fTT) * tTT;

    float mTRT = hairGaussian(2.0f * bR, sumSin + 4.0f * alpha);
    float fTRT = hairFresnelSchlick(eta, 0.5f * cosD);
    vec3 tTRT = exp(-vec3(m.sigmaA) * (3.2f / cosD));
    float nTRT = exp(17.0f * a.cosPhi - 16.78f);
    s += mTRT * nTRT * (1.0f - fTRT) * (1.0f - fTRT) * fTRT * tTRT;
    return s;
}

// Karis's multiple-scattering approximation: a wrapped diffuse around the normal facing the viewer
// blended with Kajiya-Kay's diffuse, coloured sqrt(C) and tinted by pow(C / luma(C), depth):
//   S_ms = sqrt(C) / pi * mix((dot(n_v, wi) + 1) / 4, 1 - |dot(t, wi)|, 0.33) * pow(C / luma, shadow).
// `shadow` in [0, 1] is the light's occlusion at the point, 1 - transmittance from the deep opacity
// map (0: lit, 1: fully shadowed). Karis writes the tint exponent as (1 - Shadow) with Unreal's
// Shadow being the light's visibility, i.e. the transmittance; in terms of this occlusion the
// exponent is `shadow`: light that crossed more hair is more saturated.
GPU_FN vec3 hairKarisMultiple(vec3 t, vec3 wi, vec3 wo, HairMaterial m, float shadow)
{
    vec3 c = vec3(m.baseColor);
    float kajiyaDiffuse = 1.0f - abs(dot(t, wi));
    vec3 n = wo - t * dot(t, wo); // the normal facing the viewer
    float len2 = dot(n, n);
    float wrapped = len2 > 1e-12f ? clamp((dot(n, wi) / sqrt(len2) + 1.0f) * 0.25f, 0.0f, 1.0f) : 0.25f;
    float diffuseScatter = mix(wrapped, kajiyaDiffuse, 0.33f) / kHairPi;
    float luma = max(dot(c, vec3(0.212671f, 0.715160f, 0.072169f)), 1e-6f);
    vec3 tint = pow(max(c / luma, vec3(1e-6f)), vec3(clamp(shadow, 0.0f, 1.0f)));
    return sqrt(c) * diffuseScatter * tint;
}

// How the renderer combines them (Unreal's composition: the whole hair response is scaled by the
// light's transmittance through the hair, the multiple-scattering tint deepens with the occlusion):
//   L_o = lightRadiance * hairKarisLit(t, wi, wo, m, shadow)
//       = lightRadiance * (1 - shadow) * (hairKaris(t, wi, wo, m) + hairKarisMultiple(t, wi, wo, m, shadow)).
GPU_FN vec3 hairKarisLit(vec3 t, vec3 wi, vec3 wo, HairMaterial m, float shadow)
{
    float transmittance = 1.0f - clamp(shadow, 0.0f, 1.0f);
    return transmittance * (hairKaris(t, wi, wo, m) + hairKarisMultiple(t, wi, wo, m, shadow));
}

// ---- Kajiya-Kay (1989) with Scheuermann 2004's two shifted lobes ---------------------------------

// One specular lobe sin(t', h)^e with the tangent t' tilted toward h by `shift` radians (Scheuermann
// shifts t along the normal; with the normal taken as h's part perpendicular to t that is a
// rotation of the angle between t and h), so the lobe peaks where dot(t, h) = sin(shift), i.e. at
// theta_h = (theta_i + theta_o) / 2 ~ shift. Normalised so that its integral over the sphere of wi
// is 1 for narrow lobes and any wo: near its peak it is exp(-e x^2 / 2) in
// x = dot(t, h) ~ (theta_i + theta_o) / (2 cos(phi / 2)), a Gaussian in theta_i of deviation
// 2 cos(phi / 2) / sqrt(e), whose integral with the weight cos(theta_i) ~ cos(theta_o) over theta_i
// and phi is 8 sqrt(2 pi / e) cos(theta_o) (its azimuthal profile is cos(phi / 2), Karis's N_R).
// Broad lobes (e below about 20) come out up to 20% dimmer at normal incidence.
GPU_FN float hairKajiyaLobe(float tDotH, float cosThetaO, float shift, float exponent)
{
    float sinTH = sqrt(max(1.0f - tDotH * tDotH, 0.0f));
    float x = tDotH * cos(shift) - sinTH * sin(shift); // cos of the angle between t' and h
    return pow(max(1.0f - x * x, 0.0f), 0.5f * exponent) * sqrt(exponent) * 0.0498677850f / max(cosThetaO, 0.05f);
}

// Kajiya-Kay diffuse sin(t, wi) = cos(theta_i), normalised by its integral over the sphere (pi^2),
// plus two specular lobes: the primary white (the surface reflection R), the secondary tinted by the
// base colour (TRT). The albedos in m.kajiyaWeights are the reference's lobe albedos at normal
// incidence (packHairMaterial), so the model is as bright as the reference on average.
GPU_FN vec3 hairKajiyaKay(vec3 t, vec3 wi, vec3 wo, HairMaterial m)
{
    vec3 c = vec3(m.baseColor);
    float cosThetaI = sqrt(max(1.0f - dot(t, wi) * dot(t, wi), 0.0f));
    vec3 h = wi + wo;
    float len2 = dot(h, h);
    float tDotH = len2 > 1e-12f ? dot(t, h) / sqrt(len2) : 0.0f;
    float cosThetaO = sqrt(max(1.0f - dot(t, wo) * dot(t, wo), 0.0f));
    float spec1 = hairKajiyaLobe(tDotH, cosThetaO, m.kajiya.x, m.kajiya.z);
    float spec2 = hairKajiyaLobe(tDotH, cosThetaO, m.kajiya.y, m.kajiya.w);
    vec3 diffuse = m.kajiyaWeights.x * c * (cosThetaI / (kHairPi * kHairPi));
    return diffuse + vec3(m.kajiyaWeights.y * spec1) + m.kajiyaWeights.z * c * spec2;
}

// ---- Lookup tables (Nalu: M and N precomputed from the reference) --------------------------------

// One RGBA32F 2D-array texture of kHairLutLayers layers, kHairLutSize texels square, layer-major,
// rows v, columns u, texel centres at (i + 0.5) / size; sampled with a linear filter, clamp to edge,
// normalised coordinates. Built on the CPU by shading/hair_lut.cpp (buildHairLut) for one set of
// parameters.
//   layer 0: M_R, M_TT, M_TRT, M_residual (rgba) at u = (sin(theta_i) + 1) / 2, v = (sin(theta_o) + 1) / 2,
//            the cuticle tilts baked in (they depend on theta_i and theta_o alone).
//   layers 1, 2, 3: N_R, N_TT, N_TRT (rgb; a = 0): the h-average of A_p(h) N_p(phi; h), absorption
//            and Fresnel baked in, at u = |phi| / pi, v = |sin(theta_o)| (the reference's A_p and
//            N_p depend on theta_o and phi alone; averaged over h they are even in phi).
//   layer 4: the residual's h-averaged A_pMax / (2 pi) (rgb; a = 0), constant in u, at v = |sin(theta_o)|.
GPU_CONST uint kHairLutSize = 64u;
GPU_CONST uint kHairLutLayers = 5u;
GPU_CONST uint kHairLutLayerM = 0u;
GPU_CONST uint kHairLutLayerNR = 1u;
GPU_CONST uint kHairLutLayerNTT = 2u;
GPU_CONST uint kHairLutLayerNTRT = 3u;
GPU_CONST uint kHairLutLayerNResidual = 4u;

// Where layer 0 is read for these directions.
GPU_FN vec2 hairLutUvM(HairAngles a)
{
    return vec2(0.5f * a.sinThetaI + 0.5f, 0.5f * a.sinThetaO + 0.5f);
}

// Where layers 1..4 are read.
GPU_FN vec2 hairLutUvN(HairAngles a)
{
    return vec2(acos(a.cosPhi) / kHairPi, abs(a.sinThetaO));
}

// S from the sampled texels: sum over lobes of M_p * N_p.
GPU_FN vec3 hairLutCombine(vec4 m, vec4 nR, vec4 nTT, vec4 nTRT, vec4 nResidual)
{
    return m.x * vec3(nR) + m.y * vec3(nTT) + m.z * vec3(nTRT) + m.w * vec3(nResidual);
}

#ifndef __cplusplus
// GLSL: the whole lookup mode from a sampler2DArray bound to the tables (C++: evaluateHairLut).
vec3 hairShadeLut(sampler2DArray lut, vec3 t, vec3 wi, vec3 wo)
{
    HairAngles a = hairAngles(t, wi, wo);
    vec2 uvM = hairLutUvM(a);
    vec2 uvN = hairLutUvN(a);
    return hairLutCombine(
        texture(lut, vec3(uvM, float(kHairLutLayerM))), texture(lut, vec3(uvN, float(kHairLutLayerNR))),
        texture(lut, vec3(uvN, float(kHairLutLayerNTT))), texture(lut, vec3(uvN, float(kHairLutLayerNTRT))),
        texture(lut, vec3(uvN, float(kHairLutLayerNResidual))));
}
#endif

GPU_NAMESPACE_END

#ifdef __cplusplus
// The layouts GLSL gives these blocks, checked where they are defined (C++ only).
static_assert(sizeof(gpu::HairMaterial) == 80, "HairMaterial is five vec4s: its std140 size");
static_assert(offsetof(gpu::HairMaterial, roughness) == 16);
static_assert(offsetof(gpu::HairMaterial, baseColor) == 32);
static_assert(offsetof(gpu::HairMaterial, kajiya) == 48);
static_assert(offsetof(gpu::HairMaterial, kajiyaWeights) == 64);
#endif

#endif
