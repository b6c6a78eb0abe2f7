#version 460
// hair_opacity.frag: the deep opacity pass (Yuksel & Keyser 2008). Each hair fragment seen from
// the light adds its opacity (strand opacity x ribbon coverage) to the layer its depth falls in,
// counted from the texel's first hair depth (the shadow pass's hair map); additive blending sums
// them into the RGBA layers.
#extension GL_GOOGLE_include_directive : require
#include "shared/frame_params.h"
#include "shared/shadows.h"
#include "shared/strands.h"

layout(set = 0, binding = kHairBindingFrame) uniform FrameBlock { FrameParams frame; };
layout(set = 0, binding = kBindingHairDepth) uniform sampler2D hairDepth;

layout(location = 4) in float inAlpha;
layout(location = 0) out vec4 outOpacity;

void main()
{
    float z0 = texelFetch(hairDepth, ivec2(gl_FragCoord.xy), 0).r;
    uint layers = clamp(frame.domLayers, 1u, kMaxDomLayers);
    outOpacity = frame.hairOpacity * inAlpha * domLayerMask(gl_FragCoord.z, z0, frame.domSpacing, layers);
}
