#version 460
// strands_depth.comp: one thread per pixel, before the compute path's fragments: the nearest and
// farthest of the meshes' depth samples at the pixel (a fragment in front of the nearest is in
// front of them all, one behind the farthest behind them all: only the meshes' edges need each
// sample), and the pixel's fragment count zeroed. With RASTER_SINGLE_SAMPLE
// (strands_depth_single.comp) the depth has one sample.
#extension GL_GOOGLE_include_directive : require
#include "shared/strand_raster.h"

layout(local_size_x = 8, local_size_y = 8) in;
layout(push_constant) uniform PushBlock { StrandRasterPush push; };
#ifdef RASTER_SINGLE_SAMPLE
layout(set = 0, binding = kRasterBindingMeshDepth) uniform sampler2D meshDepth;
#else
layout(set = 0, binding = kRasterBindingMeshDepth) uniform sampler2DMS meshDepth;
#endif
layout(set = 0, binding = kRasterBindingDepthRange, std430) writeonly buffer DepthRange { vec2 depthRange[]; };
layout(set = 0, binding = kRasterBindingCounts, std430) writeonly buffer Counts { uint counts[]; };

void main()
{
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (pixel.x >= int(push.targetWidth) || pixel.y >= int(push.targetHeight))
        return;
    uint p = uint(pixel.y) * push.targetWidth + uint(pixel.x);
#ifdef RASTER_SINGLE_SAMPLE
    float d = texelFetch(meshDepth, pixel, 0).r;
    vec2 range = vec2(d, d);
#else
    vec2 range = vec2(1.0, 0.0);
    for (int s = 0; s < int(push.samples); ++s) {
        float d = texelFetch(meshDepth, pixel, s).r;
        range = vec2(min(range.x, d), max(range.y, d));
    }
#endif
    depthRange[p] = range;
    counts[p] = 0u;
}
