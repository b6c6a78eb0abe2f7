#version 460
// mesh.frag: shades the head (its scalp painted under the hair) with the key, fill and rim lights
// plus a hemisphere ambient (shared/lighting.h through shared/mesh_raster.h's meshSurfaceColor), the
// key shadowed by the head and the hair as the shadow mask has it for this pixel (mesh_shadow.comp
// evaluated light_visibility.glsl in compute), tone-mapped; the target is sRGB so the hardware
// encodes the output.
#extension GL_GOOGLE_include_directive : require
#include "shared/frame_params.h"
#include "shared/mesh_params.h"
#include "shared/mesh_raster.h"  // meshSurfaceColor: the same shading as the compute meshes

layout(set = 0, binding = kFrameParamsBinding) uniform FrameBlock { FrameParams frame; };
layout(push_constant) uniform PushBlock { MeshPush push; };
layout(set = 0, binding = kMeshBindingShadowMask) uniform sampler2D shadowMask;


layout(location = 0) in vec3 inWorldPosition;
layout(location = 1) in vec3 inWorldNormal;
layout(location = 2) in float inScalp;
layout(location = 0) out vec4 outColor;

void main()
{
    vec2 parts = texelFetch(shadowMask, ivec2(gl_FragCoord.xy), 0).rg;
    outColor = vec4(meshSurfaceColor(frame, normalize(inWorldNormal), normalize(frame.cameraPosition - inWorldPosition),
                                     parts.x * parts.y, push.albedo, push.roughness, push.scalpAlbedo,
                                     push.scalpStrength * clamp(inScalp, 0.0, 1.0)),
                    1.0);
}
