#version 460
// strands_reserve.comp (strands.reserve): after the frame's resolve, one thread per pixel (and one
// for the entry past the last): the next frame's reserved layout from this frame's exact offsets
// (shared/strand_raster.h "One walk", rasterReservedSlot), which strands.count writes into.
#extension GL_GOOGLE_include_directive : require
#include "shared/strand_raster.h"

layout(local_size_x = 64) in;  // kRasterGroupSize
layout(push_constant) uniform PushBlock { StrandRasterPush push; };
layout(set = 0, binding = kRasterBindingOffsets, std430) readonly buffer Offsets { uint offsets[]; };
layout(set = 0, binding = kRasterBindingReserved, std430) writeonly buffer Reserved { uint reserved[]; };

void main()
{
    uint p = linearInvocation(gl_GlobalInvocationID, gl_NumWorkGroups.x * gl_WorkGroupSize.x);
    if (p <= push.targetWidth * push.targetHeight)
        reserved[p] = rasterReservedSlot(offsets[p], p);
}
