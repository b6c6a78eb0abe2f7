#version 460
// oit_resolve.comp: blends each pixel's list of hair fragments into one premultiplied colour and
// alpha (oit_composite.frag lays it over the target). A compute pass, so it runs on every unit of
// the GPU, not only those that run graphics (an H100 has few of those). The
// nearest `k` are kept sorted and composited front to back; the ones behind them are blended as
// one layer whose colour is their alpha-weighted mean and whose alpha is 1 - prod(1 - alpha), both
// summed in fixed point so the result never depends on the order the fragments were stored in
// (TressFX sorts the nearest k and blends the rest unsorted; this tail is its order-independent
// variant). The same code (shared/strand_raster.h insertFragment, resolveFragments) keeps each
// pixel's fragments in the compute path's rasterizer. Output is premultiplied: composited as
// src + dst * (1 - alpha).
#extension GL_GOOGLE_include_directive : require
#include "shared/shadows.h"
#include "shared/strand_raster.h"

layout(local_size_x = 8, local_size_y = 8) in;
layout(constant_id = 0) const uint kOitK = 8u;  // oit_k, 1 .. kMaxOitK: the lists stay in registers
layout(push_constant) uniform PushBlock { uint width; uint height; uint k; uint maxWalk; } push;
layout(set = 0, binding = kOitResolveBindingHeads, std430) readonly buffer Heads { uint heads[]; };
layout(set = 0, binding = kOitResolveBindingNodes, std430) readonly buffer Nodes { OitNode nodes[]; };
layout(set = 0, binding = kOitResolveBindingCounters, std430) readonly buffer Counters { OitCounters counters; };
layout(set = 0, binding = kOitResolveBindingColor, rgba16f) uniform writeonly image2D hairColor;

void main()
{
    uvec2 xy = gl_GlobalInvocationID.xy;
    if (xy.x >= push.width || xy.y >= push.height)
        return;
    uint node = heads[xy.y * push.width + xy.x];
    if (node == kOitNil) {
        imageStore(hairColor, ivec2(xy), vec4(0.0));
        return;
    }
    const uint k = kOitK;
    PixelFragments f = emptyPixelFragments();
    // The walk is bounded by the pool (a list never holds more nodes than were handed out).
    uint capacity = counters.capacity;
    for (uint steps = 0u; node != kOitNil && node < capacity && steps < push.maxWalk; ++steps) {
        OitNode n = nodes[node];
        node = n.next;
        insertFragment(f, k, n.depth, n.color);
    }
    imageStore(hairColor, ivec2(xy), resolveFragments(f, k));
}
