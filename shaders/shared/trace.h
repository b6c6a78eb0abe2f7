// shaders/shared/trace.h: rays against what the frame draws, one copy for the path tracer
// (shaders/reference_trace.comp) and C++ (its CPU twin, the BVH's builder and the tests): the strands'
// segments as capsules, the meshes' triangles, and the bounding-volume hierarchy over both
// (renderer/reference/trace_scene.cpp builds it on the CPU and flattens it into these nodes).
//
// The strands' shape. The real-time paths draw each segment between two consecutive strand vertices
// (placeStrandPoint, shared/strands.h) as a ribbon facing the camera, as wide as strandWidthAt at
// each end, its coverage of each pixel computed exactly (shared/strand_raster.h segmentCoverage): the
// silhouette of a cylinder of that diameter seen from the camera. Here each segment is a capsule:
// the cylinder of radius r = half the mean of its two ends' widths around the segment, closed by
// spheres of that radius at both ends, so consecutive segments of a bent strand join without gaps
// or slits (the ribbons' joints overlap the same way). Seen from the camera it covers what the
// ribbon covers, to the taper within one segment (a few percent of the width: 0.85 / divisions).
// Unlike the ribbon it has a back, a side seen from the light and an offset h across it (Chiang
// 2016's fibre is a cylinder: h picks where on it a ray enters).
//
// Conventions: world space, asset units; ray directions unit length; t along the ray. Every hit is an
// entry: a ray whose origin is inside a capsule (a path leaving the fibre it scattered in, whose BSDF
// already accounts for the light's path inside it) passes out of it unhit; triangles are two-sided.
#ifndef WISP_SHARED_TRACE_H
#define WISP_SHARED_TRACE_H
#include "prelude.h"

GPU_NAMESPACE_BEGIN

GPU_CONST float kTraceInfinity = 3.0e38f;
GPU_CONST uint kTraceNoHit = 0xFFFFFFFFu;
// Primitives are numbered segments first, then triangles: p < segmentCount is a segment.
GPU_CONST uint kTraceStackSize = 64u; // the deepest tree the builder makes (renderer/reference/bvh.h kBvhMaxDepth)

// One drawn strand segment (a capsule).
struct TraceSegment {
    vec3 a;       // first vertex
    float radius; // asset units
    vec3 b;       // second vertex
    uint strand;  // the drawn strand (guide * strandsPerGuide + s)
};

// One mesh triangle, with the vertex normals and scalp weights its shading interpolates.
struct TraceTriangle {
    vec4 p0; // xyz position, w the scalp weight at the vertex
    vec4 p1;
    vec4 p2;
    vec4 n0; // xyz unit vertex normal, w the object (kMeshObject* of mesh_raster.h)
    vec4 n1;
    vec4 n2;
};

// A node of the flattened tree: an interior node's children are at `first` and first + 1; a leaf
// holds `count` primitives of the primitive index list from `first`.
struct BvhNode {
    vec3 lo;
    uint first;
    vec3 hi;
    uint count; // 0: interior
};

struct TraceHit {
    float t;   // kTraceInfinity: none
    uint prim; // kTraceNoHit: none
    float u;   // segment: where along it (0 at a, 1 at b, clamped); triangle: barycentric of p1
    float v;   // triangle: barycentric of p2
};

GPU_FN TraceHit traceMiss()
{
    TraceHit h;
    h.t = kTraceInfinity;
    h.prim = kTraceNoHit;
    h.u = 0.0f;
    h.v = 0.0f;
    return h;
}

// The first entry t in (tMin, tMax) of the ray into the sphere of centre c and radius r, or -1.
// (o - c + t d)^2 = r^2 with |d| = 1: t = -b -+ sqrt(b^2 - c), b = d.(o - c), c = |o - c|^2 - r^2;
// the origin inside (c < 0) is no entry.
GPU_FN float sphereEntry(vec3 o, vec3 d, vec3 centre, float r, float tMin, float tMax)
{
    vec3 oc = o - centre;
    float b = dot(d, oc);
    float c = dot(oc, oc) - r * r;
    float disc = b * b - c;
    if (c < 0.0f || disc < 0.0f)
        return -1.0f;
    float t = -b - sqrt(disc);
    return t > tMin && t < tMax ? t : -1.0f;
}

// The first entry of the ray into the capsule around segment a..b of radius r, t in (tMin, tMax):
// the infinite cylinder first (with w = b - a, the distance to the axis squared is
// |oa + t d|^2 - ((oa + t d).w)^2 / w.w, a quadratic in t), taken where the axial position lies on
// the segment; else the end spheres. Returns t (or -1) and, in .y, where along the segment the entry
// lies (0..1). The origin inside the capsule is no entry.
GPU_FN vec2 capsuleEntry(vec3 o, vec3 d, vec3 a, vec3 b, float r, float tMin, float tMax)
{
    vec3 w = b - a;
    vec3 oa = o - a;
    float ww = dot(w, w);
    if (ww < 1e-20f) { // a degenerate segment: a sphere
        float t = sphereEntry(o, d, a, r, tMin, tMax);
        return vec2(t, 0.0f);
    }
    float wd = dot(w, d);
    float wo = dot(w, oa);
    float s0 = clamp(wo / ww, 0.0f, 1.0f); // the origin's nearest point of the segment
    vec3 near0 = oa - s0 * w;
    if (dot(near0, near0) < r * r)
        return vec2(-1.0f, 0.0f); // inside
    // Quadratic A t^2 + 2 B t + C = 0, all terms multiplied by w.w.
    float A = ww - wd * wd;
    float B = ww * dot(oa, d) - wo * wd;
    float C = ww * dot(oa, oa) - wo * wo - r * r * ww;
    float disc = B * B - A * C;
    if (disc < 0.0f)
        return vec2(-1.0f, 0.0f); // misses the infinite cylinder, so its end spheres too
    if (A > 1e-12f * ww) {
        float t = (-B - sqrt(disc)) / A;
        float s = (wo + t * wd) / ww;
        if (s >= 0.0f && s <= 1.0f)
            return t > tMin && t < tMax ? vec2(t, s) : vec2(-1.0f, 0.0f);
    }
    // Past an end of the body (or along the axis): the sphere at that end.
    float ta = sphereEntry(o, d, a, r, tMin, tMax);
    float tb = sphereEntry(o, d, b, r, tMin, tMax);
    if (ta > 0.0f && (tb < 0.0f || ta <= tb))
        return vec2(ta, 0.0f);
    if (tb > 0.0f)
        return vec2(tb, 1.0f);
    return vec2(-1.0f, 0.0f);
}

// Moller & Trumbore 1997 ("Fast, Minimum Storage Ray/Triangle Intersection"), two-sided: t (or -1)
// and the barycentrics of p1 and p2 in .yz.
GPU_FN vec3 triangleEntry(vec3 o, vec3 d, vec3 p0, vec3 p1, vec3 p2, float tMin, float tMax)
{
    vec3 e1 = p1 - p0;
    vec3 e2 = p2 - p0;
    vec3 pv = cross(d, e2);
    float det = dot(e1, pv);
    if (abs(det) < 1e-20f)
        return vec3(-1.0f, 0.0f, 0.0f);
    float inv = 1.0f / det;
    vec3 tv = o - p0;
    float u = dot(tv, pv) * inv;
    if (u < 0.0f || u > 1.0f)
        return vec3(-1.0f, 0.0f, 0.0f);
    vec3 qv = cross(tv, e1);
    float v = dot(d, qv) * inv;
    if (v < 0.0f || u + v > 1.0f)
        return vec3(-1.0f, 0.0f, 0.0f);
    float t = dot(e2, qv) * inv;
    return t > tMin && t < tMax ? vec3(t, u, v) : vec3(-1.0f, 0.0f, 0.0f);
}

// The slab test (Kay & Kajiya 1986): does the ray meet the box within (tMin, tMax)? Returns the
// entry distance, or kTraceInfinity. invD = 1 / d per component (infinite where d is 0).
GPU_FN float boxEntry(vec3 o, vec3 invD, vec3 lo, vec3 hi, float tMin, float tMax)
{
    vec3 t0 = (lo - o) * invD;
    vec3 t1 = (hi - o) * invD;
    vec3 tn = min(t0, t1);
    vec3 tf = max(t0, t1);
    float enter = max(max(tn.x, tn.y), max(tn.z, tMin));
    float leave = min(min(tf.x, tf.y), min(tf.z, tMax));
    return enter <= leave ? enter : kTraceInfinity;
}

// The ray's direction inverted for the slab test (a zero component gives an infinity of its sign).
GPU_FN vec3 traceInverse(vec3 d)
{
    return vec3(1.0f / (d.x != 0.0f ? d.x : 1e-30f), 1.0f / (d.y != 0.0f ? d.y : 1e-30f),
                1.0f / (d.z != 0.0f ? d.z : 1e-30f));
}

GPU_NAMESPACE_END

#ifdef __cplusplus
static_assert(sizeof(gpu::TraceSegment) == 32);
static_assert(sizeof(gpu::TraceTriangle) == 96);
static_assert(sizeof(gpu::BvhNode) == 32);
#endif

#endif
