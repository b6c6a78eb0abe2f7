#version 460
// hair.frag: Kajiya-Kay hair shading with two shifted specular lobes (shared/strands.h), a colour
// running from root to tip with a per-strand brightness variation, and the hemisphere ambient.
// The ribbon's coverage becomes the fragment's sample mask (shared/strands.h coverageMask): with
// MSAA the resolve averages it, with one sample it dithers.
#extension GL_GOOGLE_include_directive : require
#include "shared/frame_params.h"
#include "shared/lighting.h"
#include "shared/strands.h"

layout(push_constant) uniform PushBlock { HairPush push; };
layout(set = 0, binding = kHairBindingFrame) uniform FrameBlock { FrameParams frame; };

layout(location = 0) in vec3 inWorld;
layout(location = 1) in vec3 inTangent;
layout(location = 2) in float inT;
layout(location = 3) flat in uint inStrand;
layout(location = 4) in float inAlpha;
layout(location = 0) out vec4 outColor;

void main()
{
    vec3 t = normalize(inTangent);
    vec3 v = normalize(frame.cameraPosition - inWorld);
    vec3 n = v - t * dot(t, v);  // the ribbon faces the camera: its normal is the view, made perpendicular to t
    n = dot(n, n) > 1e-8 ? normalize(n) : vec3(0.0, 1.0, 0.0);
    float variation = 0.8 + 0.4 * hashToUnit(inStrand * 2654435761u);
    vec3 albedo = mix(push.rootColor, push.tipColor, inT) * variation;
    vec3 radiance = kajiyaKay(t, n, frame.lightDirection, v, albedo, push.specularShift,
                              frame.lightColor * frame.lightIntensity);
    radiance += albedo * frame.ambientIntensity * hemisphereAmbient(n, frame.skyColor, frame.groundColor);
    uint pixel = uint(gl_FragCoord.x) * 73856093u ^ uint(gl_FragCoord.y) * 19349663u;
    uint mask = coverageMask(inAlpha, push.samples, inStrand, pixel);
    if (mask == 0u)
        discard;
    gl_SampleMask[0] = int(mask);
    outColor = vec4(toneMapAces(radiance * frame.exposure), 1.0);
}
