#version 460
// grid_clear.comp: zeroes the hair-hair grid's accumulators, one node per thread. A separate
// dispatch: a workgroup barrier() cannot order the clear before other workgroups' splats.
#extension GL_GOOGLE_include_directive : require
#include "sim_common.glsl"

layout(local_size_x = SIM_GROUP_SIZE) in;
layout(set = 0, binding = kSimBindingGrid, std430) writeonly buffer Grid { GridNode grid[]; };

void main()
{
    uint n = gl_GlobalInvocationID.x;
    if (n >= params.gridNodeCount)
        return;
    grid[n].momentum = vec3(0.0);
    grid[n].density = 0.0;
}
