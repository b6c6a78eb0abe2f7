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

// On a variable whose value is the exact error of an addition or a product (the capsules'
// compensated arithmetic below): GLSL's `precise` keeps the compiler from fusing or reordering the
// operations that compute it. C++ needs nothing: the build targets x86-64 without -mfma, where
// nothing is contracted into an FMA, and keeps IEEE order.
#ifdef __cplusplus
#define GPU_PRECISE
#else
#define GPU_PRECISE precise
#endif

GPU_NAMESPACE_BEGIN

GPU_CONST float kTraceInfinity = 3.0e38f;
GPU_CONST uint kTraceNoHit = 0xFFFFFFFFu;
// Primitives are numbered segments first, then triangles: p < segmentCount is a segment.
GPU_CONST float kTraceBoxSlack = 1.0000005f; // boxEntry: 1 + 2 gamma(3), rounded up
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
    float v;   // segment: the offset h across the fibre (capsuleEntry); triangle: barycentric of p2
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

// ---- Capsules, robust for any radius at any distance -----------------------------------------
//
// A strand's radius (real hair: about 4e-5 in metres) can be a millionth of the ray's length to it.
// Solving the capsule's quadratic about the ray's origin loses it: its terms are of the origin's
// distance squared, where r^2 is below their rounding. So the ray is first moved, to twice float
// precision, to its point nearest the segment's middle (q = o + t0 d - a, traceShiftedOrigin), and
// everything after is solved there, in lengths of the segment's and the radius' size, by the
// geometric forms (Haines et al. 2019, "Precision Improvements for Ray/Sphere Intersection", Ray
// Tracing Gems ch. 7): the distance between the ray and the axis from their common normal, the
// chord from it. What is left is the rounding of q: about |q| 6e-8, a 1e-5 of the radius for a
// segment 300 radii long.

// Knuth's TwoSum and Dekker's product (Veltkamp's split, no FMA: Vulkan lets fma round twice),
// component-wise: hi + lo is exactly a + b, or a * b.
GPU_FN vec3 traceTwoSumError(vec3 a, vec3 b, vec3 s)
{
    GPU_PRECISE vec3 bb = s - a;
    GPU_PRECISE vec3 e = (a - (s - bb)) + (b - bb);
    return e;
}

GPU_FN vec3 traceSplitHigh(vec3 a)
{
    GPU_PRECISE vec3 c = 4097.0f * a; // 2^12 + 1: the top 12 bits of a's 24
    GPU_PRECISE vec3 hi = c - (c - a);
    return hi;
}

GPU_FN vec3 traceTwoProductError(vec3 a, vec3 b, vec3 p)
{
    vec3 ah = traceSplitHigh(a);
    vec3 bh = traceSplitHigh(b);
    GPU_PRECISE vec3 al = a - ah;
    GPU_PRECISE vec3 bl = b - bh;
    GPU_PRECISE vec3 e = ((ah * bh - p) + ah * bl + al * bh) + al * bl;
    return e;
}

// o + t0 d - a with only its last rounding: o - a and t0 d each exactly as a sum of two floats,
// their large parts added exactly, the small ones after.
GPU_FN vec3 traceShiftedOrigin(vec3 o, vec3 a, vec3 d, float t0)
{
    GPU_PRECISE vec3 m = o - a;
    vec3 me = traceTwoSumError(o, -a, m);
    vec3 t = vec3(t0);
    GPU_PRECISE vec3 p = t * d;
    vec3 pe = traceTwoProductError(t, d, p);
    GPU_PRECISE vec3 s = m + p;
    vec3 se = traceTwoSumError(m, p, s);
    GPU_PRECISE vec3 q = s + ((se + me) + pe);
    return q;
}

// The first entry t' (or -1e38) of the ray q + t' d into the sphere of radius r around v = 0, where q
// is of the sphere's size: the distance from the centre to the line as a vector (Haines et al.),
// so a grazing ray keeps its precision.
GPU_FN float sphereEntryLocal(vec3 q, vec3 d, float r)
{
    float dd = dot(d, d);
    float tau = -dot(q, d) / dd;
    vec3 e = q + tau * d;
    float e2 = dot(e, e);
    if (e2 > r * r)
        return -1e38f;
    return tau - sqrt((r * r - e2) / dd);
}

// The first entry of the ray into the capsule around segment a..b of radius r, t in (tMin, tMax):
// (t or -1, where along the segment the entry lies 0..1, h). h is the offset across the fibre that
// Chiang et al.'s BSDF takes: the signed distance between the ray and the axis, in radii, along
// normalize(cross(b - a, d)) (fiber_bsdf.h makeFiberFrame's y; 0 for a ray along the axis): the
// same anywhere on the ray, so on the end spheres too. The infinite cylinder first (a ray that
// misses it misses the spheres inside it), taken where the entry's axial position lies on the
// segment; else the end spheres. The origin inside the capsule is no entry.
GPU_FN vec3 capsuleEntry(vec3 o, vec3 d, vec3 a, vec3 b, float r, float tMin, float tMax)
{
    vec3 miss = vec3(-1.0f, 0.0f, 0.0f);
    vec3 w = b - a;
    float ww = dot(w, w);
    vec3 oa = o - a;
    float s0 = ww > 0.0f ? clamp(dot(oa, w) / ww, 0.0f, 1.0f) : 0.0f; // the origin's nearest point
    vec3 near0 = oa - s0 * w;
    if (dot(near0, near0) < r * r)
        return miss; // inside
    // The ray's point nearest the segment's middle, relative to a.
    float t0 = dot(a + 0.5f * w - o, d) / dot(d, d);
    vec3 q = traceShiftedOrigin(o, a, d, t0);
    if (ww <= 1e-12f * r * r) { // a segment of no length: a sphere
        float ts = t0 + sphereEntryLocal(q, d, r);
        return ts > tMin && ts < tMax ? vec3(ts, 0.0f, 0.0f) : miss;
    }
    float len = sqrt(ww);
    vec3 axis = w / len;
    vec3 qm = q - 0.5f * w;  // from the segment's middle: small for a ray along the axis, where
                             // the common normal's direction is least certain
    vec3 n = cross(axis, d); // the common normal of the ray and the axis
    float nn = dot(n, n);
    float dist = nn > 1e-12f * dot(d, d) ? dot(qm, n) / sqrt(nn) : 0.0f; // signed, the ray to the axis
    if (abs(dist) > r)
        return miss;
    float h = dist / r;
    float da = dot(d, axis);
    vec3 dp = d - da * axis; // the ray's direction across the axis
    float A = dot(dp, dp);
    float qa = dot(qm, axis);
    if (A > 1e-12f * dot(d, d)) {
        vec3 qp = qm - qa * axis;
        float tc = -dot(qp, dp) / A; // nearest the axis
        float tIn = tc - r * sqrt(max((1.0f - h) * (1.0f + h), 0.0f) / A);
        float s = 0.5f + (qa + tIn * da) / len;
        if (s >= 0.0f && s <= 1.0f) {
            float t = t0 + tIn;
            return t > tMin && t < tMax ? vec3(t, s, h) : miss;
        }
    }
    // Past an end of the body (or along the axis): the sphere at that end.
    float ta = t0 + sphereEntryLocal(q, d, r);
    float tb = t0 + sphereEntryLocal(qm - 0.5f * w, d, r);
    bool hitA = ta > tMin && ta < tMax;
    bool hitB = tb > tMin && tb < tMax;
    if (hitA && (!hitB || ta <= tb))
        return vec3(ta, 0.0f, h);
    if (hitB)
        return vec3(tb, 1.0f, h);
    return miss;
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
// entry distance, or kTraceInfinity. invD = 1 / d per component (infinite where d is 0). The exit
// is moved out by the slab distances' worst rounding (Ize 2013, "Robust BVH Ray Traversal": 1 +
// 2 gamma(3)), so a box a millionth of the ray's length thin is never missed by rounding.
GPU_FN float boxEntry(vec3 o, vec3 invD, vec3 lo, vec3 hi, float tMin, float tMax)
{
    vec3 t0 = (lo - o) * invD;
    vec3 t1 = (hi - o) * invD;
    vec3 tn = min(t0, t1);
    vec3 tf = max(t0, t1);
    float enter = max(max(tn.x, tn.y), max(tn.z, tMin));
    float leave = min(min(tf.x, tf.y) * kTraceBoxSlack, min(tf.z * kTraceBoxSlack, tMax));
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
