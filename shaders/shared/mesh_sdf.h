// shaders/shared/mesh_sdf.h: the signed distance to a triangle mesh, compiled as GLSL and as C++.
// The distance is the closest point's (Ericson, Real-Time Collision Detection, 5.1.5, with the
// feature it lies on); the sign is that of (p - closest) against the angle-weighted pseudonormal
// of that feature (Baerentzen & Aanaes 2005, "Signed distance computation using the angle weighted
// pseudonormal"): the face's normal inside a face, the sum of its faces' normals on an edge, the
// normals of the faces around a vertex weighted by their angles there at a vertex. Negative inside.
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

GPU_NAMESPACE_END

#ifdef __cplusplus
static_assert(sizeof(gpu::SdfTriangle) == 160);
#endif

#endif
