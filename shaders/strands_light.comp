#version 460
// strands_light.comp: the hair in the light's maps, one thread per segment of the light's strands
// (strands_generate_light.comp: fewer and wider, the same coverage; clump by clump as
// clumpOrderedSegment takes them). The thread walks the texels whose centres can lie in the
// ribbon, row by row (lightRowCentres). Specialization constant 0 chooses the map:
//   false (light.depth):   the hair's first depth, atomicMin over the float's bits (depths are
//                          positive, so their bits order as the numbers do; only a fragment
//                          nearer than the texel holds takes the atomic), on every texel whose
//                          centre lies within the ribbon, at least a texel wide (as rasterization does)
//   true  (light.opacity): on the same texels, the strand's opacity x the share of the texel-wide
//                          ribbon its width covers, added in fixed point to the deep opacity layer
//                          its depth falls in behind the first depth (Yuksel & Keyser 2008;
//                          shared/shadows.h domLayerMask), as the tessellation path's light pass
//                          adds it
#extension GL_GOOGLE_include_directive : require
#include "shared/frame_params.h"
#include "shared/strand_raster.h"

layout(local_size_x = 64) in;  // kRasterGroupSize
layout(constant_id = 0) const bool kOpacity = false;
layout(push_constant) uniform PushBlock { StrandRasterPush push; };
layout(set = 0, binding = kRasterBindingFrame) uniform FrameBlock { FrameParams frame; };
layout(set = 0, binding = kRasterBindingVertices, std430) readonly buffer Vertices { vec4 vertices[]; };
layout(set = 0, binding = kRasterBindingColors, std430) readonly buffer Colors { uint colors[]; };
layout(set = 0, binding = kRasterBindingLightDepth, std430) buffer LightDepth { uint lightDepth[]; };
layout(set = 0, binding = kRasterBindingLightOpacity, std430) buffer LightOpacity { uint lightOpacity[]; };

void touch(RasterSegment s, float za, float zb, float alpha, ivec2 texel)
{
    if (texel.x < 0 || texel.y < 0 || texel.x >= int(push.targetWidth) || texel.y >= int(push.targetHeight))
        return;
    vec3 hit = lightTexelHit(s, vec2(texel) + 0.5);  // as the tessellation path's light ribbons
    if (hit.x <= 0.0)
        return;
    uint index = uint(texel.y) * push.targetWidth + uint(texel.x);
    float depth = mix(za, zb, hit.y);
    if (!kOpacity) {
        // The texel only ever gets nearer: a value read now (however stale) is no nearer than the
        // texel will end, so a fragment not nearer than it changes nothing, and needs no atomic.
        uint bits = floatBitsToUint(max(depth, 0.0));
        if (bits < lightDepth[index])
            atomicMin(lightDepth[index], bits);
        return;
    }
    float z0 = uintBitsToFloat(lightDepth[index]);
    uint layers = clamp(push.domLayers, 1u, kMaxDomLayers);
    uint layer = min(uint(max(depth - z0, 0.0) / max(frame.domSpacing, 1e-12)), layers - 1u);
    uint add = uint(alpha * hit.z * kOpacityFixedScale + 0.5);
    if (add > 0u)
        atomicAdd(lightOpacity[index * 4u + layer], add);
}

void main()
{
    uint thread = linearInvocation(gl_GlobalInvocationID, gl_NumWorkGroups.x * gl_WorkGroupSize.x);
    uint segment = clumpOrderedSegment(thread, push.divisions, push.drawnPerGuide);
    if (thread >= push.segmentCount)
        return;
    uint v = segment / push.divisions * (push.divisions + 1u) + segment % push.divisions;
    vec4 a = vertices[v];
    vec4 b = vertices[v + 1u];
    if (a.w < 0.0 || b.w < 0.0)
        return;
    float alpha = 0.5 * (unpackUnorm4x8(colors[v]).w + unpackUnorm4x8(colors[v + 1u]).w);
    RasterSegment s = makeRasterSegment(a.xy, b.xy, a.w, b.w);
    // The texels whose centres the ribbon, at least a texel wide, can hold, row by row.
    RasterSegment reach = makeRasterSegment(a.xy, b.xy, max(a.w, 0.5), max(b.w, 0.5));
    ivec4 bounds = lightTexelBounds(reach, a.xy, b.xy, push.targetWidth, push.targetHeight);
    for (int y = bounds.y; y <= bounds.w; ++y) {
        vec2 span = lightRowCentres(reach, float(y) + 0.5);
        int x0 = max(int(ceil(span.x - 0.5)), 0);
        int x1 = min(int(floor(span.y - 0.5)), int(push.targetWidth) - 1);
        for (int x = x0; x <= x1; ++x)
            touch(s, a.z, b.z, alpha, ivec2(x, y));
    }
}
