#version 460
// background.frag: the backdrop behind the graphics meshes, a full-screen triangle drawn first in
// their pass: frameBackground (shared/frame_params.h) at the pixel's centre, the same colour
// mesh_shade.comp gives the samples no mesh covers. Linear RGB; the sRGB target encodes it.
#extension GL_GOOGLE_include_directive : require
#include "shared/frame_params.h"

layout(set = 0, binding = kFrameParamsBinding) uniform FrameBlock { FrameParams frame; };
layout(location = 0) out vec4 outColor;

void main()
{
    outColor = vec4(frameBackground(frame, gl_FragCoord.y), 1.0);
}
