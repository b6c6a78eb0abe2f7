#version 460
// strands_curves.comp: one thread per guide point at the strands' parameters t = i / D (D + 1 a
// guide): the guide's C1 curve there (shared/strands.h guideCurvePoint over the solver's
// positions), as hair.tese evaluates it. strands.generate (for the camera and the light) reads
// the D + 1 points of a strand's guide, and of its neighbours for multi strands, instead of
// evaluating the curve again for every strand.
#extension GL_GOOGLE_include_directive : require
#include "shared/strand_raster.h"
#include "shared/strands.h"

layout(local_size_x = 64) in;  // kRasterGroupSize
layout(push_constant) uniform PushBlock { StrandRasterPush push; };
layout(set = 0, binding = kRasterBindingPositions, std430) readonly buffer Positions { vec4 positions[]; };
layout(set = 0, binding = kRasterBindingCurves, std430) writeonly buffer Curves { vec4 curves[]; };

vec3 guidePoint(uint guide, uint i)
{
    return positions[vertexSlot(guide, i, push.verticesPerStrand)].xyz;
}

void main()
{
    uint id = linearInvocation(gl_GlobalInvocationID, gl_NumWorkGroups.x * gl_WorkGroupSize.x);
    uint perGuide = push.divisions + 1u;
    if (id >= push.guideCount * perGuide)
        return;
    uint guide = id / perGuide;
    float t = float(id % perGuide) / float(push.divisions);
    uint V = push.verticesPerStrand;
    uint seg = curveSegment(t, V);
    CurvePoint c = guideCurvePoint(guidePoint(guide, seg == 0u ? 0u : seg - 1u), guidePoint(guide, seg),
                                   guidePoint(guide, seg + 1u), guidePoint(guide, min(seg + 2u, V - 1u)),
                                   curveLocal(t, V, seg));
    curves[2u * id] = vec4(c.position, 0.0);
    curves[2u * id + 1u] = vec4(c.tangent, 0.0);
}
