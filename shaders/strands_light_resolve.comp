#version 460
// strands_light_resolve.comp: the deep opacity layers summed in fixed point by strands_light.comp
// into the RGBA16F image every shader samples (shared/shadows.h), one thread per texel. (The
// hair's first depth goes to its depth image by a buffer-to-image copy.)
#extension GL_GOOGLE_include_directive : require
#include "shared/strand_raster.h"

layout(local_size_x = 8, local_size_y = 8) in;
layout(push_constant) uniform PushBlock { StrandRasterPush push; };
layout(set = 0, binding = kRasterBindingLightOpacity, std430) readonly buffer LightOpacity { uvec4 lightOpacity[]; };
layout(set = 0, binding = kRasterBindingOpacityImage, rgba16f) uniform writeonly image2D opacityImage;

void main()
{
    uvec2 xy = gl_GlobalInvocationID.xy;
    if (xy.x >= push.targetWidth || xy.y >= push.targetHeight)
        return;
    vec4 opacity = vec4(lightOpacity[xy.y * push.targetWidth + xy.x]) / kOpacityFixedScale;
    imageStore(opacityImage, ivec2(xy), opacity);
}
