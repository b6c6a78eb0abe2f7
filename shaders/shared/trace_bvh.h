// shaders/shared/trace_bvh.h: the closest (or any) hit of a ray among the segments and triangles of
// shared/trace.h through their bounding-volume hierarchy: a stack walk, the nearer child first,
// boxes beyond the closest hit so far skipped. One copy for the path tracer and its CPU twin.
// The buffers are reached through accessors the includer defines first: in GLSL the shader's
// storage buffers (reference_trace.comp), in C++ the spans of TraceBuffers below:
//   BvhNode traceNode(TraceBuffers s, uint i);   uint tracePrimIndex(TraceBuffers s, uint i);
//   TraceSegment traceSegment(TraceBuffers s, uint i);   TraceTriangle traceTriangle(TraceBuffers s, uint i);
#ifndef WISP_SHARED_TRACE_BVH_H
#define WISP_SHARED_TRACE_BVH_H
#include "prelude.h"
#include "trace.h"

GPU_NAMESPACE_BEGIN

#ifdef __cplusplus
struct TraceBuffers {
    const BvhNode* nodes = nullptr;
    const uint* prims = nullptr; // primitive numbers, in the leaves' order
    const TraceSegment* segments = nullptr;
    const TraceTriangle* triangles = nullptr;
    uint segmentCount = 0;
    uint nodeCount = 0;
};
inline BvhNode traceNode(const TraceBuffers& s, uint i)
{
    return s.nodes[i];
}
inline uint tracePrimIndex(const TraceBuffers& s, uint i)
{
    return s.prims[i];
}
inline TraceSegment traceSegment(const TraceBuffers& s, uint i)
{
    return s.segments[i];
}
inline TraceTriangle traceTriangle(const TraceBuffers& s, uint i)
{
    return s.triangles[i];
}
#endif

// The entry of the ray into primitive `prim` within (tMin, tMax): t (or -1) and u, v of TraceHit.
GPU_FN vec3 tracePrimitive(TraceBuffers scene, uint prim, vec3 o, vec3 d, float tMin, float tMax)
{
    if (prim < scene.segmentCount) {
        TraceSegment s = traceSegment(scene, prim);
        return capsuleEntry(o, d, s.a, s.b, s.radius, tMin, tMax);
    }
    TraceTriangle tri = traceTriangle(scene, prim - scene.segmentCount);
    return triangleEntry(o, d, vec3(tri.p0), vec3(tri.p1), vec3(tri.p2), tMin, tMax);
}

// Is p inside the capsule of segment i (a joint's neighbour: i may be any number, or none)?
GPU_FN bool traceInsideSegment(TraceBuffers scene, uint i, uint strand, vec3 p)
{
    if (i >= scene.segmentCount)
        return false;
    TraceSegment s = traceSegment(scene, i);
    vec3 w = s.b - s.a;
    vec3 pa = p - s.a;
    float ww = dot(w, w);
    vec3 e = pa - (ww > 0.0f ? clamp(dot(pa, w) / ww, 0.0f, 1.0f) : 0.0f) * w;
    return s.strand == strand && dot(e, e) < s.radius * s.radius;
}

// Does the entry of the ray into segment `prim` at t pass through a joint of strand `strand` from
// inside it? A path leaving a fibre starts on its axis, inside the strand: its capsules overlap at
// every joint, and a ray still inside one of them enters its neighbour's end sphere there without
// entering the strand. Such entries are no hits (left alone, they would scatter the path again
// and shadow the fibre's own light, more the more the ray runs along the strand).
GPU_FN bool traceThroughJoint(TraceBuffers scene, uint prim, uint strand, vec3 o, vec3 d, float t)
{
    if (strand == kTraceNoHit || prim >= scene.segmentCount || traceSegment(scene, prim).strand != strand)
        return false;
    vec3 p = o + t * d;
    return traceInsideSegment(scene, prim - 1u, strand, p) || traceInsideSegment(scene, prim + 1u, strand, p);
}

// The closest entry along the ray within (tMin, tMax); with anyHit, the first found (shadow rays).
// `fromStrand`: the strand whose fibre the ray leaves (its origin inside it: traceThroughJoint), or
// kTraceNoHit.
GPU_FN TraceHit traceScene(TraceBuffers scene, vec3 o, vec3 d, float tMin, float tMax, bool anyHit, uint fromStrand)
{
    TraceHit hit = traceMiss();
    if (scene.nodeCount == 0u)
        return hit;
    vec3 invD = traceInverse(d);
    float closest = tMax;
    uint stack[kTraceStackSize];
    uint depth = 0u;
    uint node = 0u;
    BvhNode root = traceNode(scene, 0u);
    if (boxEntry(o, invD, root.lo, root.hi, tMin, closest) == kTraceInfinity)
        return hit;
    for (;;) {
        BvhNode n = traceNode(scene, node);
        if (n.count > 0u) {
            for (uint i = 0u; i < n.count; ++i) {
                uint prim = tracePrimIndex(scene, n.first + i);
                vec3 e = tracePrimitive(scene, prim, o, d, tMin, closest);
                if (e.x > 0.0f && !traceThroughJoint(scene, prim, fromStrand, o, d, e.x)) {
                    closest = e.x;
                    hit.t = e.x;
                    hit.prim = prim;
                    hit.u = e.y;
                    hit.v = e.z;
                    if (anyHit)
                        return hit;
                }
            }
        } else {
            BvhNode c0 = traceNode(scene, n.first);
            BvhNode c1 = traceNode(scene, n.first + 1u);
            float t0 = boxEntry(o, invD, c0.lo, c0.hi, tMin, closest);
            float t1 = boxEntry(o, invD, c1.lo, c1.hi, tMin, closest);
            uint nearChild = t0 <= t1 ? n.first : n.first + 1u;
            uint farChild = t0 <= t1 ? n.first + 1u : n.first;
            float tNear = min(t0, t1);
            float tFar = max(t0, t1);
            if (tNear != kTraceInfinity) {
                if (tFar != kTraceInfinity && depth < kTraceStackSize)
                    stack[depth++] = farChild;
                node = nearChild;
                continue;
            }
        }
        // Next from the stack (boxes pushed before a closer hit was found are tested again on the way).
        bool found = false;
        while (depth > 0u && !found) {
            node = stack[--depth];
            BvhNode next = traceNode(scene, node);
            found = boxEntry(o, invD, next.lo, next.hi, tMin, closest) != kTraceInfinity;
        }
        if (!found)
            return hit;
    }
}

GPU_NAMESPACE_END

#endif
