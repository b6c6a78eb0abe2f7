#version 460
// strands_depth.comp: one thread per pixel, before the compute path's fragments: the nearest and
// farthest of the meshes' depth samples at the pixel (a fragment in front of the nearest is in
// front of them all, one behind the farthest behind them all: only the meshes' edges need each
// sample), and the pixel's fragment count zeroed. The workgroup is one 8 x 8 tile: it writes the
// farthest of its samples (kRasterBindingTileDepth), which lets strands_fragments.comp skip the
// segments behind every tile they reach without visiting their pixels. The samples' depths come
// from the meshes' depth image (copied as float bits into the samples' buffer
// strands_fragments.comp reads: one sample with RASTER_SINGLE_SAMPLE, strands_depth_single.comp),
// or with MESH_DEPTH_BUFFER (strands_depth_buffer.comp) from that buffer, where the compute meshes
// (mesh_raster.comp) drew.
#extension GL_GOOGLE_include_directive : require
#include "shared/strand_raster.h"

layout(local_size_x = 8, local_size_y = 8) in;
layout(push_constant) uniform PushBlock { StrandRasterPush push; };
#if defined(MESH_DEPTH_BUFFER)
layout(set = 0, binding = kRasterBindingMeshSamples, std430) readonly buffer MeshSamples { uint meshSamples[]; };
#else
#ifdef RASTER_SINGLE_SAMPLE
layout(set = 0, binding = kRasterBindingMeshDepth) uniform sampler2D meshDepth;
#else
layout(set = 0, binding = kRasterBindingMeshDepth) uniform sampler2DMS meshDepth;
#endif
layout(set = 0, binding = kRasterBindingMeshSamples, std430) writeonly buffer MeshSamples { uint meshSamples[]; };
#endif
layout(set = 0, binding = kRasterBindingDepthRange, std430) writeonly buffer DepthRange { vec2 depthRange[]; };
layout(set = 0, binding = kRasterBindingCounts, std430) writeonly buffer Counts { uint counts[]; };
layout(set = 0, binding = kRasterBindingTileDepth, std430) writeonly buffer TileDepth { float tileDepth[]; };

shared uint tileFarthest;  // float bits: depths are >= 0, so their bits order as the values

// The pixel's nearest and farthest sample (its samples copied to the buffer on the way), its
// range written and its count zeroed.
vec2 pixelDepthRange(ivec2 pixel)
{
    uint p = uint(pixel.y) * push.targetWidth + uint(pixel.x);
    vec2 range = vec2(1.0, 0.0);
    for (uint s = 0u; s < push.samples; ++s) {
#if defined(MESH_DEPTH_BUFFER)
        float d = uintBitsToFloat(meshSamples[p * push.samples + s]);
#else
#ifdef RASTER_SINGLE_SAMPLE
        float d = texelFetch(meshDepth, pixel, 0).r;
#else
        float d = texelFetch(meshDepth, pixel, int(s)).r;
#endif
        meshSamples[p * push.samples + s] = floatBitsToUint(d);
#endif
        range = vec2(min(range.x, d), max(range.y, d));
    }
    depthRange[p] = range;
    counts[p] = 0u;
    return range;
}

void main()
{
    if (gl_LocalInvocationIndex == 0u)
        tileFarthest = 0u;
    barrier();
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (pixel.x < int(push.targetWidth) && pixel.y < int(push.targetHeight)) {
        float farthest = pixelDepthRange(pixel).y;
        atomicMax(tileFarthest, floatBitsToUint(farthest > 0.0 ? farthest : 0.0));  // (not -0's bits)
    }
    barrier();
    if (gl_LocalInvocationIndex == 0u)
        tileDepth[gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x] = uintBitsToFloat(tileFarthest);
}
