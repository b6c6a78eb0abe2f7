#version 460
// sim_integrate.comp: every substep of one step for one strand per thread, root to tip (a strand's
// substeps touch only its own vertices, so one dispatch runs them all: no barrier between them).
// The algorithm is the shared one (shaders/shared/sim_strand.h, which the CPU twin
// physics/cpu_solver.cpp calls too); this kernel keeps the GPU's addressing (strands interleaved in
// blocks of 32, gpu::vertexSlot), its writes, and the grid splat.
//
// The step's last substep also splats the hair-hair grid for its strand, into this step's
// accumulators (zeroed by the previous step's gather): consecutive vertices of a strand usually
// fall in the same grid cell, so their trilinear contributions are summed in registers and added
// with one set of atomics per run of vertices, instead of one per vertex (atomics on the same nodes
// were the step's bottleneck). A run that moves into a neighbouring cell keeps the corners both
// cells share and adds only the ones it leaves (slideRun): 4 nodes per cell crossed instead of 8.
// The sums are CpuSolver::gridSplat's, up to float order (a strand reset for non-finite values
// keeps the finite contributions it made before the reset; the CPU splats its rest pose). It also
// writes the tangents, which earlier substeps leave to it.
#extension GL_GOOGLE_include_directive : require
#ifdef GRID_FIXED
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
#extension GL_EXT_shader_atomic_int64 : require
#else
#extension GL_EXT_shader_atomic_float : require
#endif
#include "sim_common.glsl"
#include "grid_storage.glsl"

// The strand's vertices as sim_strand.h reaches them: a strand is its root's slot, vertex i is
// kSimStrandBlock slots further per vertex (gpu::vertexSlot).
#define StrandRef uint
vec3 strandPosition(uint base, uint i)
{
    return positions[base + i * kSimStrandBlock].xyz;
}
vec3 strandVelocity(uint base, uint i)
{
    return velocities[base + i * kSimStrandBlock].xyz;
}
void strandSetVertex(uint base, uint i, vec3 p, vec3 v)
{
    uint g = base + i * kSimStrandBlock;
    velocities[g].xyz = v;
    positions[g].xyz = p;
}
float strandRestLength(uint base, uint i)
{
    return rest[base + i * kSimStrandBlock].segmentLength;
}

// The head mesh's signed distance field as mesh_sdf_sample.h reaches it.
layout(set = 0, binding = kSimBindingSdf, std430) readonly buffer SdfField { float sdfField[]; };
float sdfFieldAt(uint node)
{
    return sdfField[node];
}

#include "shared/sim_strand.h"

layout(local_size_x = SIM_GROUP_SIZE) in;
// The run of vertices being summed: the cell they share and each corner's density and momentum.
ivec3 runCell = ivec3(-1);
bool runOpen = false;
float runDensity[8];
vec3 runMomentum[8];

// Adds corner k of the run to the grid and empties it.
void flushCorner(uint k)
{
    gridAdd(gridIndex(runCell + cornerOffset(k), params.gridResolution), runDensity[k], runMomentum[k]);
    runDensity[k] = 0.0;
    runMomentum[k] = vec3(0.0);
}

// Adds the whole run to the grid.
void flushRun()
{
    for (uint k = 0u; k < 8u; ++k)
        flushCorner(k);
    runOpen = false;
}

// Slides the run one cell along the axis whose corner bit is `bit` (1 x, 2 y, 4 z), by `dir`
// (+1 or -1): the four corners both cells share keep their sums, the four the run leaves behind
// go to the grid. A strand crossing into a neighbouring cell so adds 4 nodes instead of 8.
void slideRun(uint bit, int dir, ivec3 offset)
{
    for (uint low = 0u; low < 8u; ++low) {
        if ((low & bit) != 0u)
            continue;
        uint high = low | bit;
        if (dir > 0) {  // the low corners are left behind; the high ones become the new low ones
            flushCorner(low);
            runDensity[low] = runDensity[high];
            runMomentum[low] = runMomentum[high];
            runDensity[high] = 0.0;
            runMomentum[high] = vec3(0.0);
        } else {
            flushCorner(high);
            runDensity[high] = runDensity[low];
            runMomentum[high] = runMomentum[low];
            runDensity[low] = 0.0;
            runMomentum[low] = vec3(0.0);
        }
    }
    runCell += offset;
}

// Moves the lane's run to `cell`: slid along each axis when it is a neighbour (face, edge or
// corner), else flushed whole (the next vertex opens a new run).
void moveRun(ivec3 cell)
{
    ivec3 d = cell - runCell;
    if (any(greaterThan(abs(d), ivec3(1)))) {
        flushRun();
        return;
    }
    if (d.x != 0)
        slideRun(1u, d.x, ivec3(d.x, 0, 0));
    if (d.y != 0)
        slideRun(2u, d.y, ivec3(0, d.y, 0));
    if (d.z != 0)
        slideRun(4u, d.z, ivec3(0, 0, d.z));
}

// Adds a finished vertex (position p, velocity v) to the strand's run, sliding or flushing the
// run first when the vertex leaves its cell.
void splatVertex(vec3 p, vec3 v)
{
    if (!isFinite3(p) || !isFinite3(v))
        return;  // a strand about to be reset contributes nothing non-finite
    GridCell cell = gridCell(p, step.gridOrigin, params.gridCellSize);
    if (!cellInside(cell.base, params.gridResolution))
        return;
    if (runOpen && cell.base != runCell)
        moveRun(cell.base);
    v = clampSpeed(v, params.gridMaxSplatSpeed);
    if (!runOpen) {
        runCell = cell.base;
        runOpen = true;
        for (uint k = 0u; k < 8u; ++k) {
            runDensity[k] = 0.0;
            runMomentum[k] = vec3(0.0);
        }
    }
    for (uint k = 0u; k < 8u; ++k) {
        float w = cornerWeight(cell.frac, k);
        runDensity[k] += w;
        runMomentum[k] += w * v;
    }
}

// Substep k of strand s; the last one (splat) also splats the grid and writes the tangents.
void integrateStrand(uint s, uint k, bool splat)
{
    // The substep's start, rounded as the CPU twin's (no fused multiply-add).
    precise float time = step.time + float(k) * params.dt;
    uint V = params.verticesPerStrand;
    uint base = vertexSlot(s, 0u, V);  // vertex i is at base + i * kSimStrandBlock
    StrandInfo info = strands[s];
    StrandWalk walk = strandWalkBegin(info, positions[base].xyz, rest[base].position, time);
    // A strand pinned at both ends is finished after its bend: its splat and tangents wait for it.
    bool bothEnds = pinnedAtBothEnds(info, V);
    bool splatNow = splat && !bothEnds;
    for (uint i = 1u; i < V; ++i) {
        uint g = base + i * kSimStrandBlock;
        uint parent = g - kSimStrandBlock;
        WalkedVertex done = strandWalkStep(walk, i, V, positions[g].xyz, velocities[g].xyz, rest[g], rest[parent].position);
        positions[parent].xyz = done.position;
        velocities[parent].xyz = done.velocity;
        if (splatNow) {
            splatVertex(done.position, done.velocity);
            tangents[parent] = vec4(done.tangent, 0.0);
        }
    }
    uint last = base + (V - 1u) * kSimStrandBlock;
    WalkedVertex tip = strandWalkTip(walk);
    positions[last].xyz = tip.position;
    velocities[last].xyz = tip.velocity;
    if (splatNow) {
        tangents[last] = vec4(tip.tangent, 0.0);
        splatVertex(tip.position, tip.velocity);
        if (runOpen)
            flushRun();
    }

    if (bothEnds) {
        strandBend(base, info, V, walk.finite);
        if (splat) {
            for (uint i = 0u; i < V; ++i) {
                uint g = base + i * kSimStrandBlock;
                uint j = min(i + 1u, V - 1u);
                vec3 along = positions[base + j * kSimStrandBlock].xyz - positions[base + (j - 1u) * kSimStrandBlock].xyz;
                tangents[g] = vec4(normalize(along), 0.0);
                splatVertex(positions[g].xyz, velocities[g].xyz);
            }
            if (runOpen)
                flushRun();
        }
    }

    if (!walk.finite) {
        for (uint i = 0u; i < V; ++i) {
            uint g = base + i * kSimStrandBlock;
            uint j = base + min(i + 1u, V - 1u) * kSimStrandBlock;  // the segment ending at vertex j
            WalkedVertex r = restVertex(rest[g].position, rest[j - kSimStrandBlock].position, rest[j].position);
            positions[g].xyz = r.position;
            velocities[g].xyz = r.velocity;
            tangents[g] = vec4(r.tangent, 0.0);
        }
        atomicAdd(counters.nonfiniteResets, 1u);
    }
}

void main()
{
    uint s = gl_GlobalInvocationID.x;
    if (s >= params.strandCount)
        return;  // threads past the last strand write nothing
    for (uint k = 0u; k + 1u < params.substeps; ++k)
        integrateStrand(s, k, false);
    integrateStrand(s, params.substeps - 1u, true);
}
