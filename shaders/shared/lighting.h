// shaders/shared/lighting.h: the plain surface shading used for the head and other meshes:
// Lambert diffuse from one directional light, a normalized Blinn-Phong highlight, and a
// hemisphere ambient, then ACES-fitted tone mapping. Pure functions, shared by GLSL and C++ tests.
// Conventions: every direction points away from the shading point; colours are linear RGB.
#ifndef WISP_SHARED_LIGHTING_H
#define WISP_SHARED_LIGHTING_H
#include "prelude.h"

GPU_NAMESPACE_BEGIN

// Hemisphere ambient: sky above, ground below, blended by the normal's up component.
GPU_FN vec3 hemisphereAmbient(vec3 n, vec3 sky, vec3 ground)
{
    float t = 0.5f * n.y + 0.5f;
    return mix(ground, sky, t);
}

// Lambert + normalized Blinn-Phong. n, l, v unit vectors away from the surface.
// roughness in [0, 1] maps to a Blinn-Phong exponent between 256 and 4; the highlight is
// normalized by (e + 8) / (8 pi) (Akenine-Moller et al., Real-Time Rendering, 4th ed. 9.8)
// and kept weak (a 4% dielectric Fresnel at normal incidence), as on matte plastic.
GPU_FN vec3 surfaceRadiance(vec3 n, vec3 l, vec3 v, vec3 albedo, float roughness, vec3 lightRadiance)
{
    float nl = max(dot(n, l), 0.0f);
    // (A light straight behind the point as seen, l = -v, has no half vector: a rim light can be
    // there; nl is then 0 for any surface the viewer sees, and h = n keeps the product finite.)
    vec3 lv = l + v;
    vec3 h = dot(lv, lv) > 1e-12f ? normalize(lv) : n;
    float e = mix(256.0f, 4.0f, clamp(roughness, 0.0f, 1.0f));
    float spec = 0.04f * (e + 8.0f) / (8.0f * 3.14159265f) * pow(max(dot(n, h), 0.0f), e);
    return (albedo / 3.14159265f + vec3(spec)) * lightRadiance * nl;
}

// ACES filmic curve fitted by Narkowicz (2015), input and output linear, output in [0, 1].
GPU_FN vec3 toneMapAces(vec3 x)
{
    vec3 num = x * (2.51f * x + 0.03f);
    vec3 den = x * (2.43f * x + 0.59f) + 0.14f;
    return clamp(num / den, vec3(0.0f), vec3(1.0f));
}

GPU_NAMESPACE_END

#endif
