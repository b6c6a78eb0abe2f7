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
//   5. a strand pinned at both ends (TressFX bothEndsImmovable) bends at two vertices after the walk,
//      its three parts moving rigidly, so that its end lands on the pinned tip (strandBend, with
//      sim.h's twoLinkJoint and bendTarget), every segment kept;
//   6. a strand with any non-finite value is reset to its rest pose (the caller writes it) and counted.
// Vertex i-1 is finished while vertex i is walked (StrandWalk carries what it needs), so no
// per-strand arrays are needed.
//
// In GLSL the kernel's uniform block `params` (SimParams) and push constants `step` (SimStep) are
// globals; in C++ they are the first parameters (sim.h's SIM_CONTEXT declares them, SIM_ARGS passes them).
// The bend reaches any vertex of its strand, so the includer defines first how (its addressing):
// a type StrandRef naming one strand, and strandPosition(s, i), strandVelocity(s, i),
// strandSetVertex(s, i, position, velocity) and strandRestLength(s, i) for its vertex i.
#ifndef WISP_SHARED_SIM_STRAND_H
#define WISP_SHARED_SIM_STRAND_H
#include "mesh_sdf_sample.h"
#include "sim.h"

GPU_NAMESPACE_BEGIN

// The head's colliders are ellipsoids fitted under the scalp (physics/colliders.h), so a strand
// grown or styled along the head rests within the margin shell, and even dips into a collider by a
// millimetre or so where the scalp does; the first vertices of every strand, rooted on the scalp,
// rest inside the shell. The penalty measures depth into the shell beyond the rest position's own
// (`restHead`, head space; restDepth: how deep it lies inside collider c, <= 0 outside): pushed
// from the shell's surface instead, those vertices were pushed against their pinned roots every
// step, k * margin up to 20 g at the 5 cm margin, which the FTL correction turned into sideways
// velocity (the bob's 160 guides on the CPU for two seconds, worst kinetic energy: 4,677 at margin
// 0.05 m against 64 at 0.003 m). Measured from the rest depth, 52 against 50
// (tests/test_sim_stability.cpp, after a quarter of a second's settling).
// The push-out moves a rest vertex inside a collider out at the first steps. It is not measured
// against the rest depth too: that popped nothing, but fur's crown strands, then not held off the
// head, kept moving 1 to 3 mm a step once the head stopped (docs/physics.md).
GPU_FN float restDepth(Ellipsoid e, vec3 restHead)
{
    return ellipsoidContact(e, restHead, 0.0f).depth;
}

// Acceleration from the colliders' penalty forces k * depth * n at x (x in the head's space once
// for every head collider), with the margin: the depth beyond the rest pose's depth into the
// margin shell (at most the margin: no allowance reaches inside the collider for the penalty).
GPU_FN vec3 colliderPenalty(SIM_CONTEXT vec3 x, vec3 restHead)
{
    vec3 a = vec3(0.0f);
    vec3 local = toHeadSpace(step.headTransform, x);
    for (uint c = 0u; c < params.colliderCount; ++c) {
        // Outside the shell (most hair) the depth is <= 0 <= allowed: no force, and neither the
        // contact nor the rest pose's depth is worked out.
        if (!ellipsoidMayContain(params.colliders[c], local, params.collisionMargin))
            continue;
        Contact k = ellipsoidContact(params.colliders[c], local, params.collisionMargin);
        float allowed =
            clamp(restDepth(params.colliders[c], restHead) + params.collisionMargin, 0.0f, params.collisionMargin);
        if (k.depth > allowed)
            a += params.penaltyStiffness * (k.depth - allowed) * (mat3(step.headTransform) * k.normal);
    }
    // The head mesh itself (its field, in head space): the same penalty along the field's gradient
    // where the vertex lies nearer the surface than the margin, beyond its rest position's own depth
    // into that shell (roots rest on the scalp, inside it).
    if (params.sdf.dims.x > 0u) {
        float d = sdfSample(SIM_SDF params.sdf, local);
        if (d < params.collisionMargin) {
            float allowed =
                clamp(params.collisionMargin - sdfSample(SIM_SDF params.sdf, restHead), 0.0f, params.collisionMargin);
            float depth = params.collisionMargin - d;
            vec3 g = sdfGradient(SIM_SDF params.sdf, local);
            if (depth > allowed && dot(g, g) > 0.0f)
                a += params.penaltyStiffness * (depth - allowed) * (mat3(step.headTransform) * normalize(g));
        }
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
        if (!ellipsoidMayContain(params.colliders[c], local, 0.0f))
            continue;
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
    SimPart part;    // the strand's part's parameters
    uint pinnedRoot; // leading vertices that follow the head
    uint pinnedTip;  // 1: the tip follows the head too
    vec3 wind;       // the strand's wind this substep (strandWind)
    vec3 prevX;      // the parent's position at the substep's start
    vec3 prevP;      // the parent's new position
    vec3 prevShift;  // the parent's local-shape displacement (kept out of its velocity)
    bool prevPinned;
    mat3 frame;       // the parent's frame for local shape: the head's axes transported along the strand
    vec3 lastTangent; // the last segment's direction (the tip's tangent)
    bool finite;      // no non-finite position so far
};

// A vertex the walk has finished: its new position and velocity, and its tangent toward the tip.
struct WalkedVertex {
    vec3 position;
    vec3 velocity;
    vec3 tangent;
};

// Starts a strand's substep that begins at `time` (seconds): its root (at rootX) is pinned where the
// head puts its rest position.
GPU_FN StrandWalk strandWalkBegin(SIM_CONTEXT StrandInfo info, vec3 rootX, vec3 rootRest, float time)
{
    StrandWalk w;
    w.part = params.parts[info.part];
    w.pinnedRoot = info.pinnedRoot;
    w.pinnedTip = info.pinnedTip;
    w.wind = strandWind(step.wind, step.windFrequency, time, info.seed);
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
        vec3 a =
            params.gravity - w.part.drag * v + windAcceleration(t, w.wind) + colliderPenalty(SIM_ARGS x, r.position);
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
    parent.tangent = normalize(p - w.prevP); // |p - prevP| = L_i > 0 after FTL
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

// ---- A strand pinned at both ends ------------------------------------------------------------

// Moves vertex i of strand s to p as an inelastic constraint (constrainedVelocity, sim.h).
GPU_FN void bendMove(SIM_CONTEXT StrandRef s, uint i, vec3 p, GPU_INOUT(bool) finite)
{
    strandSetVertex(s, i, p, constrainedVelocity(strandVelocity(s, i), p - strandPosition(s, i), params.dt));
    finite = finite && isFinite3(p);
}

// The shortest chord of the three parts strand s would bend into at vertices i1 < i2, or -1 when
// they cannot reach its tip (bendTarget).
GPU_FN float bendChord(StrandRef s, vec3 a, vec3 tipP, vec3 end, float d, uint i1, uint i2)
{
    vec3 q1 = strandPosition(s, i1);
    vec3 q2 = strandPosition(s, i2);
    if (bendTarget(length(tipP - q1), length(q1 - a), length(q2 - q1), length(end - q2), d) < 0.0f)
        return -1.0f;
    return min(min(length(q1 - a), length(q2 - q1)), length(end - q2));
}

// After the walk, a strand pinned at both ends (info.pinnedTip, free vertices between) bends at two
// vertices so that its end lands on the pinned tip, its three parts moving rigidly (sim.h); a moved
// vertex keeps no velocity against its move. `finite` turns false on a non-finite move.
GPU_FN void strandBend(SIM_CONTEXT StrandRef s, StrandInfo info, uint V, GPU_INOUT(bool) finite)
{
    uint anchor = info.pinnedRoot - 1u; // the last pinned root vertex
    uint span = V - 1u - anchor;
    vec3 a = strandPosition(s, anchor);
    vec3 tipP = strandPosition(s, V - 1u);
    float d = length(tipP - a);
    if (span == 2u) { // one free vertex: where the spheres around a and the tip meet
        bendMove(
            SIM_ARGS s, V - 2u,
            twoLinkJoint(a, tipP, strandRestLength(s, V - 2u), strandRestLength(s, V - 1u), strandPosition(s, V - 2u)),
            finite);
        return;
    }
    vec3 end = ftlProject(strandPosition(s, V - 2u), tipP, strandRestLength(s, V - 1u)); // where FTL put the tip
    // The bends: a third and two thirds along, unless their parts cannot reach the tip or one
    // part's chord is tiny (a curled loop's middle: its direction would be rounding); then the pair
    // whose parts reach it with the longest shortest chord.
    uint m1 = max(anchor + span / 3u, anchor + 1u);
    uint m2 = max(anchor + (2u * span) / 3u, m1 + 1u);
    float best = bendChord(s, a, tipP, end, d, m1, m2);
    if (best < kBendMinChord * length(end - a) / 3.0f)
        for (uint i1 = anchor + 1u; i1 < V - 2u; ++i1)
            for (uint i2 = i1 + 1u; i2 < V - 1u; ++i2) {
                float c = bendChord(s, a, tipP, end, d, i1, i2);
                if (c > best) {
                    best = c;
                    m1 = i1;
                    m2 = i2;
                }
            }
    vec3 p1 = strandPosition(s, m1);
    vec3 p2 = strandPosition(s, m2);
    float l1 = length(p1 - a), l2 = length(p2 - p1), l3 = length(end - p2);
    float target = bendTarget(length(tipP - p1), l1, l2, l3, d);
    if (target >= 0.0f && l1 > 1e-12f && l2 > 1e-12f && l3 > 1e-12f) {
        vec3 b1 = twoLinkJoint(a, tipP, l1, target, p1);
        vec3 b2 = twoLinkJoint(b1, tipP, l2, l3, p2);
        mat3 r1 = rotationBetween((p1 - a) / l1, normalize(b1 - a));
        mat3 r2 = rotationBetween((p2 - p1) / l2, normalize(b2 - b1));
        mat3 r3 = rotationBetween((end - p2) / l3, normalize(tipP - b2));
        for (uint i = m2 + 1u; i < V - 1u; ++i)
            bendMove(SIM_ARGS s, i, b2 + r3 * (strandPosition(s, i) - p2), finite);
        for (uint i = m1 + 1u; i <= m2; ++i)
            bendMove(SIM_ARGS s, i, b1 + r2 * (strandPosition(s, i) - p1), finite);
        for (uint i = info.pinnedRoot; i <= m1; ++i)
            bendMove(SIM_ARGS s, i, a + r1 * (strandPosition(s, i) - a), finite);
    }
}

// True when strand `info` of V vertices is pinned at both ends with free vertices between.
GPU_FN bool pinnedAtBothEnds(StrandInfo info, uint V)
{
    return info.pinnedTip != 0u && info.pinnedRoot < V - 1u;
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
