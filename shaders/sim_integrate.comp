#version 460
// sim_integrate.comp: one substep of one strand per thread, root to tip (the CPU twin is
// CpuSolver::integrateStrand in physics/cpu_solver.cpp; keep them in step).
//   1. predict p = x + dt v + dt² a with gravity, drag, wind and collider penalty forces;
//   2. pull toward the rest pose in the head frame (global shape, strongest at the root) and each
//      segment toward its rest direction in its parent's frame (local shape, TressFX);
//   3. push out of the colliders (a safety net for large steps), then follow-the-leader:
//      p_i <- p_{i-1} + L_i (p_i - p_{i-1}) / |p_i - p_{i-1}|, remembering d_i = p_i(after) - p_i(before);
//   4. v_i = (p_i - x_i - l_i) / dt - s_damp d_{i+1} / dt (Muller et al. 2012, eq. 9), the tip without
//      d_{i+1}; l_i is the local-shape displacement, kept out of the velocity: the pull moves only the
//      child (it is not momentum-conserving), and fed into the velocity it pumps energy into the hair
//      (measured: hair never came to rest); as a pure position correction it holds the style and settles;
//   5. a strand pinned at both ends (TressFX bothEndsImmovable) bends at two vertices, its three
//      parts moving rigidly, so that its end lands on the pinned tip (sim.h), every segment kept;
//   6. a strand with any non-finite value is reset to its rest pose and counted.
// Vertex i-1 is finished (written) while vertex i is processed, so no per-strand arrays are needed.
//
// The variant with kSplatToGrid (the step's last substep) also splats the hair-hair grid for its
// strand: consecutive vertices of a strand usually fall in the same grid cell, so their trilinear
// contributions are summed in registers and added with one set of atomics per run of vertices,
// instead of one per vertex (atomics on the same nodes were the step's bottleneck). A run that
// moves into a neighbouring cell keeps the corners both cells share and adds only the ones it
// leaves (slideRun): 4 nodes per cell crossed instead of 8. The sums are CpuSolver::gridSplat's,
// up to float order (a strand reset for non-finite values keeps the finite contributions it made
// before the reset; the CPU splats its rest pose). It also writes the tangents, which earlier
// substeps leave to it.
#extension GL_GOOGLE_include_directive : require
#ifdef GRID_FIXED
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
#extension GL_EXT_shader_atomic_int64 : require
#else
#extension GL_EXT_shader_atomic_float : require
#endif
#include "sim_common.glsl"
#include "grid_storage.glsl"

layout(local_size_x = SIM_GROUP_SIZE) in;
layout(constant_id = 0) const bool kSplatToGrid = false;

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

// Acceleration from the colliders' penalty forces k * depth * n at x (x in the head's space once
// for every head collider).
vec3 penalty(vec3 x)
{
    vec3 a = vec3(0.0);
    vec3 local = toHeadSpace(step.headTransform, x);
    for (uint c = 0u; c < params.colliderCount; ++c) {
        Contact k = ellipsoidContact(params.colliders[c], local, params.collisionMargin);
        if (k.depth > 0.0)
            a += params.penaltyStiffness * k.depth * (mat3(step.headTransform) * k.normal);
    }
    if (step.sphereRadius > 0.0) {
        Contact k = sphereContact(step.sphereCenter, step.sphereRadius, x, params.collisionMargin);
        if (k.depth > 0.0)
            a += params.penaltyStiffness * k.depth * k.normal;
    }
    return a;
}

// Moves p onto the surface of any collider it is inside (no margin), one collider after another.
vec3 pushOut(vec3 p)
{
    vec3 local = toHeadSpace(step.headTransform, p);
    for (uint c = 0u; c < params.colliderCount; ++c) {
        Contact k = ellipsoidContact(params.colliders[c], local, 0.0);
        if (k.depth > 0.0) {
            p += k.depth * (mat3(step.headTransform) * k.normal);
            local = toHeadSpace(step.headTransform, p);
        }
    }
    if (step.sphereRadius > 0.0) {
        Contact k = sphereContact(step.sphereCenter, step.sphereRadius, p, 0.0);
        if (k.depth > 0.0)
            p += k.depth * k.normal;
    }
    return p;
}

// The shortest chord of the three parts a strand pinned at both ends would bend into at vertices
// i1 < i2, or -1 when they cannot reach its tip (sim.h bendTarget).
float bendChord(uint base, vec3 a, vec3 tipP, vec3 end, float d, uint i1, uint i2)
{
    vec3 q1 = positions[base + i1 * kSimStrandBlock].xyz;
    vec3 q2 = positions[base + i2 * kSimStrandBlock].xyz;
    if (bendTarget(length(tipP - q1), length(q1 - a), length(q2 - q1), length(end - q2), d) < 0.0)
        return -1.0;
    return min(min(length(q1 - a), length(q2 - q1)), length(end - q2));
}

// Moves vertex i of the strand at `base` to p, as an inelastic constraint (constrainedVelocity).
void moveVertex(uint base, uint i, vec3 p, inout bool finite)
{
    uint g = base + i * kSimStrandBlock;
    velocities[g].xyz = constrainedVelocity(velocities[g].xyz, p - positions[g].xyz, params.dt);
    positions[g].xyz = p;
    finite = finite && isFinite3(p);
}

void main()
{
    uint s = gl_GlobalInvocationID.x;
    if (s >= params.strandCount)
        return;  // threads past the last strand write nothing
    uint V = params.verticesPerStrand;
    uint base = vertexSlot(s, 0u, V);  // vertex i is at base + i * kSimStrandBlock
    StrandInfo info = strands[s];
    SimPart part = params.parts[info.part];
    float dt = params.dt;
    mat3 R = mat3(step.headTransform);
    vec3 wind = strandWind(params.wind, params.windFrequency, step.time, info.seed);
    bool finite = true;
    vec3 lastTangent = vec3(0.0);

    // The root: pinned to the head.
    vec3 prevX = positions[base].xyz;
    vec3 prevP = (step.headTransform * vec4(rest[base].position, 1.0)).xyz;
    bool prevPinned = true;
    vec3 prevShift = vec3(0.0);  // the parent's local-shape displacement (kept out of its velocity)
    mat3 frame = R;  // the parent's frame for local shape: head axes transported along the strand
    // A strand with both ends pinned is finished after the bends below: its splat and tangents
    // wait for them.
    bool bothEnds = info.pinnedTip != 0u && info.pinnedRoot < V - 1u;
    bool splatNow = kSplatToGrid && !bothEnds;

    for (uint i = 1u; i < V; ++i) {
        uint g = base + i * kSimStrandBlock;
        uint parent = g - kSimStrandBlock;
        vec3 x = positions[g].xyz;
        vec3 v = velocities[g].xyz;
        RestVertex r = rest[g];
        vec3 restWorld = (step.headTransform * vec4(r.position, 1.0)).xyz;
        vec3 restDir = (r.position - rest[parent].position) / r.segmentLength;
        vec3 targetDir = frame * restDir;
        bool pinned = i < info.pinnedRoot || (info.pinnedTip != 0u && i == V - 1u);

        vec3 p;
        vec3 d = vec3(0.0);
        vec3 shift = vec3(0.0);
        if (pinned) {
            p = restWorld;
        } else {
            vec3 segment = x - prevX;
            float segLen = length(segment);
            vec3 t = segLen > 1e-12 ? segment / segLen : targetDir;
            vec3 a = params.gravity - part.drag * v + windAcceleration(t, wind) + penalty(x);
            p = x + dt * v + dt * dt * a;
            p = mix(p, restWorld, globalShapeWeight(part.globalStiffness, i, V));
            vec3 beforeShape = p;
            p = mix(p, prevP + r.segmentLength * targetDir, part.localStiffness);
            shift = p - beforeShape;
            p = pushOut(p);
            vec3 before = p;
            p = ftlProject(prevP, p, r.segmentLength);
            d = p - before;
        }
        finite = finite && isFinite3(p);

        // Finish the parent: its velocity needs this vertex's correction d_i.
        vec3 prevV = (prevP - prevX - prevShift) / dt;
        if (!prevPinned)
            prevV -= part.ftlDamping * d / dt;
        positions[parent].xyz = prevP;
        velocities[parent].xyz = prevV;
        vec3 actualDir = normalize(p - prevP);  // |p - prevP| = L_i > 0 after FTL
        if (splatNow) {
            splatVertex(prevP, prevV);
            tangents[parent] = vec4(actualDir, 0.0);
        }
        lastTangent = actualDir;

        frame = transportFrame(frame, targetDir, actualDir);
        prevX = x;
        prevP = p;
        prevPinned = pinned;
        prevShift = shift;
    }
    // The tip has no d_{i+1}.
    uint tip = base + (V - 1u) * kSimStrandBlock;
    vec3 tipV = (prevP - prevX - prevShift) / dt;
    positions[tip].xyz = prevP;
    velocities[tip].xyz = tipV;
    if (splatNow) {
        tangents[tip] = vec4(lastTangent, 0.0);
        splatVertex(prevP, tipV);
        if (runOpen)
            flushRun();
    }

    // Both ends pinned: the strand bends at two vertices so that its end lands on the pinned tip,
    // its three parts moving rigidly (sim.h); a moved vertex keeps no velocity against its move.
    if (bothEnds) {
        uint anchor = info.pinnedRoot - 1u;  // the last pinned root vertex
        uint span = V - 1u - anchor;
        vec3 a = positions[base + anchor * kSimStrandBlock].xyz;
        vec3 tipP = positions[tip].xyz;
        float d = length(tipP - a);
        if (span == 2u) {  // one free vertex: where the spheres around a and the tip meet
            uint g = base + (V - 2u) * kSimStrandBlock;
            moveVertex(base, V - 2u, twoLinkJoint(a, tipP, rest[g].segmentLength, rest[tip].segmentLength, positions[g].xyz), finite);
        } else {
            vec3 end = ftlProject(positions[base + (V - 2u) * kSimStrandBlock].xyz, tipP, rest[tip].segmentLength);
            // The bends: a third and two thirds along, unless their parts cannot reach the tip or
            // one part's chord is tiny; then the pair that reaches it with the longest shortest chord
            // (CpuSolver searches in the same order).
            uint m1 = max(anchor + span / 3u, anchor + 1u);
            uint m2 = max(anchor + (2u * span) / 3u, m1 + 1u);
            float best = bendChord(base, a, tipP, end, d, m1, m2);
            if (best < kBendMinChord * length(end - a) / 3.0)
                for (uint i1 = anchor + 1u; i1 < V - 2u; ++i1)
                    for (uint i2 = i1 + 1u; i2 < V - 1u; ++i2) {
                        float c = bendChord(base, a, tipP, end, d, i1, i2);
                        if (c > best) {
                            best = c;
                            m1 = i1;
                            m2 = i2;
                        }
                    }
            vec3 p1 = positions[base + m1 * kSimStrandBlock].xyz;
            vec3 p2 = positions[base + m2 * kSimStrandBlock].xyz;
            float l1 = length(p1 - a), l2 = length(p2 - p1), l3 = length(end - p2);
            float target = bendTarget(length(tipP - p1), l1, l2, l3, d);
            if (target >= 0.0 && l1 > 1e-12 && l2 > 1e-12 && l3 > 1e-12) {
                vec3 b1 = twoLinkJoint(a, tipP, l1, target, p1);
                vec3 b2 = twoLinkJoint(b1, tipP, l2, l3, p2);
                mat3 r1 = rotationBetween((p1 - a) / l1, normalize(b1 - a));
                mat3 r2 = rotationBetween((p2 - p1) / l2, normalize(b2 - b1));
                mat3 r3 = rotationBetween((end - p2) / l3, normalize(tipP - b2));
                for (uint i = m2 + 1u; i < V - 1u; ++i)
                    moveVertex(base, i, b2 + r3 * (positions[base + i * kSimStrandBlock].xyz - p2), finite);
                for (uint i = m1 + 1u; i <= m2; ++i)
                    moveVertex(base, i, b1 + r2 * (positions[base + i * kSimStrandBlock].xyz - p1), finite);
                for (uint i = info.pinnedRoot; i <= m1; ++i)
                    moveVertex(base, i, a + r1 * (positions[base + i * kSimStrandBlock].xyz - a), finite);
            }
        }
        if (kSplatToGrid) {
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

    if (!finite) {
        for (uint i = 0u; i < V; ++i) {
            uint g = base + i * kSimStrandBlock;
            positions[g].xyz = (step.headTransform * vec4(rest[g].position, 1.0)).xyz;
            velocities[g].xyz = vec3(0.0);
            uint j = base + min(i + 1u, V - 1u) * kSimStrandBlock;
            tangents[g] = vec4(R * normalize(rest[j].position - rest[j - kSimStrandBlock].position), 0.0);
        }
        atomicAdd(counters.nonfiniteResets, 1u);
    }
}
