#version 460
// grid_splat.comp: each vertex adds its trilinear weights (density) and weighted velocity
// (momentum) to the 8 nodes around it with float atomic adds (Petrovic et al. 2005). Vertices
// whose cell leaves the grid contribute nothing (and take no friction in grid_gather).
#extension GL_EXT_shader_atomic_float : require
#extension GL_GOOGLE_include_directive : require
#include "sim_common.glsl"

layout(local_size_x = SIM_GROUP_SIZE) in;
layout(set = 0, binding = kSimBindingGrid, std430) buffer Grid { GridNode grid[]; };

void main()
{
    uint g = gl_GlobalInvocationID.x;
    if (g >= params.strandCount * params.verticesPerStrand)
        return;
    GridCell cell = gridCell(positions[g].xyz, step.gridOrigin, params.gridCellSize);
    if (!cellInside(cell.base, params.gridResolution))
        return;
    vec3 v = velocities[g].xyz;
    for (uint k = 0u; k < 8u; ++k) {
        float w = cornerWeight(cell.frac, k);
        uint n = gridIndex(cell.base + cornerOffset(k), params.gridResolution);
        atomicAdd(grid[n].density, w);
        atomicAdd(grid[n].momentum.x, w * v.x);
        atomicAdd(grid[n].momentum.y, w * v.y);
        atomicAdd(grid[n].momentum.z, w * v.z);
    }
}
