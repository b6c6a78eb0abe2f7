#version 460
// hair.frag: shades a hair fragment and hands it on.
// Shading (shared/hair_shading.h, frame.shadingModel): Karis 2016 with his multiple scattering
// (default), Kajiya-Kay with Scheuermann's two lobes, or the lookup tables built from the reference
// BSDF (single scattering) plus Karis's multiple scattering. Each strand's absorption varies around the material's (a per-strand factor, lighter toward
// the tip, and streaks along the strand from value noise, as Meshuggah's hair varies its colour
// along strands with a noise texture). The light reaches the fragment through the head's shadow
// (PCF) and the hair in front of it (deep opacity map), both evaluated per vertex in hair.tese
// (light_visibility.glsl) and interpolated; the hemisphere ambient is darkened by the same opacity.
// Then, by transparency mode:
// - msaa (hair.frag): the ribbon's coverage becomes the fragment's sample mask
//   (shared/strands.h coverageMask): with MSAA the resolve averages it, with one sample it dithers.
// - oit (hair_oit.frag, HAIR_OIT): the fragment, with alpha = strand opacity x coverage, is pushed
//   onto its pixel's linked list (an atomic exchange of the head pointer, nodes from a pool with
//   an atomic counter); oit_resolve.comp blends the lists. A full pool drops the fragment and
//   counts it.
#extension GL_GOOGLE_include_directive : require
#include "shared/frame_params.h"
#include "shared/hair_shading.h"
#include "shared/lighting.h"
#include "shared/strands.h"

layout(push_constant) uniform PushBlock { HairPush push; };
layout(set = 0, binding = kHairBindingFrame) uniform FrameBlock { FrameParams frame; };
layout(set = 0, binding = kHairBindingLut) uniform sampler2DArray hairLut;
#include "shared/shadows.h"

#ifdef HAIR_OIT
layout(early_fragment_tests) in;  // hidden fragments (behind the head) never reach the lists
layout(set = 0, binding = kHairBindingOitHeads, std430) coherent buffer Heads { uint heads[]; };
layout(set = 0, binding = kHairBindingOitNodes, std430) writeonly buffer Nodes { OitNode nodes[]; };
layout(set = 0, binding = kHairBindingOitCounters, std430) coherent buffer Counters { OitCounters counters; };
#endif

layout(location = 0) in vec3 inWorld;
layout(location = 1) in vec3 inTangent;
layout(location = 2) in float inT;
layout(location = 3) flat in uint inStrand;
layout(location = 4) in float inAlpha;
layout(location = 5) in vec2 inVisibility;  // x head shadow, y hair transmittance (from hair.tese)
layout(location = 0) out vec4 outColor;

// Smooth 1D value noise in [-1, 1] along a strand, a different row per strand.
float streakNoise(uint strand, float x)
{
    float i = floor(x);
    float f = x - i;
    uint h = hashUint(strand * 747796405u + 2891336453u);
    float a = hashToUnit(h ^ hashUint(uint(i)));
    float b = hashToUnit(h ^ hashUint(uint(i) + 1u));
    return 2.0 * mix(a, b, f * f * (3.0 - 2.0 * f)) - 1.0;
}

vec3 shade()
{
    vec3 t = normalize(inTangent);
    vec3 wo = normalize(frame.cameraPosition - inWorld);
    vec3 wi = frame.lightDirection;

    // This strand's absorption: a per-strand factor, lighter toward the tip, streaks along it.
    float perStrand = 2.0 * hashToUnit(inStrand * 2654435761u) - 1.0;
    float streak = streakNoise(inStrand, inT * 7.0) + 0.5 * streakNoise(inStrand + 7919u, inT * 19.0);
    float factor = exp2(frame.hairVariation * perStrand + 0.6 * frame.hairStreaks * streak) * (1.25 - 0.5 * inT);
    HairMaterial m = frame.hair;
    vec3 baseColor = m.baseColor.rgb;
    m.sigmaA.xyz *= factor;
    m.baseColor.rgb = pow(max(baseColor, vec3(1e-4)), vec3(sqrt(factor)));  // c = exp(-sqrt(sigma_a) ...), Chiang 2016

    vec2 visibility = inVisibility;
    float transmittance = visibility.y;
    vec3 s;
    if (frame.shadingModel == kShadingKaris) {
        s = hairKarisLit(t, wi, wo, m, 1.0 - transmittance);
    } else if (frame.shadingModel == kShadingKajiya) {
        s = transmittance * hairKajiyaKay(t, wi, wo, m);
    } else {
        // The tables hold the material's single scattering (absorption baked in; the strand's own
        // tints it); the light scattered between fibres comes from Karis's approximation, as in
        // the karis mode.
        vec3 single = hairShadeLut(hairLut, t, wi, wo) * (m.baseColor.rgb / max(baseColor, vec3(1e-4)));
        s = transmittance * (single + hairKarisMultiple(t, wi, wo, m, 1.0 - transmittance));
    }
    vec3 radiance = s * frame.lightColor * frame.lightIntensity * visibility.x;

    vec3 n = wo - t * dot(t, wo);  // the ribbon faces the camera
    n = dot(n, n) > 1e-8 ? normalize(n) : vec3(0.0, 1.0, 0.0);
    float occlusion = mix(1.0, transmittance, frame.hairAmbientOcclusion);
    radiance += m.baseColor.rgb * frame.ambientIntensity * occlusion * hemisphereAmbient(n, frame.skyColor, frame.groundColor);
    return toneMapAces(radiance * frame.exposure);
}

void main()
{
#ifdef HAIR_OIT
    float alpha = clamp(frame.hairOpacity * inAlpha, 0.0, 1.0);
    if (alpha <= 0.0)
        discard;
    vec3 color = shade();
    uint index = atomicAdd(counters.allocated, 1u);
    if (index >= counters.capacity) {
        atomicAdd(counters.overflow, 1u);
        discard;
    }
    uint pixel = uint(gl_FragCoord.y) * uint(frame.viewportWidth) + uint(gl_FragCoord.x);
    OitNode node;
    node.color = packUnorm4x8(vec4(sqrt(color), alpha));
    node.depth = gl_FragCoord.z;
    node.next = atomicExchange(heads[pixel], index);
    nodes[index] = node;
    outColor = vec4(0.0);  // the attachment is bound with writes masked off
#else
    uint pixel = uint(gl_FragCoord.x) * 73856093u ^ uint(gl_FragCoord.y) * 19349663u;
    uint mask = coverageMask(inAlpha, push.samples, inStrand, pixel);
    if (mask == 0u)
        discard;
    gl_SampleMask[0] = int(mask);
    outColor = vec4(shade(), 1.0);
#endif
}
