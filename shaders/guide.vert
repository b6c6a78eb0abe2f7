#version 460
// guide.vert: a guide vertex from the physics buffer, coloured by its place along the strand.
#extension GL_GOOGLE_include_directive : require
#include "shared/frame_params.h"
#include "shared/guide_params.h"
#include "shared/sim.h"

layout(location = kGuideLocationPosition) in vec4 inPosition;
layout(set = 0, binding = kFrameParamsBinding) uniform FrameBlock { FrameParams frame; };
layout(push_constant) uniform PushBlock { GuidePush push; };
layout(location = 0) out vec3 outColor;

void main()
{
    float along = float(vertexOfSlot(uint(gl_VertexIndex), push.verticesPerStrand)) / float(push.verticesPerStrand - 1u);
    outColor = mix(push.rootColor, push.tipColor, along);
    gl_Position = frame.viewProjection * vec4(inPosition.xyz, 1.0);
}
