// shaders/shared/strand_shading.h: the colour one point of a drawn strand shows, one copy for
// hair.frag (the tessellation path, per fragment), strands_generate.comp (the compute path, per
// strand vertex: shading amortised along the strand, as Frostbite and Unreal do) and C++.
// Each strand's absorption varies around the material's: a per-strand factor, lighter toward the
// tip, and streaks along the strand from value noise (Meshuggah varies colour along strands with a
// noise texture). The light reaches the point through the head's shadow (x of `visibility`) and
// the hair in front of it (y: the deep opacity map's transmittance); the hemisphere ambient is
// darkened by the same opacity. Output: tone-mapped linear RGB in [0, 1].
#ifndef WISP_SHARED_STRAND_SHADING_H
#define WISP_SHARED_STRAND_SHADING_H
#include "frame_params.h"
#include "hair_shading.h"
#include "lighting.h"
#include "prelude.h"
#include "sim.h"

GPU_NAMESPACE_BEGIN

// Smooth 1D value noise in [-1, 1] along a strand, a different row per strand.
GPU_FN float hairStreakNoise(uint strand, float x)
{
    float i = floor(x);
    float f = x - i;
    uint h = hashUint(strand * 747796405u + 2891336453u);
    float a = hashToUnit(h ^ hashUint(uint(i)));
    float b = hashToUnit(h ^ hashUint(uint(i) + 1u));
    return 2.0f * mix(a, b, f * f * (3.0f - 2.0f * f)) - 1.0f;
}

// Point t (0 root .. 1 tip) of strand `strand` at `world` with unit `tangent`. `lutSingle` is the
// lookup mode's single scattering for these directions (hairShadeLut in GLSL, evaluateHairLut in
// C++); the other models ignore it.
GPU_FN vec3 shadeStrandPoint(FrameParams frame, vec3 world, vec3 tangent, float t, uint strand, vec2 visibility,
                             vec3 lutSingle)
{
    vec3 wo = normalize(frame.cameraPosition - world);
    vec3 wi = frame.lightDirection;

    float perStrand = 2.0f * hashToUnit(strand * 2654435761u) - 1.0f;
    float streak = hairStreakNoise(strand, t * 7.0f) + 0.5f * hairStreakNoise(strand + 7919u, t * 19.0f);
    float factor = exp2(frame.hairVariation * perStrand + 0.6f * frame.hairStreaks * streak) * (1.25f - 0.5f * t);
    HairMaterial m = frame.hair;
    vec3 baseColor = vec3(m.baseColor);
    m.sigmaA = vec4(vec3(m.sigmaA) * factor, m.sigmaA.w);
    // c = exp(-sqrt(sigma_a) ...) (Chiang 2016): the colour follows the absorption's square root.
    m.baseColor = vec4(pow(max(baseColor, vec3(1e-4f)), vec3(sqrt(factor))), m.baseColor.w);

    float transmittance = visibility.y;
    vec3 s;
    if (frame.shadingModel == kShadingKaris) {
        s = hairKarisLit(tangent, wi, wo, m, 1.0f - transmittance);
    } else if (frame.shadingModel == kShadingKajiya) {
        s = transmittance * hairKajiyaKay(tangent, wi, wo, m);
    } else {
        // The tables hold the material's single scattering (absorption baked in; the strand's own
        // tints it); the light scattered between fibres comes from Karis's approximation, as in
        // the karis mode.
        vec3 single = lutSingle * (vec3(m.baseColor) / max(baseColor, vec3(1e-4f)));
        s = transmittance * (single + hairKarisMultiple(tangent, wi, wo, m, 1.0f - transmittance));
    }
    vec3 radiance = s * frame.lightColor * frame.lightIntensity * visibility.x;

    vec3 n = wo - tangent * dot(tangent, wo); // the ribbon faces the camera
    n = dot(n, n) > 1e-8f ? normalize(n) : vec3(0.0f, 1.0f, 0.0f);
    float occlusion = mix(1.0f, transmittance, frame.hairAmbientOcclusion);
    radiance += vec3(m.baseColor) * frame.ambientIntensity * occlusion *
                hemisphereAmbient(n, frame.skyColor, frame.groundColor);
    return toneMapAces(radiance * frame.exposure);
}

GPU_NAMESPACE_END

#endif
