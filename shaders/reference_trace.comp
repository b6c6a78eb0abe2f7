#version 460
// reference_trace.comp: the path-traced reference, one thread per pixel: `push.samples` paths from
// sample `push.firstSample` on (shared/reference_path.h referenceSample), added to the pixel's sums,
// the even samples' in the first half of the buffer and the odd samples' in the second (their
// difference tells how much noise is left), and the rays they cast to the pixel's count. The
// hierarchy is walked through shared/trace_bvh.h with this shader's buffers as its accessors.
#extension GL_GOOGLE_include_directive : require
#include "shared/reference_params.h"
#include "shared/trace.h"

layout(local_size_x = kReferenceGroupSize, local_size_y = kReferenceGroupSize) in;
layout(set = 0, binding = kReferenceBindingNodes, std430) readonly buffer Nodes { BvhNode nodes[]; };
layout(set = 0, binding = kReferenceBindingPrims, std430) readonly buffer Prims { uint prims[]; };
layout(set = 0, binding = kReferenceBindingSegments, std430) readonly buffer Segments { TraceSegment segments[]; };
layout(set = 0, binding = kReferenceBindingTriangles, std430) readonly buffer Triangles { TraceTriangle triangles[]; };

// trace_bvh.h's accessors.
struct TraceBuffers {
    uint segmentCount;
    uint nodeCount;
};
BvhNode traceNode(TraceBuffers s, uint i) { return nodes[i]; }
uint tracePrimIndex(TraceBuffers s, uint i) { return prims[i]; }
TraceSegment traceSegment(TraceBuffers s, uint i) { return segments[i]; }
TraceTriangle traceTriangle(TraceBuffers s, uint i) { return triangles[i]; }

#include "shared/reference_path.h"

layout(set = 0, binding = kReferenceBindingParams) uniform ParamsBlock { ReferenceParams params; };
layout(set = 0, binding = kReferenceBindingSums, std430) buffer Sums { vec4 sums[]; };
layout(set = 0, binding = kReferenceBindingRays, std430) buffer Rays { uint rays[]; };
layout(push_constant) uniform PushBlock { ReferencePush push; };

void main()
{
    uvec2 pixel = gl_GlobalInvocationID.xy;
    if (pixel.x >= params.width || pixel.y >= params.height)
        return;
    TraceBuffers scene = TraceBuffers(params.segmentCount, params.nodeCount);
    uint pixels = params.width * params.height;
    uint at = pixel.y * params.width + pixel.x;
    vec4 even = vec4(0.0), odd = vec4(0.0);
    uint traced = 0u;
    for (uint k = 0u; k < push.samples; ++k) {
        uint s = push.firstSample + k;
        vec4 r = referenceSample(scene, params, pixel, s, traced);
        if ((s & 1u) == 0u)
            even += r;
        else
            odd += r;
    }
    sums[at] += even;
    sums[pixels + at] += odd;
    rays[at] += traced;
}
