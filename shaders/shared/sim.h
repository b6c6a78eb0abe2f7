// shaders/shared/sim.h: the hair simulation's GPU interface and its pure math, compiled as GLSL by
// the compute kernels and as C++ by the CPU reference solver (physics/cpu_solver.cpp).
// Conventions: world space is the head's asset units (y up); time in seconds; accelerations in
// asset units / s². A strand is V consecutive vertices, root first.
#ifndef WISP_SHARED_SIM_H
#define WISP_SHARED_SIM_H
#include "mesh_sdf.h"
#include "prelude.h"

// What a kernel's functions reach as globals in GLSL, the uniform block `params` (SimParams) and
// the push constants `step` (SimStep), are their first parameters in C++: SIM_CONTEXT declares
// them, SIM_ARGS passes them (sim_strand.h, sim_grid.h). So with the head mesh's signed distance
// field (mesh_sdf.h): the kernel's buffer, reached through `sdfFieldAt`, is the C++ functions'
// `sdfField` (SIM_SDF passes it to mesh_sdf_sample.h's functions).
#ifdef __cplusplus
#define SIM_CONTEXT                                                                                                    \
    [[maybe_unused]] const SimParams &params, [[maybe_unused]] const SimStep &step,                                    \
        [[maybe_unused]] const float *sdfField,
#define SIM_ARGS params, step, sdfField,
#define SIM_SDF sdfField,
#define GPU_INOUT(T) T&
#else
#define SIM_CONTEXT
#define SIM_ARGS
#define SIM_SDF
#define GPU_INOUT(T) inout T
#endif

GPU_NAMESPACE_BEGIN

// Threads per workgroup in every simulation kernel (a define: a constant would make glslang emit
// LocalSizeId, which needs maintenance4). One warp: at Sintel's 11,400 strands, one a thread, the
// integrate's 357 warps go to an H100's 132 SMs one by one, 2 or 3 an SM, instead of as 179 pairs
// (85 SMs with 2 warps, 47 with 4).
#define SIM_GROUP_SIZE 32
GPU_CONST uint kSimGroupSize = SIM_GROUP_SIZE;
GPU_CONST uint kSimMaxColliders = 16;    // ellipsoids in SimParams (the user's sphere is separate)
GPU_CONST uint kSimMaxParts = 8;         // hair parts with their own parameters (a groom in pieces)
GPU_CONST float kGridMinDensity = 1e-4f; // grid nodes lighter than this carry no velocity

// Bindings of the simulation kernels (one push-descriptor set).
GPU_CONST uint kSimBindingParams = 0;     // uniform SimParams (SimStep is a push constant)
GPU_CONST uint kSimBindingPositions = 1;  // vec4[]: xyz position, w inverse mass (0 = pinned)
GPU_CONST uint kSimBindingVelocities = 2; // vec4[]: xyz velocity, w unused
GPU_CONST uint kSimBindingRest = 3;       // RestVertex[]
GPU_CONST uint kSimBindingStrands = 4;    // StrandInfo[]
GPU_CONST uint kSimBindingTangents = 5;   // vec4[]: xyz unit tangent toward the tip, w unused
GPU_CONST uint kSimBindingGrid = 6;       // GridNode[] (splat accumulators: this step's)
GPU_CONST uint kSimBindingGridNext = 7;   // the next step's accumulators, which the gather zeroes
GPU_CONST uint kSimBindingCounters = 8;   // SimCounters
GPU_CONST uint kSimBindingSdf = 9;        // float[]: the head mesh's signed distance field (SimParams.sdf)

// An ellipsoid collider: a point p is inside when |R^T (p - center) / radii| < 1.
struct Ellipsoid {
    mat4 rotation; // columns 0..2: the ellipsoid's axes in world space (orthonormal)
    vec3 center;   // world space
    float pad0;
    vec3 radii; // along the axes, > 0
    float pad1;
};

// Per hair part (one loaded file, or the grown guides): the parameters a user tunes per asset.
struct SimPart {
    float globalStiffness; // pull toward the rest pose in the head frame per step, [0, 1], at the root
    float localStiffness;  // pull of each segment toward its rest direction in its parent's frame, [0, 1]
    float ftlDamping;      // s_damp of Muller et al. 2012, [0.5, 1] (settings_table.cpp says why)
    float drag;            // velocity damping, 1/s
};

// Fixed for a run (a uniform block, written once when the solver is made): forces, the grid's size,
// the parts and colliders. What changes while it runs is SimStep's.
struct SimParams {
    vec3 gravity;           // world acceleration, asset units / s²
    float dt;               // one substep, seconds (fixed)
    uint strandCount;       // real strands; threads past them return
    uint verticesPerStrand; // V, 4..64
    uint colliderCount;     // ellipsoids in use, <= kSimMaxColliders
    uint gridResolution;    // nodes per axis (the grid is a cube)
    float penaltyStiffness; // k of the penalty force k * depth * n, 1/s²
    float collisionMargin;  // colliders act this far outside their surface, asset units
    float gridFriction;     // Petrovic et al. 2005 blend toward the grid velocity, [0, 1]
    float gridRepulsion;    // blend of the velocity along -grad(density) toward the separation speed, [0, 1]
    float gridCellSize;     // asset units
    uint partCount;
    uint gridNodeCount;        // gridResolution³
    float gridFixedScale;      // fixed-point grid: integer units per unit of density or momentum; 0 = float atomics
    float gridMaxSplatSpeed;   // velocities splatted into the grid are clamped to this, asset units / s
    float gridRestDensity;     // the rest pose's typical node density (restGridDensity), > 0
    float gridSeparationSpeed; // repulsion's speed down a gradient of gridRestDensity per cell, asset units / s
    uint substeps;             // integrate/FTL substeps per step, each dt long (one dispatch runs them all)
    SimPart parts[kSimMaxParts];
    Ellipsoid colliders[kSimMaxColliders]; // in head space: they move with the head
    SdfGrid sdf;                           // the head mesh's signed distance field, in head space; dims.x = 0: none
};

// What changes from step to step (push constants): the head's pose, the user's sphere, time, wind.
struct SimStep {
    mat4 headTransform;  // head space -> world (rigid): roots, rest pose and colliders follow it
    vec3 sphereCenter;   // the user's collision sphere, world space
    float sphereRadius;  // 0 disables it
    vec3 gridOrigin;     // world position of grid node (0, 0, 0)
    float time;          // simulated seconds at the start of the step (substep k starts k x dt later)
    vec3 wind;           // direction * strength, asset units / s² (before the gusts, strandWind)
    float windFrequency; // Hz of the gust modulation
};

struct RestVertex {
    vec3 position;       // rest position in head space
    float segmentLength; // rest length of the segment to the parent vertex (0 at the root)
};

struct StrandInfo {
    uint part;       // index into SimParams.parts
    uint pinnedRoot; // leading vertices that follow the head rigidly (>= 1; V: the whole strand, too short to simulate)
    uint pinnedTip;  // 1 when the tip is pinned too (TressFX bothEndsImmovable)
    uint seed;       // per-strand random seed (wind variation)
};

// Splat accumulators: float atomics add into these. The fixed-point grid (the GRID_FIXED shader
// variants) keeps the same four sums as 64-bit integers scaled by SimParams.gridFixedScale, in
// four arrays (gridFixedWord): integer adds commute, so its result does not depend on the order
// threads run in.
GPU_CONST uint kGridFixedWordsPerNode = 4u;
// Where word w (0 density, 1..3 momentum) of a node lies: four arrays of `nodeCount` words.
GPU_FN uint gridFixedWord(uint node, uint w, uint nodeCount)
{
    return w * nodeCount + node;
}
// The fixed-point scale is chosen so no node can overflow: each vertex adds weights summing to 1
// and momenta of at most kGridMaxSplatSpeed (metres per second, in the head's units) to a node.
GPU_CONST float kGridMaxSplatSpeed = 20.0f;

struct GridNode {
    vec3 momentum; // sum of weight * velocity
    float density; // sum of trilinear weights
};

struct SimCounters {
    uint nonfiniteResets; // strands reset to rest after a NaN or infinity (cumulative)
    uint pad0;
    uint pad1;
    uint pad2;
};

// ---- Vertex layout on the GPU ------------------------------------------------------------
// Strands are interleaved in blocks of kSimStrandBlock: vertex i of strand s lives at
//   ((s / 32) * V + i) * 32 + s % 32,
// so the 32 threads of a warp, each walking its own strand root to tip, read vertex i of 32
// strands from 512 consecutive bytes (coalesced) instead of from 32 places V * 16 bytes apart.
// The per-vertex kernels see the same slots; padding slots (strand >= strandCount) are skipped.
// The CPU reference keeps the plain strand-major order; GpuSolver converts on upload and readback.
GPU_CONST uint kSimStrandBlock = 32u;

GPU_FN uint vertexSlot(uint strand, uint i, uint V)
{
    return ((strand / kSimStrandBlock) * V + i) * kSimStrandBlock + strand % kSimStrandBlock;
}

GPU_FN uint strandOfSlot(uint slot, uint V)
{
    return (slot / (kSimStrandBlock * V)) * kSimStrandBlock + slot % kSimStrandBlock;
}

GPU_FN uint vertexOfSlot(uint slot, uint V)
{
    return (slot / kSimStrandBlock) % V;
}

GPU_FN uint paddedStrandCount(uint strands)
{
    return (strands + kSimStrandBlock - 1u) / kSimStrandBlock * kSimStrandBlock;
}

// ---- Pure math ---------------------------------------------------------------------------

// PCG hash (O'Neill 2014, as in Jarzynski & Olano 2020, "Hash Functions for GPU Rendering").
GPU_FN uint hashUint(uint v)
{
    uint state = v * 747796405u + 2891336453u;
    uint word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
    return (word >> 22u) ^ word;
}

// A uniform number in [0, 1) from a hash.
GPU_FN float hashToUnit(uint v)
{
    return float(hashUint(v) >> 8u) * (1.0f / 16777216.0f);
}

// Smooth 1D value noise in [0, 1): hashed values at integer x, blended with a smoothstep.
GPU_FN float valueNoise(float x, uint seed)
{
    float cell = floor(x);
    float f = x - cell;
    uint i = uint(int(cell) + 1048576); // keep the hash input positive for negative x
    float a = hashToUnit(i * 1664525u + seed);
    float b = hashToUnit((i + 1u) * 1664525u + seed);
    return mix(a, b, f * f * (3.0f - 2.0f * f));
}

// The wind a strand feels at time t: the base wind modulated by a slow gust (sine) and turbulence
// (value noise at about 2.3 times the gust frequency), with a per-strand phase, gain and noise
// stream, so neighbouring strands do not move in lockstep. The factor stays within [0.15, 1.25].
GPU_FN vec3 strandWind(vec3 wind, float frequencyHz, float t, uint seed)
{
    float phase = 6.2831853f * hashToUnit(seed);
    float gain = 0.75f + 0.5f * hashToUnit(seed ^ 0x9E3779B9u);
    float gust = 0.6f + 0.25f * sin(6.2831853f * frequencyHz * t + phase);
    float turbulence = 0.3f * (valueNoise(2.3f * frequencyHz * t + phase, seed) - 0.5f);
    return wind * (gain * (gust + turbulence));
}

// Wind on a segment with unit direction t (the TressFX wind term): (t x w) x t = w - t (t . w),
// the part of w perpendicular to the segment, so a strand aligned with the wind feels none.
GPU_FN vec3 windAcceleration(vec3 t, vec3 w)
{
    return cross(cross(t, w), t);
}

struct Contact {
    vec3 normal; // outward unit normal at the closest surface point (approximate for ellipsoids)
    float depth; // how far inside (including the margin); <= 0 when outside
};

// Sphere contact, exact.
GPU_FN Contact sphereContact(vec3 center, float radius, vec3 p, float margin)
{
    Contact c;
    vec3 d = p - center;
    float len = length(d);
    c.normal = len > 1e-12f ? d / len : vec3(0.0f, 1.0f, 0.0f);
    c.depth = radius + margin - len;
    return c;
}

// Ellipsoid contact along the ray from the centre: in the ellipsoid's unit-sphere space the
// point q = R^T (p - c) / r lies at radius |q|; its radial projection onto the surface is
// c + R (r * q / |q|), the depth is the distance to it, and the normal is the implicit
// function's gradient there, R (q / r) normalized. Exact for spheres, close for the mildly
// eccentric ellipsoids of heads (the error vanishes at the surface, where contacts matter).
GPU_FN Contact ellipsoidContact(Ellipsoid e, vec3 p, float margin)
{
    Contact c;
    mat3 R = mat3(e.rotation);
    vec3 radii = e.radii + vec3(margin);
    vec3 local = transpose(R) * (p - e.center);
    vec3 q = local / radii;
    float len = length(q);
    if (len < 1e-12f) {
        c.normal = R * vec3(0.0f, 1.0f, 0.0f);
        c.depth = radii.y;
        return c;
    }
    vec3 surface = radii * (q / len);
    c.depth = (1.0f - len) * length(surface);
    c.normal = vec3(0.0f);
    if (c.depth > 0.0f) // outside (most hair, most of the time) the normal is not used
        c.normal = normalize(R * (surface / (radii * radii)));
    return c;
}

// False when p lies outside ellipsoid e grown by `margin` (|q|² >= 1 for ellipsoidContact's q, so
// its depth is <= 0): the solvers skip the contact there, which is where most hair is. (Where the
// GPU's square root rounds |q| just below 1, the contact would give a depth of a few units in the
// last place; skipped, it gives none.)
GPU_FN bool ellipsoidMayContain(Ellipsoid e, vec3 p, float margin)
{
    vec3 q = (transpose(mat3(e.rotation)) * (p - e.center)) / (e.radii + vec3(margin));
    return dot(q, q) < 1.0f;
}

// A world-space point in the head's space, for a head posed by the rigid `head`.
GPU_FN vec3 toHeadSpace(mat4 head, vec3 p)
{
    return transpose(mat3(head)) * (p - vec3(head[3]));
}

// A head-space ellipsoid against a world-space point, for a head posed by the rigid `head`.
// (The solvers transform each vertex once for every collider with toHeadSpace and
// ellipsoidContact, which is this.)
GPU_FN Contact headColliderContact(Ellipsoid e, mat4 head, vec3 p, float margin)
{
    Contact c = ellipsoidContact(e, toHeadSpace(head, p), margin);
    c.normal = mat3(head) * c.normal;
    return c;
}

// Follow-the-leader projection (Muller et al. 2012, eq. 4): p moves onto the sphere of radius
// restLength around its parent, along the line through both.
GPU_FN vec3 ftlProject(vec3 parent, vec3 p, float restLength)
{
    vec3 d = p - parent;
    float len = length(d);
    if (len < 1e-12f)
        return parent + vec3(0.0f, -restLength, 0.0f);
    return parent + d * (restLength / len);
}

// The smallest rotation taking unit vector a to unit vector b (Rodrigues' formula written
// with v = a x b, c = a . b: R = I + [v]x + [v]x² / (1 + c)). Near-opposite vectors return the
// identity (the constraint just does not turn the frame that step).
GPU_FN mat3 minimalRotation(vec3 a, vec3 b)
{
    vec3 v = cross(a, b);
    float c = dot(a, b);
    if (c < -0.9999f)
        return mat3(1.0f);
    float k = 1.0f / (1.0f + c);
    return mat3(v.x * v.x * k + c, v.y * v.x * k + v.z, v.z * v.x * k - v.y, v.x * v.y * k - v.z, v.y * v.y * k + c,
                v.z * v.y * k + v.x, v.x * v.z * k + v.y, v.y * v.z * k - v.x, v.z * v.z * k + c);
}

// The velocity a vertex splats into the grid, no faster than maxSpeed (it bounds what a grid node
// can hold, which the fixed-point grid's overflow-safe scale relies on).
GPU_FN vec3 clampSpeed(vec3 v, float maxSpeed)
{
    float speed = length(v);
    return speed > maxSpeed ? v * (maxSpeed / speed) : v;
}

// True when no component is NaN or infinite (comparisons with NaN are false).
GPU_FN bool isFinite3(vec3 p)
{
    return abs(p.x) <= 3.0e38f && abs(p.y) <= 3.0e38f && abs(p.z) <= 3.0e38f;
}

// Carries the local-shape frame from a segment to the next: rotate it by the smallest rotation
// from the rest-predicted direction to the actual one, then re-orthonormalize (Gram-Schmidt) so
// float error cannot accumulate along 64 vertices. A segment that flipped by more than ~170
// degrees (a collision kicked it back) leaves the frame as it was.
GPU_FN mat3 transportFrame(mat3 frame, vec3 predictedDir, vec3 actualDir)
{
    vec3 a = normalize(predictedDir);
    vec3 b = normalize(actualDir);
    if (dot(a, b) < -0.985f)
        return frame;
    mat3 f = minimalRotation(a, b) * frame;
    vec3 x = normalize(f[0]);
    vec3 y = normalize(f[1] - dot(f[1], x) * x);
    return mat3(x, y, cross(x, y));
}

// Global shape: how strongly vertex i of V is pulled to its rest pose: strongest at the root,
// falling linearly to a quarter at the tip (tips still hold a styled shape).
GPU_FN float globalShapeWeight(float stiffness, uint i, uint V)
{
    float u = float(i) / float(V - 1u);
    return stiffness * (1.0f - 0.75f * u);
}

// ---- Strands pinned at both ends ---------------------------------------------------------------
// TressFX's bothEndsImmovable pins the tip as well as the root. Follow-the-leader from the root
// alone keeps every segment but the last, which stretches to wherever the tip is pinned (measured:
// stretch 2 to 7.5 and kinetic energy about 1e7 within 10 steps). Iterating FABRIK passes
// (Aristidou and Lasenby 2011) from there converges too slowly on long strands (64 vertices: 2%
// stretch after 8 passes, 0.06% after 32). Instead, after FTL the strand bends at two vertices,
// m1 and m2, a third and two thirds of the way from the last pinned root vertex a to the tip: the
// part a..m1 turns rigidly about a, the part m1..m2 and the part m2..tip move rigidly, so that m1
// keeps its distance l1 from a, m2 its distances l2 from m1 and l3 from where FTL put the tip,
// and the tip lands where it is pinned (three links between two fixed points: m1 goes where the
// distance to the tip lets the last two links reach it, bendTarget, then m2 where they meet,
// twoLinkJoint). Rigid parts keep every segment's length exactly; the root and tip follow the
// head rigidly, so the distance between them is the rest pose's, which the strand reaches. Loops
// whose ends nearly touch are solved too (one bend could not: its two parts must then be nearly
// equal). Measured on a 64-vertex loop: stretch about 1e-5 (float rounding of the turns), and it
// comes to rest (kinetic energy 1e-9) once the head stops.

// The point at distance la from `a` and lb from `b` nearest `p` (on the circle where the two
// spheres meet). When they do not meet the chain is taut: the point on the line between them that
// shares the stretch between both segments; when one holds the other, the projection around `a`.
GPU_FN vec3 twoLinkJoint(vec3 a, vec3 b, float la, float lb, vec3 p)
{
    vec3 ab = b - a;
    float d = length(ab);
    if (d < 1e-12f || d < abs(la - lb))
        return ftlProject(a, p, la);
    vec3 axis = ab / d;
    if (d >= la + lb)
        return a + axis * (d * la / (la + lb));
    float along = (d * d + la * la - lb * lb) / (2.0f * d); // from a, toward b
    float radius = sqrt(max(la * la - along * along, 0.0f));
    vec3 centre = a + along * axis;
    vec3 w = p - centre;
    w -= dot(w, axis) * axis;
    float wl = length(w);
    if (wl < 1e-12f) { // p on the axis: any point of the circle; the one toward the largest other axis
        vec3 helper = abs(axis.x) < 0.9f ? vec3(1.0f, 0.0f, 0.0f) : vec3(0.0f, 1.0f, 0.0f);
        w = normalize(cross(axis, helper));
    } else {
        w /= wl;
    }
    return centre + radius * w;
}

// A rotation taking unit vector a to unit vector b at any angle, to float precision: the minimal
// rotation, which loses precision as the vectors near opposite (its 1 / (1 + a.b)), composed with
// a half turn about an axis across a when they are more than 90 degrees apart.
GPU_FN mat3 rotationBetween(vec3 a, vec3 b)
{
    if (dot(a, b) >= 0.0f)
        return minimalRotation(a, b);
    vec3 helper = abs(a.x) < 0.9f ? vec3(1.0f, 0.0f, 0.0f) : vec3(0.0f, 1.0f, 0.0f);
    vec3 u = normalize(cross(a, helper));
    mat3 halfTurn = 2.0f * outerProduct(u, u) - mat3(1.0f); // takes a to -a
    return minimalRotation(-a, b) * halfTurn;
}

// The bends sit a third and two thirds along unless a part's chord is shorter than this share of
// a third of the strand's span, or the parts cannot reach the tip; then every pair is tried.
GPU_CONST float kBendMinChord = 0.2f;

// Where the first bend m1 (l1 from a, `current` from the tip now) must go: its distance to the
// tip, `d` from a, nearest `current` such that m1 stays l1 from a and the links l2, l3 still reach
// the tip from it. Negative when no distance does (a chain too short for its ends).
GPU_FN float bendTarget(float current, float l1, float l2, float l3, float d)
{
    float lo = max(abs(l2 - l3), abs(l1 - d));
    float hi = min(l2 + l3, l1 + d);
    if (lo > hi)
        return -1.0f;
    // A little inside the range: at its ends the joints fall on an axis, where the circle's radius
    // is the square root of rounding (and the GPU and the CPU round differently).
    float inset = 0.01f * (hi - lo);
    return clamp(current, lo + inset, hi - inset);
}

// The bend is an inelastic constraint, like a contact: a vertex it moves by `move` over a substep
// of dt loses the velocity that ran against the move, up to the move's own speed |move| / dt (what
// the constraint cancelled), and keeps the rest. (Feeding the move into the velocity, as PBD does,
// kept a loop jittering by millimetres a step at rest; leaving the velocity alone let gravity
// build up a velocity of metres per second that the bend absorbed every substep; removing the
// whole opposing part made a move of rounding size change the velocity.)
GPU_FN vec3 constrainedVelocity(vec3 v, vec3 move, float dt)
{
    float len = length(move);
    if (len < 1e-12f)
        return v;
    vec3 n = move / len;
    float against = dot(v, n);
    return against < 0.0f ? v + min(-against, len / dt) * n : v;
}

// ---- The hair-hair grid (Petrovic et al. 2005) ---------------------------------------------

struct GridCell {
    ivec3 base; // the lower corner node
    vec3 frac;  // position inside the cell, [0, 1)³
};

GPU_FN GridCell gridCell(vec3 p, vec3 origin, float cellSize)
{
    GridCell g;
    vec3 x = (p - origin) / cellSize;
    vec3 f = floor(x);
    g.base = ivec3(f);
    g.frac = x - f;
    return g;
}

// Trilinear weight of corner k (bit 0: +x, bit 1: +y, bit 2: +z); the 8 weights sum to 1.
GPU_FN float cornerWeight(vec3 frac, uint k)
{
    float wx = (k & 1u) != 0u ? frac.x : 1.0f - frac.x;
    float wy = (k & 2u) != 0u ? frac.y : 1.0f - frac.y;
    float wz = (k & 4u) != 0u ? frac.z : 1.0f - frac.z;
    return wx * wy * wz;
}

GPU_FN ivec3 cornerOffset(uint k)
{
    return ivec3(int(k & 1u), int((k >> 1u) & 1u), int((k >> 2u) & 1u));
}

// True when all 8 corners of the cell are inside a grid of n nodes per axis.
GPU_FN bool cellInside(ivec3 base, uint n)
{
    int last = int(n) - 2;
    return base.x >= 0 && base.y >= 0 && base.z >= 0 && base.x <= last && base.y <= last && base.z <= last;
}

GPU_FN uint gridIndex(ivec3 node, uint n)
{
    return uint(node.x) + n * (uint(node.y) + n * uint(node.z));
}

// The gather's running sums over the 8 corners.
struct GridSample {
    vec3 velocity; // sum of w * v over corners with density
    float weight;  // sum of w over those corners
};

GPU_FN GridSample gridSampleZero()
{
    GridSample s;
    s.velocity = vec3(0.0f);
    s.weight = 0.0f;
    return s;
}

GPU_FN GridSample gridAccumulate(GridSample s, vec3 frac, uint k, vec3 nodeVelocity, float nodeDensity)
{
    float w = cornerWeight(frac, k);
    if (nodeDensity > kGridMinDensity) {
        s.velocity += w * nodeVelocity;
        s.weight += w;
    }
    return s;
}

// Hair-hair friction (Petrovic et al. 2005): v <- (1 - friction) v + friction v_grid.
GPU_FN vec3 gridFriction(vec3 v, GridSample s, float friction)
{
    return s.weight > 0.0f ? mix(v, s.velocity / s.weight, friction) : v;
}

// Repulsion moves hair down the density gradient at most this many grid cells per step (at
// repulsion 1, where the density falls by the rest density over one cell or more): a displacement
// well under a cell per step keeps the explicit step of this diffusion-like flow stable.
GPU_CONST float kRepulsionCellsPerStep = 0.05f;

// Hair-hair repulsion (volume keeping, after Petrovic et al. 2005): the change of velocity v that
// moves the hair apart where it is dense, for the density gradient `densityGrad` (per cell).
//   g = densityGrad / restDensity: dimensionless, so independent of the groom's vertex count, the
//       grid's resolution and the head's units;
//   the velocity's component along n = -g / |g| is blended, by `repulsion` in [0, 1], toward the
//   separation speed u = separationSpeed * min(|g|, 1) where it is slower (hair already moving
//   apart faster is left alone).
// A blend toward a bounded speed, not an impulse: it cannot build up from step to step, so every
// repulsion in [0, 1] is stable. (The impulse it replaces, repulsion * grad(density) / cellSize with
// the density in vertices, gave the 35,200 vertices of the default bob 400 m/s in one step at 0.1.)
GPU_FN vec3 gridRepulsionChange(vec3 v, vec3 densityGrad, float repulsion, float separationSpeed, float restDensity)
{
    vec3 g = densityGrad / restDensity;
    float len = length(g);
    if (repulsion <= 0.0f || len < 1e-6f)
        return vec3(0.0f);
    vec3 n = -g / len;
    float target = separationSpeed * min(len, 1.0f);
    float along = dot(v, n);
    return along < target ? (repulsion * (target - along)) * n : vec3(0.0f);
}

// A change of velocity dv less its part toward a collider surface within `reach` of the point (the
// contact's outward normal n): no hair lies inside a collider, so the density falls toward it and
// its gradient would push the hair's inner layer into the head, which the contacts push back out,
// step after step.
GPU_FN vec3 withoutPartInto(vec3 dv, Contact c)
{
    if (c.depth <= 0.0f)
        return dv;
    float into = dot(dv, c.normal);
    return into < 0.0f ? dv - into * c.normal : dv;
}

GPU_NAMESPACE_END

#ifdef __cplusplus
// The layouts GLSL gives these blocks, checked where they are defined (C++ only).
static_assert(sizeof(gpu::SimParams) == 1808, "SimParams must match its std140 layout");
static_assert(offsetof(gpu::SimParams, parts) == 80 && offsetof(gpu::SimParams, colliders) == 208);
static_assert(sizeof(gpu::SimStep) == 112 && sizeof(gpu::SimStep) <= 128,
              "SimStep must match its push-constant layout");
static_assert(offsetof(gpu::SimStep, wind) == 96);
static_assert(sizeof(gpu::RestVertex) == 16 && sizeof(gpu::StrandInfo) == 16 && sizeof(gpu::GridNode) == 16);
#endif

#endif
