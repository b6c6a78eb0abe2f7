#version 460
// strands_generate.comp: the compute path's strands, one thread per strand vertex (D + 1 per
// strand, strands of a guide side by side, so neighbouring threads read the same guide). Each
// point is placed as the tessellation path places it (shared/strands.h placeStrandPoint: the
// guide's C1 Bezier, as strands_curves.comp evaluated it, between its samples where the strand is
// shorter than its guide (strandLengthFraction, curveBetweenSamples), single or multi interpolation,
// deviations, then out of the colliders), projected, and for the camera shaded there
// (shared/strand_shading.h, with the light's visibility read from its maps as hair.tese reads it).
// With STRANDS_FROM_LIGHT (strands_generate_light.comp) the points are projected into the light's
// maps, unshaded.
#extension GL_GOOGLE_include_directive : require
#include "shared/frame_params.h"
#include "shared/strand_raster.h"
#include "shared/strand_shading.h"
#include "shared/strands.h"

layout(local_size_x = 64) in;  // kRasterGroupSize
layout(push_constant) uniform PushBlock { StrandRasterPush push; };
layout(set = 0, binding = kRasterBindingFrame) uniform FrameBlock { FrameParams frame; };
layout(set = 0, binding = kRasterBindingSim) uniform SimBlock { SimParams sim; };
layout(set = 0, binding = kRasterBindingCurves, std430) readonly buffer Curves { vec4 curves[]; };
layout(set = 0, binding = kRasterBindingTriangles, std430) readonly buffer Triangles { uvec4 triangles[]; };
layout(set = 0, binding = kRasterBindingVertices, std430) writeonly buffer Vertices { vec4 vertices[]; };
layout(set = 0, binding = kRasterBindingColors, std430) writeonly buffer Colors { uint colors[]; };
#ifndef STRANDS_FROM_LIGHT
layout(set = 0, binding = kRasterBindingLut) uniform sampler2DArray hairLut;
#include "light_visibility.glsl"
#endif

// The guide's curve at its point i (t = i / D), as strands.curves evaluated it.
CurvePoint guideCurve(uint guide, uint i)
{
    uint at = 2u * (guide * (push.divisions + 1u) + i);
    return CurvePoint(curves[at].xyz, curves[at + 1u].xyz);
}

// The guide's curve at x / D (x in [0, D]), between the two points around it (curveBetweenSamples).
CurvePoint guideCurveAt(uint guide, float x)
{
    uint k = curveSampleBelow(x, push.divisions);
    return curveBetweenSamples(guideCurve(guide, k), guideCurve(guide, k + 1u), x - float(k),
                               float(push.verticesPerStrand - 1u) / float(push.divisions));
}

void main()
{
    uint id = linearInvocation(gl_GlobalInvocationID, gl_NumWorkGroups.x * gl_WorkGroupSize.x);
    uint perStrand = push.divisions + 1u;
    if (id >= push.guideCount * push.drawnPerGuide * perStrand)
        return;
    uint drawn = id / perStrand;
    uint i = id % perStrand;
    uint guide = drawn / push.drawnPerGuide;
    uint s = drawn % push.drawnPerGuide;
    float t = float(i) / float(push.divisions);
    // The strand's own length (strandLengthFraction): its point i lies at x / D along its guide.
    float fraction = strandLengthFraction(guide, s, frame.strandLengthJitter);
    float x = float(i) * fraction;

    CurvePoint g = guideCurveAt(guide, x);
    CurvePoint g1 = g, g2 = g;
    uvec4 tri = triangles[guide];
    if (strandIsMulti(push.interpolation, s)) {
        g1 = guideCurveAt(tri.y, x);
        g2 = guideCurveAt(tri.z, x);
    }
    CurvePoint point = placeStrandPoint(g, g1, g2, guide, s, strandGuideParameter(t, fraction), push.interpolation,
                                        push.clumpRadius, push.deviation, guideLength(tri.w), push.coilRadius,
                                        push.coilFrequency, push.divisions);
    vec3 p = point.position;
    if (s != 0u)
        for (uint c = 0u; c < sim.colliderCount; ++c)
            p = pushOutOfCollider(sim.colliders[c], frame.headTransform, p);

    uint strand = guide * push.strandsPerGuide + s;
    float alpha = frame.hairOpacity * lodAlpha(s, push.lodStrands);
    float worldWidth = strandWidthAt(push.width * guideWidthScale(tri.w), t);
#ifdef STRANDS_FROM_LIGHT
    vertices[id] = projectStrandVertex(frame.lightViewProjection, vec2(frame.shadowMapSize), p, worldWidth,
                                       frame.lightTexelsPerUnit);
    colors[id] = packFragmentColor(vec3(0.0), alpha);
#else
    vec2 size = vec2(frame.viewportWidth, frame.viewportHeight);
    float pixelsPerUnit = abs(frame.projection[1][1]) * 0.5 * size.y;  // at w = 1
    vertices[id] = projectStrandVertex(frame.viewProjection, size, p, worldWidth, pixelsPerUnit);
    // As hair.tese: about a strand's depth of bias for the hair's own depth map, the PCF disk
    // turned per strand.
    vec2 noise = vec2(float(strand % 251u), float(strand / 251u % 241u)) + 17.0 * t;
    vec2 visibility = lightVisibilityParts(p, noise, 4.0 * frame.shadowBias, false);
    vec3 lut[kFrameLights];
    strandLutSingles(frame, hairLut, point.tangent, normalize(frame.cameraPosition - p), lut);
    colors[id] = packFragmentColor(shadeStrandPoint(frame, p, point.tangent, t, strand, visibility, lut), alpha);
#endif
}
