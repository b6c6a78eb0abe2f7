#version 460
// hair.tese: a point of one strand. The guide's C1 Bezier (shared/strands.h) is evaluated at the
// strand's parameter t (along the first strandLengthFraction of it: each strand its own length); a single-strand strand is offset in the guide's clump disc, a
// multi-strand one blends three guides with barycentric weights (Nalu); random deviations come
// last, and every generated strand is then pushed out of the head's colliders.
#extension GL_GOOGLE_include_directive : require
#include "shared/frame_params.h"
#include "shared/strands.h"

layout(isolines, equal_spacing) in;
layout(push_constant) uniform PushBlock { HairPush push; };
layout(set = 0, binding = kHairBindingFrame) uniform FrameBlock { FrameParams frame; };
layout(set = 0, binding = kHairBindingSim) uniform SimBlock { SimParams sim; };
layout(set = 0, binding = kHairBindingPositions, std430) readonly buffer Positions { vec4 positions[]; };
layout(set = 0, binding = kHairBindingTriangles, std430) readonly buffer Triangles { uvec4 triangles[]; };

layout(location = 0) patch in uint patchGuide;
layout(location = 1) patch in uint patchStrandBase;
layout(location = 2) patch in uint patchLines;
layout(location = 3) patch in uint patchDivisionBase;
layout(location = 4) patch in uint patchDivisions;

layout(location = 0) out vec3 outWorld;
layout(location = 1) out vec3 outTangent;
layout(location = 2) out float outT;
layout(location = 3) flat out uint outStrand;  // guide * strandsPerGuide + s
layout(location = 4) out float outLodAlpha;
layout(location = 5) out vec2 outVisibility;  // the light's visibility here (light_visibility.glsl)
layout(location = 6) out float outWidthScale;  // the guide's (guideWidthScale): finer at the hairline

#ifndef HAIR_FROM_LIGHT
// The light's visibility is evaluated per tessellated vertex and interpolated along the ribbon:
// shadows vary slowly along a strand, and there are about ten times fewer vertices than fragments.
#include "light_visibility.glsl"
#endif

vec3 guidePoint(uint guide, uint i)
{
    return positions[vertexSlot(guide, i, push.verticesPerStrand)].xyz;
}

// The guide's curve at t: position and (unnormalized) tangent.
CurvePoint evaluateGuide(uint guide, float t)
{
    uint V = push.verticesPerStrand;
    uint seg = curveSegment(t, V);
    return guideCurvePoint(guidePoint(guide, seg == 0u ? 0u : seg - 1u), guidePoint(guide, seg),
                           guidePoint(guide, seg + 1u), guidePoint(guide, min(seg + 2u, V - 1u)),
                           curveLocal(t, V, seg));
}

void main()
{
    uint s = patchStrandBase + uint(round(gl_TessCoord.y * float(patchLines)));
    float t = (float(patchDivisionBase) + gl_TessCoord.x * float(patchDivisions)) / float(push.divisions);
    uint guide = patchGuide;
    // The strand's own length (strandLengthFraction): its point t lies at tg along its guide.
    float tg = strandGuideParameter(t, strandLengthFraction(guide, s, frame.strandLengthJitter));

    CurvePoint g = evaluateGuide(guide, tg);
    CurvePoint g1 = g, g2 = g;
    uvec4 tri = triangles[guide];
    if (strandIsMulti(push.interpolation, s)) {
        g1 = evaluateGuide(tri.y, tg);
        g2 = evaluateGuide(tri.z, tg);
    }
    CurvePoint point = placeStrandPoint(g, g1, g2, guide, s, tg, push.interpolation, push.clumpRadius, push.deviation,
                                          guideLength(tri.w), push.coilRadius, push.coilFrequency, push.divisions);
    vec3 p = point.position;
    // Every generated strand is kept out of the head's colliders: blends of two outside points,
    // and offsets across a guide lying on the scalp, would otherwise fall inside the head.
    if (s != 0u)
        for (uint c = 0u; c < sim.colliderCount; ++c)
            p = pushOutOfCollider(sim.colliders[c], frame.headTransform, p);

    outWorld = p;
    outTangent = point.tangent;
    outT = t;
    outStrand = guide * push.strandsPerGuide + s;
    outLodAlpha = lodAlpha(s, push.lodStrands);
    outWidthScale = guideWidthScale(tri.w);
#ifdef HAIR_FROM_LIGHT
    gl_Position = frame.lightViewProjection * vec4(p, 1.0);  // shadow and deep opacity passes
    outVisibility = vec2(1.0);
#else
    gl_Position = frame.viewProjection * vec4(p, 1.0);
    // Hair receiving the hair's own depth map (deep opacity off) needs about a strand's depth of
    // bias; the PCF disk turns per strand instead of per pixel.
    vec2 noise = vec2(float(outStrand % 251u), float(outStrand / 251u % 241u)) + 17.0 * t;
    outVisibility = lightVisibilityParts(p, noise, 4.0 * frame.shadowBias, false);
#endif
}
