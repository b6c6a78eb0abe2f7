#version 460
// strands_light_resolve.comp: the deep opacity layers summed in fixed point by strands_light.comp
// into the RGBA16F image every shader samples (shared/shadows.h), and the hair's first depth into
// the R32F image the deep opacity lookups sample, one thread per texel. (The depth image the PCF
// of the hair's shadow compares against, without opacity layers, gets it by a buffer-to-image
// copy: light.copy.)
#extension GL_GOOGLE_include_directive : require
#include "shared/strand_raster.h"

layout(local_size_x = 8, local_size_y = 8) in;
layout(push_constant) uniform PushBlock { StrandRasterPush push; };
layout(set = 0, binding = kRasterBindingLightOpacity, std430) readonly buffer LightOpacity { uvec4 lightOpacity[]; };
layout(set = 0, binding = kRasterBindingOpacityImage, rgba16f) uniform writeonly image2D opacityImage;
layout(set = 0, binding = kRasterBindingLightDepth, std430) readonly buffer LightDepth { uint lightDepth[]; };
layout(set = 0, binding = kRasterBindingLightDepthImage, r32f) uniform writeonly image2D depthImage;

void main()
{
    uvec2 xy = gl_GlobalInvocationID.xy;
    if (xy.x >= push.targetWidth || xy.y >= push.targetHeight)
        return;
    uint t = xy.y * push.targetWidth + xy.x;
    imageStore(opacityImage, ivec2(xy), vec4(lightOpacity[t]) / kOpacityFixedScale);
    imageStore(depthImage, ivec2(xy), vec4(uintBitsToFloat(lightDepth[t]), 0.0, 0.0, 0.0));
}
