#version 460
// mesh_shadow.comp: the meshes' shadow mask, one thread per pixel. From the nearest of the pixel's
// depth samples (the meshes' depth pass) it places the surface in the world and evaluates the key
// light's visibility there as mesh.frag did per fragment (light_visibility.glsl: PCF over the
// head's depth from the light, the hair's transmittance from the deep opacity map). Done in
// compute, where a GPU like the H100 runs on all its units (it runs fragment shaders on few);
// mesh.frag then reads one texel. Pixels without a mesh keep visibility 1.
// With MESH_SINGLE_SAMPLE (mesh_shadow_single.comp) the depth has one sample.
#extension GL_GOOGLE_include_directive : require
#include "shared/frame_params.h"
#include "shared/mesh_params.h"

layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = kMeshBindingFrame) uniform FrameBlock { FrameParams frame; };
layout(push_constant) uniform PushBlock { MeshShadowPush push; };
#ifdef MESH_SINGLE_SAMPLE
layout(set = 0, binding = kMeshBindingDepth) uniform sampler2D meshDepth;
#else
layout(set = 0, binding = kMeshBindingDepth) uniform sampler2DMS meshDepth;
#endif
layout(set = 0, binding = kMeshBindingShadowMask, rgba8) uniform writeonly image2D shadowMask;
#include "light_visibility.glsl"

void main()
{
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (pixel.x >= int(push.width) || pixel.y >= int(push.height))
        return;
#ifdef MESH_SINGLE_SAMPLE
    float depth = texelFetch(meshDepth, pixel, 0).r;
#else
    float depth = 1.0;
    for (int s = 0; s < int(push.samples); ++s)
        depth = min(depth, texelFetch(meshDepth, pixel, s).r);
#endif
    vec2 visibility = vec2(1.0);
    if (depth < 1.0) {
        vec2 ndc = (vec2(pixel) + 0.5) / vec2(push.width, push.height) * 2.0 - 1.0;
        vec4 world = push.inverseViewProjection * vec4(ndc, depth, 1.0);
        visibility = lightVisibilityParts(world.xyz / world.w, vec2(pixel) + 0.5, frame.shadowBias, true);
    }
    imageStore(shadowMask, pixel, vec4(visibility, 0.0, 1.0));
}
