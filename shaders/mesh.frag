#version 460
// mesh.frag: shades the head (its scalp painted under the hair) with one directional key light plus a hemisphere ambient
// (shared/lighting.h), shadowed by the head and the hair as the shadow mask has it for this pixel
// (mesh_shadow.comp evaluated light_visibility.glsl in compute), tone-mapped; the target is sRGB
// so the hardware encodes the output.
#extension GL_GOOGLE_include_directive : require
#include "shared/frame_params.h"
#include "shared/mesh_params.h"
#include "shared/lighting.h"

layout(set = 0, binding = kFrameParamsBinding) uniform FrameBlock { FrameParams frame; };
layout(push_constant) uniform PushBlock { MeshPush push; };
layout(set = 0, binding = kMeshBindingShadowMask) uniform sampler2D shadowMask;


layout(location = 0) in vec3 inWorldPosition;
layout(location = 1) in vec3 inWorldNormal;
layout(location = 2) in float inScalp;
layout(location = 0) out vec4 outColor;

void main()
{
    vec3 n = normalize(inWorldNormal);
    vec3 v = normalize(frame.cameraPosition - inWorldPosition);
    if (dot(n, v) < 0.0)
        n = -n;  // back faces seen through open meshes shade like their front
    vec2 parts = texelFetch(shadowMask, ivec2(gl_FragCoord.xy), 0).rg;
    float visibility = parts.x * parts.y;
    // The scalp under the hair is painted a darkened hair colour, fading out past the hairline,
    // and matte: a scalp under hair has no highlight of its own.
    float scalp = push.scalpStrength * clamp(inScalp, 0.0, 1.0);
    vec3 albedo = mix(push.albedo, push.scalpAlbedo, scalp);
    vec3 radiance = surfaceRadiance(n, frame.lightDirection, v, albedo, mix(push.roughness, 1.0, scalp),
                                    frame.lightColor * frame.lightIntensity * visibility);
    radiance += albedo * frame.ambientIntensity *
                hemisphereAmbient(n, frame.skyColor, frame.groundColor);
    outColor = vec4(toneMapAces(radiance * frame.exposure), 1.0);
}
