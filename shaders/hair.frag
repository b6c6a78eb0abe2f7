#version 460
// hair.frag: shades a hair fragment and hands it on. Shading: Kajiya-Kay with two shifted
// specular lobes (shared/strands.h), a colour running from root to tip with a per-strand
// brightness variation, the hemisphere ambient, and the light's visibility (head shadow by PCF,
// hair self-shadowing by the deep opacity map: light_visibility.glsl).
// Then, by transparency mode:
// - msaa (hair.frag): the ribbon's coverage becomes the fragment's sample mask
//   (shared/strands.h coverageMask): with MSAA the resolve averages it, with one sample it dithers.
// - oit (hair_oit.frag, HAIR_OIT): the fragment, with alpha = strand opacity x coverage, is pushed
//   onto its pixel's linked list (an atomic exchange of the head pointer, nodes from a pool with
//   an atomic counter); oit_resolve.frag blends the lists. A full pool drops the fragment and
//   counts it.
#extension GL_GOOGLE_include_directive : require
#include "shared/frame_params.h"
#include "shared/lighting.h"
#include "shared/strands.h"

layout(push_constant) uniform PushBlock { HairPush push; };
layout(set = 0, binding = kHairBindingFrame) uniform FrameBlock { FrameParams frame; };
#include "light_visibility.glsl"

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
layout(location = 0) out vec4 outColor;

vec3 shade()
{
    vec3 t = normalize(inTangent);
    vec3 v = normalize(frame.cameraPosition - inWorld);
    vec3 n = v - t * dot(t, v);  // the ribbon faces the camera: its normal is the view, made perpendicular to t
    n = dot(n, n) > 1e-8 ? normalize(n) : vec3(0.0, 1.0, 0.0);
    float variation = 0.8 + 0.4 * hashToUnit(inStrand * 2654435761u);
    vec3 albedo = mix(push.rootColor, push.tipColor, inT) * variation;
    // Hair receiving the hair's own depth map needs a bias of about a strand's depth extent.
    float visibility = lightVisibility(inWorld, gl_FragCoord.xy, 4.0 * frame.shadowBias);
    vec3 radiance = kajiyaKay(t, n, frame.lightDirection, v, albedo, push.specularShift,
                              frame.lightColor * frame.lightIntensity * visibility);
    radiance += albedo * frame.ambientIntensity * hemisphereAmbient(n, frame.skyColor, frame.groundColor);
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
