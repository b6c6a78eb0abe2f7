#version 460
// oit_resolve.comp: blends each pixel's list of hair fragments into one premultiplied colour and
// alpha (oit_composite.frag lays it over the target). A compute pass, so it runs on every unit of
// the GPU, not only those that run graphics (an H100 has few of those). The
// nearest `k` are kept sorted (insertion into a small array) and composited front to back; the
// ones behind them are blended as one layer whose colour is their alpha-weighted mean and whose
// alpha is 1 - prod(1 - alpha): both sums commute, so the result never depends on the order the
// fragments were stored in (TressFX sorts the nearest k and blends the rest unsorted; this tail
// is its order-independent variant). Output is premultiplied: composited as src + dst * (1 - alpha).
#extension GL_GOOGLE_include_directive : require
#include "shared/shadows.h"

layout(local_size_x = 8, local_size_y = 8) in;
layout(push_constant) uniform PushBlock { uint width; uint height; uint k; uint maxWalk; } push;
layout(set = 0, binding = 0, std430) readonly buffer Heads { uint heads[]; };
layout(set = 0, binding = 1, std430) readonly buffer Nodes { OitNode nodes[]; };
layout(set = 0, binding = 2, std430) readonly buffer Counters { OitCounters counters; };
layout(set = 0, binding = 3, rgba16f) uniform writeonly image2D hairColor;

// Fragments order by depth, ties by their colour bits, so equal depths sort the same whatever
// order they were stored in.
bool farther(float da, uint ca, float db, uint cb)
{
    return da != db ? da > db : ca > cb;
}

vec4 unpackColor(uint c)
{
    vec4 v = unpackUnorm4x8(c);
    return vec4(v.rgb * v.rgb, v.a);  // stored as sqrt(rgb)
}

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

    float nearDepth[kMaxOitK];
    uint nearColor[kMaxOitK];
    uint count = 0u;
    uint k = min(push.k, kMaxOitK);
    vec3 tailColor = vec3(0.0);   // sum of alpha * colour behind the nearest k
    float tailWeight = 0.0;       // sum of alpha
    float tailClear = 1.0;        // prod(1 - alpha)

    // The walk is bounded by the pool (a list never holds more nodes than were handed out).
    uint capacity = counters.capacity;
    for (uint steps = 0u; node != kOitNil && node < capacity && steps < push.maxWalk; ++steps) {
        OitNode n = nodes[node];
        node = n.next;
        uint c = n.color;
        float d = n.depth;
        if (count < k) {
            uint i = count++;
            while (i > 0u && farther(nearDepth[i - 1u], nearColor[i - 1u], d, c)) {
                nearDepth[i] = nearDepth[i - 1u];
                nearColor[i] = nearColor[i - 1u];
                --i;
            }
            nearDepth[i] = d;
            nearColor[i] = c;
            continue;
        }
        vec4 tail;
        if (farther(nearDepth[k - 1u], nearColor[k - 1u], d, c)) {
            // Nearer than the farthest kept: that one goes to the tail, this one is inserted.
            tail = unpackColor(nearColor[k - 1u]);
            uint i = k - 1u;
            while (i > 0u && farther(nearDepth[i - 1u], nearColor[i - 1u], d, c)) {
                nearDepth[i] = nearDepth[i - 1u];
                nearColor[i] = nearColor[i - 1u];
                --i;
            }
            nearDepth[i] = d;
            nearColor[i] = c;
        } else {
            tail = unpackColor(c);
        }
        tailColor += tail.a * tail.rgb;
        tailWeight += tail.a;
        tailClear *= 1.0 - tail.a;
    }

    // Front to back: colour += transmittance * alpha * c; transmittance *= 1 - alpha.
    vec3 color = vec3(0.0);
    float transmittance = 1.0;
    for (uint i = 0u; i < count; ++i) {
        vec4 c = unpackColor(nearColor[i]);
        color += transmittance * c.a * c.rgb;
        transmittance *= 1.0 - c.a;
    }
    if (tailWeight > 0.0) {
        color += transmittance * (1.0 - tailClear) * (tailColor / tailWeight);
        transmittance *= tailClear;
    }
    imageStore(hairColor, ivec2(xy), vec4(color, 1.0 - transmittance));
}
