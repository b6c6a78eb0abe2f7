#version 460
// grid_normalize.comp: node velocity = momentum / density where the node holds enough hair;
// w keeps the density for the gather's repulsion term.
#extension GL_GOOGLE_include_directive : require
#include "sim_common.glsl"

layout(local_size_x = SIM_GROUP_SIZE) in;
layout(set = 0, binding = kSimBindingGrid, std430) readonly buffer Grid { GridNode grid[]; };

void main()
{
    uint n = gl_GlobalInvocationID.x;
    if (n >= params.gridNodeCount)
        return;
    GridNode node = grid[n];
    vec3 velocity = node.density > kGridMinDensity ? node.momentum / node.density : vec3(0.0);
    gridVelocity[n] = vec4(velocity, node.density);
}
