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
//   5. a strand with any non-finite value is reset to its rest pose and counted.
// Vertex i-1 is finished (written) while vertex i is processed, so no per-strand arrays are needed.
#extension GL_GOOGLE_include_directive : require
#include "sim_common.glsl"

layout(local_size_x = SIM_GROUP_SIZE) in;

// Acceleration from the colliders' penalty forces k * depth * n at x.
vec3 penalty(vec3 x)
{
    vec3 a = vec3(0.0);
    for (uint c = 0u; c < params.colliderCount; ++c) {
        Contact k = headColliderContact(params.colliders[c], step.headTransform, x, params.collisionMargin);
        if (k.depth > 0.0)
            a += params.penaltyStiffness * k.depth * k.normal;
    }
    if (step.sphereRadius > 0.0) {
        Contact k = sphereContact(step.sphereCenter, step.sphereRadius, x, params.collisionMargin);
        if (k.depth > 0.0)
            a += params.penaltyStiffness * k.depth * k.normal;
    }
    return a;
}

// Moves p onto the surface of any collider it is inside (no margin).
vec3 pushOut(vec3 p)
{
    for (uint c = 0u; c < params.colliderCount; ++c) {
        Contact k = headColliderContact(params.colliders[c], step.headTransform, p, 0.0);
        if (k.depth > 0.0)
            p += k.depth * k.normal;
    }
    if (step.sphereRadius > 0.0) {
        Contact k = sphereContact(step.sphereCenter, step.sphereRadius, p, 0.0);
        if (k.depth > 0.0)
            p += k.depth * k.normal;
    }
    return p;
}

void main()
{
    uint s = gl_GlobalInvocationID.x;
    if (s >= params.strandCount)
        return;  // threads past the last strand write nothing
    uint V = params.verticesPerStrand;
    uint base = s * V;
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

    for (uint i = 1u; i < V; ++i) {
        uint g = base + i;
        vec3 x = positions[g].xyz;
        vec3 v = velocities[g].xyz;
        RestVertex r = rest[g];
        vec3 restWorld = (step.headTransform * vec4(r.position, 1.0)).xyz;
        vec3 restDir = (r.position - rest[g - 1u].position) / r.segmentLength;
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
        positions[g - 1u].xyz = prevP;
        velocities[g - 1u].xyz = prevV;
        vec3 actualDir = normalize(p - prevP);  // |p - prevP| = L_i > 0 after FTL
        tangents[g - 1u] = vec4(actualDir, 0.0);
        lastTangent = actualDir;

        frame = transportFrame(frame, targetDir, actualDir);
        prevX = x;
        prevP = p;
        prevPinned = pinned;
        prevShift = shift;
    }
    // The tip has no d_{i+1}.
    positions[base + V - 1u].xyz = prevP;
    velocities[base + V - 1u].xyz = (prevP - prevX - prevShift) / dt;
    tangents[base + V - 1u] = vec4(lastTangent, 0.0);

    if (!finite) {
        for (uint i = 0u; i < V; ++i) {
            positions[base + i].xyz = (step.headTransform * vec4(rest[base + i].position, 1.0)).xyz;
            velocities[base + i].xyz = vec3(0.0);
            uint j = min(i + 1u, V - 1u);
            tangents[base + i] = vec4(R * normalize(rest[base + j].position - rest[base + j - 1u].position), 0.0);
        }
        atomicAdd(counters.nonfiniteResets, 1u);
    }
}
