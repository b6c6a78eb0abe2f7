// shaders/shared/strand_shading.h: the colour one point of a drawn strand shows, one copy for
// hair.frag (the tessellation path, per fragment), strands_generate.comp (the compute path, per
// strand vertex: shading amortised along the strand, as Frostbite and Unreal do) and C++.
// Each strand's absorption varies around the material's: a per-strand factor, lighter toward the
// tip, and streaks along the strand from value noise (Meshuggah varies colour along strands with a
// noise texture). The studio's three lights (frame_params.h frameLight: the key, shadowed, the fill
// and the rim) are each evaluated by strandLightResponse in one loop; the hemisphere ambient is
// darkened by the hair's opacity. Output: tone-mapped linear RGB in [0, 1].
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

// How much strand `strand` at t (0 root .. 1 tip) scales the material's absorption: a per-strand
// factor (hairVariation), streaks along it (hairStreaks) and lighter toward the tip (hairAlong.x:
// at 1, 1.25 at the root to 0.75 at the tip; at 0 the same all along). The path tracer
// (reference_path.h) gives its fibres the same absorption.
GPU_FN float strandAbsorptionScale(FrameParams frame, uint strand, float t)
{
    float perStrand = 2.0f * hashToUnit(strand * 2654435761u) - 1.0f;
    float streak = hairStreakNoise(strand, t * 7.0f) + 0.5f * hairStreakNoise(strand + 7919u, t * 19.0f);
    return exp2(frame.hairVariation * perStrand + 0.6f * frame.hairStreaks * streak) *
           (1.0f + frame.hairAlong.x * (0.25f - 0.5f * t));
}

// The hair's response S (hair_shading.h: outgoing radiance per unit incoming radiance) at a point
// of material `m` (`baseColor` the material's own, before the strand's variation) to one light
// from wi, reaching it through hair of `transmittance`, by the frame's model. `lutSingle` is the
// lookup mode's single scattering for these directions; the other models ignore it. With
// frame.multipleScattering 0 the karis and lut models leave out Karis's multiple scattering (the
// light scattered between fibres) and keep the single scattering alone; kajiya has none to leave.
GPU_FN vec3 strandLightResponse(FrameParams frame, HairMaterial m, vec3 baseColor, vec3 tangent, vec3 wi, vec3 wo,
                                float transmittance, vec3 lutSingle)
{
    if (frame.shadingModel == kShadingKajiya)
        return transmittance * hairKajiyaKay(tangent, wi, wo, m);
    vec3 multiple =
        frame.multipleScattering != 0u ? hairKarisMultiple(tangent, wi, wo, m, 1.0f - transmittance) : vec3(0.0f);
    if (frame.shadingModel == kShadingKaris)
        return transmittance * (hairKaris(tangent, wi, wo, m) + multiple); // hairKarisLit, with the setting
    // The tables hold the material's single scattering (absorption baked in; the strand's own
    // tints it); the light scattered between fibres comes from Karis's approximation, as in
    // the karis mode.
    vec3 single = lutSingle * (vec3(m.baseColor) / max(baseColor, vec3(1e-4f)));
    return transmittance * (single + multiple);
}

#ifndef __cplusplus
// The lookup mode's single scattering toward the camera for each of the frame's lights, from the
// tables (zeros in the other modes, which do not read them).
void strandLutSingles(FrameParams frame, sampler2DArray lut, vec3 tangent, vec3 wo, out vec3 singles[kFrameLights])
{
    for (uint i = 0u; i < kFrameLights; ++i)
        singles[i] = frame.shadingModel == kShadingLut ? hairShadeLut(lut, tangent, frameLight(frame, i).direction, wo)
                                                       : vec3(0.0f);
}
#endif

// How much of a light without shadows (the fill, the rim) reaches a point of the hair, which it
// would reach through the rest of the hair and the head: the hair taken as a sphere (`volume`:
// centre, radius) lit from wi with wrapped diffuse (Green, "Real-Time Approximations to Subsurface
// Scattering", GPU Gems 2004, ch. 16: (dot(n, l) + w) / (1 + w), light carried past the terminator
// by scattering), its normal the direction from the centre to the point. A rim from behind so
// reaches the crown and the silhouette (the terminator, seen from the front: a third of it) but not
// the hair over the face; w = 0.5. Without a volume (radius 0), 1.
GPU_CONST float kHairVolumeWrap = 0.5f;
GPU_FN float hairVolumeExposure(vec4 volume, vec3 world, vec3 wi)
{
    vec3 d = world - vec3(volume);
    float len2 = dot(d, d);
    if (volume.w <= 0.0f || len2 <= 1e-12f * volume.w * volume.w)
        return 1.0f;
    return clamp((dot(d, wi) / sqrt(len2) + kHairVolumeWrap) / (1.0f + kHairVolumeWrap), 0.0f, 1.0f);
}

// Point t (0 root .. 1 tip) of strand `strand` at `world` with unit `tangent`, lit by the frame's
// lights (frameLight). `visibility` is the key light's: x through the head's shadow, y through the
// hair in front of it (the deep opacity map's transmittance). `lutSingle[i]` is the lookup mode's
// single scattering for light i (hairShadeLut in GLSL, evaluateHairLut in C++; ignored by the other
// models). The fill and the rim have no maps of their own. What reaches a point of them is
// approximated twice: the side of the hair's volume they light (hairVolumeExposure: the rim lights
// the crown and the silhouette, not the hair over the face, which the head would hide from it), and
// how deep in the hair the point lies, which the key's deep opacity map knows (its transmittance
// softened as the ambient's occlusion is, mix(1, T, hairAmbientOcclusion): the deep opacity map
// standing in for the hair's ambient occlusion, as it does for the ambient below): strands inside
// the volume get less of the rim than those on its edge.
GPU_FN vec3 shadeStrandPoint(FrameParams frame, vec3 world, vec3 tangent, float t, uint strand, vec2 visibility,
                             vec3 lutSingle[kFrameLights])
{
    vec3 wo = normalize(frame.cameraPosition - world);

    float factor = strandAbsorptionScale(frame, strand, t);
    HairMaterial m = frame.hair;
    vec3 baseColor = vec3(m.baseColor);
    m.sigmaA = vec4(vec3(m.sigmaA) * factor, m.sigmaA.w);
    // c = exp(-sqrt(sigma_a) ...) (Chiang 2016): the colour follows the absorption's square root.
    m.baseColor = vec4(pow(max(baseColor, vec3(1e-4f)), vec3(sqrt(factor))), m.baseColor.w);

    float occlusion = mix(1.0f, visibility.y, frame.hairAmbientOcclusion);
    vec3 radiance = vec3(0.0f);
    for (uint i = 0u; i < kFrameLights; ++i) {
        FrameLight light = frameLight(frame, i);
        if (light.intensity <= 0.0f)
            continue;
        bool key = i == kFrameKeyLight;
        float transmittance = key ? visibility.y : occlusion;
        float head = key ? visibility.x : hairVolumeExposure(frame.hairVolume, world, light.direction);
        radiance +=
            strandLightResponse(frame, m, baseColor, tangent, light.direction, wo, transmittance, lutSingle[i]) *
            light.color * (light.intensity * head);
    }

    vec3 n = wo - tangent * dot(tangent, wo); // the ribbon faces the camera
    n = dot(n, n) > 1e-8f ? normalize(n) : vec3(0.0f, 1.0f, 0.0f);
    radiance += vec3(m.baseColor) * frame.ambientIntensity * occlusion *
                hemisphereAmbient(n, frame.skyColor, frame.groundColor);
    return toneMapAces(radiance * frame.exposure);
}

GPU_NAMESPACE_END

#endif
