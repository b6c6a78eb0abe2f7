#version 460
// grid_gather.comp: each free vertex reads the grid velocity around it (each of its cell's corners
// momentum / density, where the node holds enough hair), trilinearly, and blends
// v <- (1 - friction) v + friction v_grid (Petrovic et al. 2005); optionally a repulsion along
// -grad(density) keeps volume (shared/sim_grid.h, as the CPU twin). Pinned vertices keep the
// head's velocity. The same threads zero the next step's accumulators, one node each: the step
// needs two dispatches (sim_integrate, this), where a clear and a normalize pass made it four.
#extension GL_GOOGLE_include_directive : require
#ifdef GRID_FIXED
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
#extension GL_EXT_shader_atomic_int64 : require
#else
#extension GL_EXT_shader_atomic_float : require
#endif
#include "sim_common.glsl"
#include "grid_storage.glsl"

// The grid as sim_grid.h reaches it: this step's accumulators, a node's density their first sum.
#define GridRef uint
float gridNodeDensity(uint grid, ivec3 node)
{
    return gridRead(gridIndex(node, params.gridResolution)).density;
}

#include "shared/sim_grid.h"

layout(local_size_x = SIM_GROUP_SIZE) in;

void gatherVertex(uint g)
{
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
        vec4 node = gridNodeVelocity(gridIndex(cell.base + cornerOffset(k), params.gridResolution));
        gs = gridAccumulate(gs, cell.frac, k, node.xyz, node.w);
    }
    velocities[g].xyz = gridGatherVelocity(0u, cell, positions[g].xyz, velocities[g].xyz, gs);
}

void main()
{
    uint g = gl_GlobalInvocationID.x;
    if (g < params.gridNodeCount)
        gridZeroNext(g);
    gatherVertex(g);
}
