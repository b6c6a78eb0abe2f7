// shaders/shared/sim_strand.h: the integration algorithm of one strand in one substep, root to
// tip, compiled as GLSL by shaders/sim_integrate.comp and as C++ by the CPU twin
// (physics/cpu_solver.cpp). Each of them keeps only its addressing (where vertex i of strand s
// lies), its writes and, on the GPU, the grid splat; everything in between is here, once:
//   1. predict p = x + dt v + dt² a with gravity, drag, wind and the colliders' penalty forces;
//   2. pull toward the rest pose in the head frame (global shape, strongest at the root) and each
//      segment toward its rest direction in its parent's frame (local shape, TressFX);
//   3. push out of the colliders (a safety net for large steps), then follow-the-leader:
//      p_i <- p_{i-1} + L_i (p_i - p_{i-1}) / |p_i - p_{i-1}|, remembering d_i = p_i(after) - p_i(before);
//   4. v_i = (p_i - x_i - l_i) / dt - s_damp d_{i+1} / dt (Muller et al. 2012, eq. 9), the tip without
//      d_{i+1}; l_i is the local-shape displacement, kept out of the velocity: the pull moves only the
//      child (it is not momentum-conserving), and fed into the velocity it pumps energy into the hair
//      (measured: hair never came to rest); as a pure position correction it holds the style and settles;
//   5. a strand with any non-finite value is reset to its rest pose (the caller writes it) and counted.
// Vertex i-1 is finished while vertex i is walked (StrandWalk carries what it needs), so no
// per-strand arrays are needed.
//
// In GLSL the kernel's uniform block `params` (SimParams) and push constants `step` (SimStep) are
// globals; in C++ they are the first parameters (SIM_CONTEXT declares them, SIM_ARGS passes them).
#ifndef WISP_SHARED_SIM_STRAND_H
#define WISP_SHARED_SIM_STRAND_H
#include "sim.h"

#ifdef __cplusplus
#define SIM_CONTEXT [[maybe_unused]] const SimParams &params, [[maybe_unused]] const SimStep &step,
#define SIM_ARGS params, step,
#define GPU_INOUT(T) T&
#else
#define SIM_CONTEXT
#define SIM_ARGS
#define GPU_INOUT(T) inout T
#endif

GPU_NAMESPACE_BEGIN

// Acceleration from the colliders' penalty forces k * depth * n at x (x in the head's space once
// for every head collider), with the margin.
GPU_FN vec3 colliderPenalty(SIM_CONTEXT vec3 x)
{
    vec3 a = vec3(0.0f);
    vec3 local = toHeadSpace(step.headTransform, x);
    for (uint c = 0u; c < params.colliderCount; ++c) {
        Contact k = ellipsoidContact(params.colliders[c], local, params.collisionMargin);
        if (k.depth > 0.0f)
            a += params.penaltyStiffness * k.depth * (mat3(step.headTransform) * k.normal);
    }
    if (step.sphereRadius > 0.0f) {
        Contact k = sphereContact(step.sphereCenter, step.sphereRadius, x, params.collisionMargin);
        if (k.depth > 0.0f)
            a += params.penaltyStiffness * k.depth * k.normal;
    }
    return a;
}

// Moves p onto the surface of any collider it is inside (no margin), one collider after another.
GPU_FN vec3 collidersPushOut(SIM_CONTEXT vec3 p)
{
    vec3 local = toHeadSpace(step.headTransform, p);
    for (uint c = 0u; c < params.colliderCount; ++c) {
        Contact k = ellipsoidContact(params.colliders[c], local, 0.0f);
        if (k.depth > 0.0f) {
            p += k.depth * (mat3(step.headTransform) * k.normal);
            local = toHeadSpace(step.headTransform, p);
        }
    }
    if (step.sphereRadius > 0.0f) {
        Contact k = sphereContact(step.sphereCenter, step.sphereRadius, p, 0.0f);
        if (k.depth > 0.0f)
            p += k.depth * k.normal;
    }
    return p;
}

// What the walk from root to tip carries from one vertex to the next.
struct StrandWalk {
    SimPart part;      // the strand's part's parameters
    uint pinnedRoot;   // leading vertices that follow the head
    uint pinnedTip;    // 1: the tip follows the head too
    vec3 wind;         // the strand's wind this substep (strandWind)
    vec3 prevX;        // the parent's position at the substep's start
    vec3 prevP;        // the parent's new position
    vec3 prevShift;    // the parent's local-shape displacement (kept out of its velocity)
    bool prevPinned;
    mat3 frame;        // the parent's frame for local shape: the head's axes transported along the strand
    vec3 lastTangent;  // the last segment's direction (the tip's tangent)
    bool finite;       // no non-finite position so far
};

// A vertex the walk has finished: its new position and velocity, and its tangent toward the tip.
struct WalkedVertex {
    vec3 position;
    vec3 velocity;
    vec3 tangent;
};

// Starts a strand: its root (at rootX) is pinned where the head puts its rest position.
GPU_FN StrandWalk strandWalkBegin(SIM_CONTEXT StrandInfo info, vec3 rootX, vec3 rootRest)
{
    StrandWalk w;
    w.part = params.parts[info.part];
    w.pinnedRoot = info.pinnedRoot;
    w.pinnedTip = info.pinnedTip;
    w.wind = strandWind(step.wind, step.windFrequency, step.time, info.seed);
    w.prevX = rootX;
    w.prevP = vec3(step.headTransform * vec4(rootRest, 1.0f));
    w.prevShift = vec3(0.0f);
    w.prevPinned = true;
    w.frame = mat3(step.headTransform);
    w.lastTangent = vec3(0.0f);
    w.finite = true;
    return w;
}

// Walks vertex i of V (1 .. V-1; at x with velocity v before the substep, `r` its rest vertex,
// `parentRest` its parent's rest position): predicts, shapes, pushes out and projects it, and
// returns its parent finished (the parent's velocity needs this vertex's FTL correction).
GPU_FN WalkedVertex strandWalkStep(SIM_CONTEXT GPU_INOUT(StrandWalk) w, uint i, uint V, vec3 x, vec3 v, RestVertex r,
                                   vec3 parentRest)
{
    float dt = params.dt;
    vec3 restWorld = vec3(step.headTransform * vec4(r.position, 1.0f));
    vec3 restDir = (r.position - parentRest) / r.segmentLength;
    vec3 targetDir = w.frame * restDir;
    bool pinned = i < w.pinnedRoot || (w.pinnedTip != 0u && i == V - 1u);

    vec3 p;
    vec3 d = vec3(0.0f);
    vec3 shift = vec3(0.0f);
    if (pinned) {
        p = restWorld;
    } else {
        vec3 segment = x - w.prevX;
        float segLen = length(segment);
        vec3 t = segLen > 1e-12f ? segment / segLen : targetDir;
        vec3 a = params.gravity - w.part.drag * v + windAcceleration(t, w.wind) + colliderPenalty(SIM_ARGS x);
        p = x + dt * v + dt * dt * a;
        p = mix(p, restWorld, globalShapeWeight(w.part.globalStiffness, i, V));
        vec3 beforeShape = p;
        p = mix(p, w.prevP + r.segmentLength * targetDir, w.part.localStiffness);
        shift = p - beforeShape;
        p = collidersPushOut(SIM_ARGS p);
        vec3 before = p;
        p = ftlProject(w.prevP, p, r.segmentLength);
        d = p - before;
    }
    w.finite = w.finite && isFinite3(p);

    // Finish the parent: its velocity needs this vertex's correction d_i.
    WalkedVertex parent;
    parent.position = w.prevP;
    parent.velocity = (w.prevP - w.prevX - w.prevShift) / dt;
    if (!w.prevPinned)
        parent.velocity -= w.part.ftlDamping * d / dt;
    parent.tangent = normalize(p - w.prevP);  // |p - prevP| = L_i > 0 after FTL
    w.lastTangent = parent.tangent;

    w.frame = transportFrame(w.frame, targetDir, parent.tangent);
    w.prevX = x;
    w.prevP = p;
    w.prevPinned = pinned;
    w.prevShift = shift;
    return parent;
}

// The tip, finished after the last vertex was walked: it has no d_{i+1}.
GPU_FN WalkedVertex strandWalkTip(SIM_CONTEXT StrandWalk w)
{
    WalkedVertex tip;
    tip.position = w.prevP;
    tip.velocity = (w.prevP - w.prevX - w.prevShift) / params.dt;
    tip.tangent = w.lastTangent;
    return tip;
}

// A vertex of a strand reset after a non-finite value: its rest position where the head puts it,
// at rest, and the rest direction of the segment from `a` to `b` (head space; the vertex's own
// segment, the tip's its last one) as its tangent.
GPU_FN WalkedVertex restVertex(SIM_CONTEXT vec3 restPosition, vec3 a, vec3 b)
{
    WalkedVertex o;
    o.position = vec3(step.headTransform * vec4(restPosition, 1.0f));
    o.velocity = vec3(0.0f);
    o.tangent = mat3(step.headTransform) * normalize(b - a);
    return o;
}

GPU_NAMESPACE_END

#endif
