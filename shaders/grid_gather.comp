#version 460
// grid_gather.comp: each free vertex reads the trilinear grid velocity around it and blends
// v <- (1 - friction) v + friction v_grid (Petrovic et al. 2005); optionally a repulsion along
// -grad(density) keeps volume (shared/sim_grid.h, as the CPU twin). Pinned vertices keep the
// head's velocity.
#extension GL_GOOGLE_include_directive : require
#include "sim_common.glsl"

// The normalized grid as sim_grid.h reaches it: the one bound buffer, a node's density in w.
#define GridRef uint
float gridNodeDensity(uint grid, ivec3 node)
{
    return gridVelocity[gridIndex(node, params.gridResolution)].w;
}

#include "shared/sim_grid.h"

layout(local_size_x = SIM_GROUP_SIZE) in;

void main()
{
    uint g = gl_GlobalInvocationID.x;
    if (g >= paddedStrandCount(params.strandCount) * params.verticesPerStrand ||
        strandOfSlot(g, params.verticesPerStrand) >= params.strandCount)
        return;  // past the end, or a padding slot of the last strand block
    if (positions[g].w == 0.0)
        return;  // pinned
    GridCell cell = gridCell(positions[g].xyz, step.gridOrigin, params.gridCellSize);
    if (!cellInside(cell.base, params.gridResolution))
        return;
    GridSample gs = gridSampleZero();
    for (uint k = 0u; k < 8u; ++k) {
        vec4 node = gridVelocity[gridIndex(cell.base + cornerOffset(k), params.gridResolution)];
        gs = gridAccumulate(gs, cell.frac, k, node.xyz, node.w);
    }
    velocities[g].xyz = gridGatherVelocity(0u, cell, positions[g].xyz, velocities[g].xyz, gs);
}
