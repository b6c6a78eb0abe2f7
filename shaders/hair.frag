#version 460
// hair.frag: shades a hair fragment and hands it on.
// Shading (shared/strand_shading.h over shared/hair_shading.h, frame.shadingModel; the key, fill and
// rim lights of frame_params.h's frameLight): Karis 2016 with
// his multiple scattering (default), Kajiya-Kay with Scheuermann's two lobes, or the lookup tables
// built from the reference BSDF (single scattering) plus Karis's multiple scattering, each strand's
// absorption varied along it. The key light reaches the fragment through the head's shadow (PCF) and
// the hair in front of it (deep opacity map), both evaluated per vertex in hair.tese
// (light_visibility.glsl) and interpolated.
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
#include "shared/strand_shading.h"
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

vec3 shade()
{
    vec3 t = normalize(inTangent);
    vec3 lut[kFrameLights];
    strandLutSingles(frame, hairLut, t, normalize(frame.cameraPosition - inWorld), lut);
    return shadeStrandPoint(frame, inWorld, t, inT, inStrand, inVisibility, lut);
}

void main()
{
#ifdef HAIR_OIT
    // The fragment stands for the samples of its pixel the ribbon covers (one shader run per pixel
    // under MSAA): a ribbon a pixel wide touches samples of about two pixels per row, so without
    // this share thin hair would come out up to twice as dense as its area.
    float covered = float(bitCount(gl_SampleMaskIn[0])) / float(push.samples);
    float alpha = clamp(frame.hairOpacity * inAlpha * covered, 0.0, 1.0);
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
