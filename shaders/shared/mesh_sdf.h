// shaders/shared/mesh_sdf.h: the signed distance to a triangle mesh, compiled as GLSL and as C++.
// The distance is the closest point's (Ericson, Real-Time Collision Detection, 5.1.5, with the
// feature it lies on); the sign is that of (p - closest) against the angle-weighted pseudonormal
// of that feature (Baerentzen & Aanaes 2005, "Signed distance computation using the angle weighted
// pseudonormal"): the face's normal inside a face, the sum of its faces' normals on an edge, the
// normals of the faces around a vertex weighted by their angles there at a vertex. Negative inside.
//
// The field: a grid of nodes over the mesh's bounds and a margin, cubic cells, built in two kernels
// (mesh_sdf_splat.comp, mesh_sdf_sign.comp; CPU twin physics/mesh_sdf.cpp):
//   splat: one thread per work item (a triangle and a box of nodes around it, at most
//          kSdfMaxItemNodes: a large triangle is several items, so no invocation runs long). Each
//          node of the box nearer the triangle than the band takes the smallest key of the
//          triangles near it by a 32-bit atomicMin: the distance quantized over the band in the
//          high bits, the triangle's index in the low `dims.w` bits (the nearest triangle, ties
//          within a quantum to the lowest index).
//   sign:  one thread per row of nodes along x. A node with a key takes its triangle's exact signed
//          distance; the others lie farther than the band and take +-band, the sign of the row's
//          previous node with a key (the next one before any): the surface cannot cross the row
//          between two nodes without a node within the band (a row with none: outside).
#ifndef WISP_SHARED_MESH_SDF_H
#define WISP_SHARED_MESH_SDF_H
#include "prelude.h"

#ifndef GPU_INOUT
#ifdef __cplusplus
#define GPU_INOUT(T) T&
#else
#define GPU_INOUT(T) inout T
#endif
#endif

GPU_NAMESPACE_BEGIN

// Where on a triangle abc its closest point to p lies.
GPU_CONST uint kSdfVertexA = 0u;
GPU_CONST uint kSdfVertexB = 1u;
GPU_CONST uint kSdfVertexC = 2u;
GPU_CONST uint kSdfEdgeAB = 3u;
GPU_CONST uint kSdfEdgeBC = 4u;
GPU_CONST uint kSdfEdgeCA = 5u;
GPU_CONST uint kSdfFace = 6u;

// One triangle with the pseudonormals of its features (std430; w unused). A degenerate
// triangle's face normal is zero.
struct SdfTriangle {
    vec4 a, b, c;
    vec4 face;
    vec4 edgeAB, edgeBC, edgeCA;
    vec4 vertexA, vertexB, vertexC;
};

// The closest point of triangle abc to p (xyz) and the feature holding it (w, one of kSdf*).
GPU_FN vec4 sdfClosestOnTriangle(vec3 p, vec3 a, vec3 b, vec3 c)
{
    vec3 ab = b - a;
    vec3 ac = c - a;
    vec3 ap = p - a;
    float d1 = dot(ab, ap);
    float d2 = dot(ac, ap);
    if (d1 <= 0.0f && d2 <= 0.0f)
        return vec4(a, float(kSdfVertexA));
    vec3 bp = p - b;
    float d3 = dot(ab, bp);
    float d4 = dot(ac, bp);
    if (d3 >= 0.0f && d4 <= d3)
        return vec4(b, float(kSdfVertexB));
    float vc = d1 * d4 - d3 * d2;
    if (vc <= 0.0f && d1 >= 0.0f && d3 <= 0.0f)
        return vec4(a + ab * (d1 / (d1 - d3)), float(kSdfEdgeAB));
    vec3 cp = p - c;
    float d5 = dot(ab, cp);
    float d6 = dot(ac, cp);
    if (d6 >= 0.0f && d5 <= d6)
        return vec4(c, float(kSdfVertexC));
    float vb = d5 * d2 - d1 * d6;
    if (vb <= 0.0f && d2 >= 0.0f && d6 <= 0.0f)
        return vec4(a + ac * (d2 / (d2 - d6)), float(kSdfEdgeCA));
    float va = d3 * d6 - d5 * d4;
    if (va <= 0.0f && (d4 - d3) >= 0.0f && (d5 - d6) >= 0.0f)
        return vec4(b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6))), float(kSdfEdgeBC));
    float denom = va + vb + vc;
    if (!(abs(denom) > 0.0f))
        return vec4(a, float(kSdfVertexA)); // a degenerate triangle: its first corner
    float v = vb / denom;
    float w = vc / denom;
    return vec4(a + ab * v + ac * w, float(kSdfFace));
}

// The pseudonormal of the feature `region` of `t` (not normalized: only its direction counts).
GPU_FN vec3 sdfPseudonormal(SdfTriangle t, uint region)
{
    if (region == kSdfVertexA)
        return vec3(t.vertexA);
    if (region == kSdfVertexB)
        return vec3(t.vertexB);
    if (region == kSdfVertexC)
        return vec3(t.vertexC);
    if (region == kSdfEdgeAB)
        return vec3(t.edgeAB);
    if (region == kSdfEdgeBC)
        return vec3(t.edgeBC);
    if (region == kSdfEdgeCA)
        return vec3(t.edgeCA);
    // A degenerate triangle has no face normal of its own: its edges' neighbours tell.
    vec3 face = vec3(t.face);
    return dot(face, face) > 0.0f ? face : vec3(t.edgeAB) + vec3(t.edgeBC) + vec3(t.edgeCA);
}

// The signed distance of p to triangle t alone when t holds p's closest point on the mesh: its
// magnitude the distance, its sign the side of the closest feature's pseudonormal (on the surface:
// 0; a point exactly in the feature's tangent plane off it counts as outside).
GPU_FN float sdfSignedDistance(vec3 p, SdfTriangle t)
{
    vec4 closest = sdfClosestOnTriangle(p, vec3(t.a), vec3(t.b), vec3(t.c));
    vec3 d = p - vec3(closest);
    float distance = length(d);
    return dot(d, sdfPseudonormal(t, uint(closest.w))) < 0.0f ? -distance : distance;
}

// ---- The field on a grid ------------------------------------------------------------------------

#define SDF_GROUP_SIZE 64
GPU_CONST uint kSdfGroupSize = SDF_GROUP_SIZE;
GPU_CONST uint kSdfBindingTriangles = 0; // SdfTriangle[]
GPU_CONST uint kSdfBindingItems = 1;     // uvec4[]: triangle, x0 | x1 << 16, y0 | y1 << 16, z0 | z1 << 16
GPU_CONST uint kSdfBindingKeys = 2;      // uint[] per node: kSdfNoKey, or quantized distance | triangle
GPU_CONST uint kSdfBindingField = 3;     // float[] per node: the signed distance, head units
GPU_CONST uint kSdfNoKey = 0xffffffffu;
GPU_CONST uint kSdfMaxItemNodes = 4096; // nodes of one work item's box (lavapipe ends long loops early)
GPU_CONST uint kSdfBandCells = 3;       // the band's half-width, cells

// The grid (the kernels' push constants, the solver's view of the field). Node (i, j, k) lies at
// origin + cell * (i, j, k); node index i + dims.x * (j + dims.y * k).
struct SdfGrid {
    vec4 origin;  // xyz the first node, w the cell's size
    uvec4 dims;   // xyz nodes along each axis, w the bits of a key holding the triangle (1 .. 24)
    vec4 band;    // x the band's half-width (head units), yzw unused
    uvec4 counts; // x work items, yzw unused
};

GPU_FN uint sdfNodeIndex(SdfGrid g, uvec3 n)
{
    return n.x + g.dims.x * (n.y + g.dims.y * n.z);
}

GPU_FN vec3 sdfNodePosition(SdfGrid g, uvec3 n)
{
    return vec3(g.origin) + g.origin.w * vec3(n);
}

// The key of `triangle` at distance d (< band) from a node: ordered by distance, then triangle.
GPU_FN uint sdfKey(SdfGrid g, float d, uint triangle)
{
    uint levels = (1u << (32u - g.dims.w)) - 1u; // the distance's quanta (the top one is kSdfNoKey's)
    uint q = uint(min(d / g.band.x, 1.0f) * float(levels - 1u));
    return (q << g.dims.w) | triangle;
}

GPU_FN uint sdfKeyTriangle(SdfGrid g, uint key)
{
    return key & ((1u << g.dims.w) - 1u);
}

// What a node of a work item offers: its key, or kSdfNoKey when the triangle lies farther than the band.
GPU_FN uint sdfSplatKey(SdfGrid g, SdfTriangle t, uint triangle, uvec3 node)
{
    vec3 p = sdfNodePosition(g, node);
    vec3 q = vec3(sdfClosestOnTriangle(p, vec3(t.a), vec3(t.b), vec3(t.c)));
    float d = length(p - q);
    return d < g.band.x ? sdfKey(g, d, triangle) : kSdfNoKey;
}

// A work item's box of nodes, from its packed bounds (inclusive).
GPU_FN uvec3 sdfItemLow(uvec4 item)
{
    return uvec3(item.y & 0xffffu, item.z & 0xffffu, item.w & 0xffffu);
}
GPU_FN uvec3 sdfItemHigh(uvec4 item)
{
    return uvec3(item.y >> 16u, item.z >> 16u, item.w >> 16u);
}

// The field at a node holding a key: its triangle's exact signed distance, within the band.
GPU_FN float sdfBandValue(SdfGrid g, SdfTriangle t, uvec3 node)
{
    float d = sdfSignedDistance(sdfNodePosition(g, node), t);
    return clamp(d, -g.band.x, g.band.x);
}

// The trilinear weights' cell: the node below p (clamped into the grid) and p's fraction across it.
// Outside the grid: false (the field says nothing there).
GPU_FN bool sdfCell(SdfGrid g, vec3 p, GPU_INOUT(uvec3) base, GPU_INOUT(vec3) frac)
{
    vec3 x = (p - vec3(g.origin)) / g.origin.w;
    vec3 top = vec3(float(g.dims.x), float(g.dims.y), float(g.dims.z)) - vec3(1.0f);
    if (x.x < 0.0f || x.y < 0.0f || x.z < 0.0f || x.x > top.x || x.y > top.y || x.z > top.z)
        return false;
    vec3 f = min(floor(x), top - vec3(1.0f));
    base = uvec3(f);
    frac = x - f;
    return true;
}

GPU_NAMESPACE_END

#ifdef __cplusplus
static_assert(sizeof(gpu::SdfTriangle) == 160);
static_assert(sizeof(gpu::SdfGrid) == 64);
#endif

#endif
