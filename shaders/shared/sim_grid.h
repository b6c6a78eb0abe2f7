// shaders/shared/sim_grid.h: what the hair-hair grid does to one free vertex after a step, compiled
// as GLSL by shaders/grid_gather.comp and as C++ by the CPU twin (physics/cpu_solver.cpp
// gridGather): friction toward the grid's velocity, then repulsion down the density gradient with
// no part toward a collider the vertex lies within a cell of (sim.h gridFriction,
// gridRepulsionChange, withoutPartInto). Each caller keeps its addressing: it defines, before
// including this, a type GridRef naming the normalized grid and gridNodeDensity(grid, node), the
// density of a node; it samples the 8 corners of the vertex's cell into a
// GridSample and writes the velocity gridGatherVelocity returns.
#ifndef WISP_SHARED_SIM_GRID_H
#define WISP_SHARED_SIM_GRID_H
#include "sim.h"

GPU_NAMESPACE_BEGIN

// d(density)/d(cell coordinates) at a point of `cell` in a grid of n nodes per axis: central
// differences at the cell's 8 corner nodes (one-sided at the grid's faces), interpolated
// trilinearly. A continuous field, so hair moved down it comes to rest where it vanishes; the
// trilinear interpolant's own derivative jumps at every cell face, and would push hair in a valley
// of the density across the face and back every step.
GPU_FN vec3 gridDensityGradient(GridRef grid, GridCell cell, uint n)
{
    vec3 gradient = vec3(0.0f);
    int last = int(n) - 1;
    for (uint k = 0u; k < 8u; ++k) {
        ivec3 node = cell.base + cornerOffset(k);
        float w = cornerWeight(cell.frac, k);
        for (int axis = 0; axis < 3; ++axis) {
            ivec3 lo = node, hi = node;
            lo[axis] = max(node[axis] - 1, 0);
            hi[axis] = min(node[axis] + 1, last);
            gradient[axis] += w * (gridNodeDensity(grid, hi) - gridNodeDensity(grid, lo)) / float(hi[axis] - lo[axis]);
        }
    }
    return gradient;
}

// The velocity of a free vertex at world position p in `cell`, with velocity v, once the grid has
// acted on it (`s`: its cell's corners sampled).
GPU_FN vec3 gridGatherVelocity(SIM_CONTEXT GridRef grid, GridCell cell, vec3 p, vec3 v, GridSample s)
{
    v = gridFriction(v, s, params.gridFriction);
    if (params.gridRepulsion <= 0.0f)
        return v;
    vec3 gradient = gridDensityGradient(grid, cell, params.gridResolution);
    vec3 dv =
        gridRepulsionChange(v, gradient, params.gridRepulsion, params.gridSeparationSpeed, params.gridRestDensity);
    float reach = params.gridCellSize; // the gradient's own scale: a cell
    for (uint c = 0u; c < params.colliderCount; ++c)
        dv = withoutPartInto(dv, headColliderContact(params.colliders[c], step.headTransform, p, reach));
    if (step.sphereRadius > 0.0f)
        dv = withoutPartInto(dv, sphereContact(step.sphereCenter, step.sphereRadius, p, reach));
    return v + dv;
}

GPU_NAMESPACE_END

#endif
