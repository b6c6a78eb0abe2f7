// shaders/shared/strands.h: how simulated guides become a head of hair in the tessellation
// stages, and the pure math of it, shared by hair.tesc/.tese/.geom/.frag and the C++ tests:
// C1 cubic Bezier segments from the guide polyline (uniform Catmull-Rom tangents), strands around
// a guide (single-strand interpolation: a tapered disc, i.e. clumps) or between three guides
// (multi-strand interpolation, barycentric, Nalu), random deviations (Rapp 2014's five profiles),
// render-time coils finer than the simulated vertices, each drawn strand's own length along its
// guide, and continuous level of detail. (The shading models are in hair_shading.h.)
// Conventions: world space in the head's units; t in [0, 1] runs root to tip.
#ifndef WISP_SHARED_STRANDS_H
#define WISP_SHARED_STRANDS_H
#include "prelude.h"
#include "sim.h"

GPU_NAMESPACE_BEGIN

// Tessellation limits of every device here (and Vulkan's guaranteed minimum is 64 too): more
// strands or divisions than this come from more patches, never from a silently capped level.
GPU_CONST uint kMaxTessLevel = 64u;
// By default a patch emits at most this many vertices (its lines x (divisions + 1); the tests' knob
// StrandSettings::maxPatchVertices changes it, no setting does). Bigger patches hardly help on the
// H100 (docs/drawing.md, "The tessellation path"); on lavapipe they draw the same picture once
// draws keep within kMaxTessVerticesPerDraw (what bigger patches lose there is that limit, not the
// patch's size).
GPU_CONST uint kMaxPatchVertices = 128u;
// The tessellated vertices one instance of one draw may produce. Mesa's draw module (lavapipe)
// indexes a draw's tessellation output with 16 bits: past 65,535 vertices per instance it
// connects the wrong vertices and loses strands, by draw order (measured: 524 patches of 5 x 25
// vertices draw every strand, 525 do not). So the hair pass splits its patches into draws of at
// most this many vertices, on every device (a few draws more cost nothing measurable).
GPU_CONST uint kMaxTessVerticesPerDraw = 65535u;

// Bindings of the hair pass (one push-descriptor set).
GPU_CONST uint kHairBindingFrame = 0;     // uniform FrameParams
GPU_CONST uint kHairBindingSim = 1;       // uniform SimParams (colliders for multi-strand correction)
GPU_CONST uint kHairBindingPositions = 2; // the solver's positions (interleaved slots, sim.h)
GPU_CONST uint kHairBindingTriangles = 3; // uvec4 per guide: the guide and its two neighbours
// 4..7: the light's maps (shared/shadows.h kBinding*)
GPU_CONST uint kHairBindingOitHeads = 8;     // uint per pixel: the first node of its list
GPU_CONST uint kHairBindingOitNodes = 9;     // OitNode pool
GPU_CONST uint kHairBindingOitCounters = 10; // OitCounters
GPU_CONST uint kHairBindingLut = 11;         // sampler2DArray: the lookup mode's M and N tables (hair_shading.h)

GPU_CONST uint kInterpolationSingle = 0u;
GPU_CONST uint kInterpolationMulti = 1u;
GPU_CONST uint kInterpolationMixed = 2u; // alternate strands single / multi

// Push constants of the hair pass.
struct HairPush {
    uint guideCount;
    uint verticesPerStrand; // V of the guides
    uint strandsPerGuide;   // S as asked (instances cover it in chunks of up to 64)
    uint divisions;         // D segments per strand as asked (patches along the strand cover it)
    uint lengthChunks;      // patches along each strand: ceil(D / 64)
    uint strandsPerPatch;   // lines a patch holds (<= 64, and <= max patch vertices / (divisions + 1))
    uint interpolation;     // kInterpolation*
    float clumpRadius;      // single-strand disc radius, asset units
    float deviation;        // strength of random deviations, asset units
    float width;            // strand width at the root, asset units
    float lodStrands;       // strands per guide drawn after LOD (continuous, <= S)
    float lodWidthScale;    // width multiplier from LOD (keeps coverage as strands thin out)
    float minPixelWidth;    // ribbons narrower than this are widened, alpha scaled by coverage
    uint reverseOrder;      // 1: draw guides and strand chunks last to first (order-independence tests)
    float coilRadius;       // render-time coil's helix radius, asset units (0: none; coilOffset)
    float coilFrequency;    // its turns per asset unit of length along the strand
    vec4 reserved0;         // (free: the hair's look lives in FrameParams.hair)
    vec3 reserved1;
    uint samples; // MSAA samples of the target (for the coverage mask)
};

// ---- Curves -----------------------------------------------------------------------------------

struct Bezier {
    vec3 b0;
    vec3 b1;
    vec3 b2;
    vec3 b3;
};

// Segment i..i+1 of a polyline as a cubic Bezier with Catmull-Rom tangents (p_{i+1} - p_{i-1}) / 2,
// so neighbouring segments share position and tangent at their joint (C1). Ends repeat the end point.
GPU_FN Bezier catmullRomBezier(vec3 pPrev, vec3 p0, vec3 p1, vec3 pNext)
{
    Bezier b;
    b.b0 = p0;
    b.b1 = p0 + (p1 - pPrev) / 6.0f;
    b.b2 = p1 - (pNext - p0) / 6.0f;
    b.b3 = p1;
    return b;
}

GPU_FN vec3 bezierPoint(Bezier b, float u)
{
    float v = 1.0f - u;
    return v * v * v * b.b0 + 3.0f * v * v * u * b.b1 + 3.0f * v * u * u * b.b2 + u * u * u * b.b3;
}

GPU_FN vec3 bezierTangent(Bezier b, float u)
{
    float v = 1.0f - u;
    return 3.0f * v * v * (b.b1 - b.b0) + 6.0f * v * u * (b.b2 - b.b1) + 3.0f * u * u * (b.b3 - b.b2);
}

// A point of a curve and its (unnormalized) tangent.
struct CurvePoint {
    vec3 position;
    vec3 tangent;
};

// The guide's C1 curve at u in [0, 1] within segment p0..p1 (pPrev and pNext its neighbours).
GPU_FN CurvePoint guideCurvePoint(vec3 pPrev, vec3 p0, vec3 p1, vec3 pNext, float u)
{
    Bezier b = catmullRomBezier(pPrev, p0, p1, pNext);
    CurvePoint c;
    c.position = bezierPoint(b, u);
    c.tangent = bezierTangent(b, u);
    return c;
}

// Which segment a parameter t in [0, 1] falls in, and where in it.
GPU_FN uint curveSegment(float t, uint V)
{
    return min(uint(t * float(V - 1u)), V - 2u);
}

GPU_FN float curveLocal(float t, uint V, uint segment)
{
    return t * float(V - 1u) - float(segment);
}

// ---- Strands around and between guides ---------------------------------------------------------

// Two unit vectors perpendicular to the unit tangent t (a frame for offsets around the strand):
// the x and z axes turned by the least rotation taking straight down (-y, where hair mostly points)
// onto t (Rodrigues' formula with k = -y x t, cos = -t.y). The frame turns continuously with the
// tangent everywhere but at t = +y, a single direction (a frame switching its helper axis at a
// threshold flipped back and forth along hanging strands and drew their offsets as zigzags).
GPU_FN mat3 strandFrame(vec3 t)
{
    float c = -t.y;
    float inv = 1.0f / max(1.0f + c, 1e-4f);
    vec3 e1 = vec3(c + t.z * t.z * inv, t.x, -t.z * t.x * inv);
    vec3 e2 = vec3(-t.x * t.z * inv, t.z, c + t.x * t.x * inv);
    return mat3(t, normalize(e1), normalize(e2));
}

// The clump profile: zero at the root (strands grow from one follicle region), full a fifth of
// the way down, narrowing again toward the tip (wet-look clumps); in [0, 1].
GPU_FN float clumpTaper(float t)
{
    float grow = clamp(t / 0.2f, 0.0f, 1.0f);
    return grow * grow * (3.0f - 2.0f * grow) * (1.0f - 0.6f * t);
}

// Strand s of a guide: its polar position in the clump disc, uniform over the disc's area
// (strand 0 is the guide itself).
GPU_FN vec2 discOffset(uint guide, uint s)
{
    if (s == 0u)
        return vec2(0.0f);
    uint h = hashUint(guide * 9781u + s * 6271u + 17u);
    float r = sqrt(hashToUnit(h));
    float a = 6.2831853f * hashToUnit(h ^ 0x68E31DA4u);
    return vec2(r * cos(a), r * sin(a));
}

// Barycentric weights of strand s between three guides, uniform over the triangle; they sum to 1.
GPU_FN vec3 triangleWeights(uint guide, uint s)
{
    uint h = hashUint(guide * 7919u + s * 104729u + 3u);
    float r1 = sqrt(hashToUnit(h));
    float r2 = hashToUnit(h ^ 0xB5297A4Du);
    return vec3(1.0f - r1, r1 * (1.0f - r2), r1 * r2);
}

// One collider's part in keeping a generated strand point outside the head: moved radially onto
// the ellipsoid's surface when inside (the hair pass applies every collider in turn).
GPU_FN vec3 pushOutOfCollider(Ellipsoid e, mat4 head, vec3 p)
{
    Contact k = headColliderContact(e, head, p, 0.0f);
    return k.depth > 0.0f ? p + k.depth * k.normal : p;
}

// Whether strand s uses multi-strand interpolation under the chosen mode.
GPU_FN bool strandIsMulti(uint interpolation, uint s)
{
    if (interpolation == kInterpolationMulti)
        return s != 0u;
    if (interpolation == kInterpolationMixed)
        return (s & 1u) == 1u;
    return false;
}

// Random deviations (Rapp 2014): with probability 1/2 a strand strays from its guide along one of
// five profiles over t: a Gaussian near the root (strays), two Gaussians lower down, an exponential
// at the tip (flyaways) and a gradual one (drift). Returns the profile's weight at t (0 for strands
// that do not deviate); the direction comes from deviationDirection(). Each profile rises over at
// least a fifth of the strand, so the default 24 divisions draw it with five points or more (bumps a
// tenth of the strand wide were drawn with two or three: a triangle, scribbles round the outline).
GPU_FN float deviationProfile(uint guide, uint s, float t)
{
    uint h = hashUint(guide * 3571u + s * 2903u + 101u);
    if (hashToUnit(h) < 0.5f)
        return 0.0f;
    uint kind = uint(5.0f * hashToUnit(h ^ 0x1B873593u)) % 5u;
    if (kind == 0u)
        return exp(-pow((t - 0.2f) / 0.12f, 2.0f));
    if (kind == 1u)
        return exp(-pow((t - 0.45f) / 0.14f, 2.0f));
    if (kind == 2u)
        return exp(-pow((t - 0.75f) / 0.14f, 2.0f));
    if (kind == 3u)
        return exp(5.0f * (t - 1.0f));
    return exp(3.0f * (t - 1.0f)) * t;
}

// The deviation's direction in the strand's perpendicular plane, as an angle.
GPU_FN float deviationAngle(uint guide, uint s)
{
    return 6.2831853f * hashToUnit(hashUint(guide * 613u + s * 7727u + 55u));
}

// ---- Render-time coils --------------------------------------------------------------------------
// Tight coils (afro-textured hair: 4 to 15 mm a turn) are finer than a guide's simulated vertices
// can hold (the afro's 32 over 13 cm, 4 mm apart), so the drawing adds them: a helix about the
// placed strand, `radius` around it (asset units), `frequency` turns per asset unit of length along
// it, each strand at a phase of its own (coils of one clump do not turn in step). Lengths along the
// strand are t x the guide's rest length (guides keep their length within a fraction of a percent).
// A turn drawn with fewer than about 5 of the strand's D + 1 points is a zigzag, not a coil, so the
// helix fades out between 6 and 4 points a turn (set the divisions with the frequency); and it
// grows in over its first turn from the root, so the root stays on its follicle.
struct CoilShape {
    float radius;  // the helix's radius at t, asset units (0: no coil here)
    float angular; // its phase's rate, radians per asset unit of length
    float phase;   // its phase at t, radians
};

// smoothstep, which the C++ prelude does not map.
GPU_FN float coilFade(float e0, float e1, float x)
{
    float u = clamp((x - e0) / (e1 - e0), 0.0f, 1.0f);
    return u * u * (3.0f - 2.0f * u);
}

GPU_FN CoilShape coilAt(uint guide, uint s, float t, float radius, float frequency, float guideLength, uint divisions)
{
    CoilShape c;
    float turns = frequency * guideLength;
    c.angular = 6.2831853f * frequency;
    c.phase = 6.2831853f * (turns * t + hashToUnit(hashUint(guide * 2971u + s * 5087u + 29u)));
    c.radius = 0.0f;
    if (radius > 0.0f && turns > 0.0f) {
        float pointsPerTurn = float(divisions) / turns;
        c.radius = radius * coilFade(4.0f, 6.0f, pointsPerTurn) * coilFade(0.0f, 1.0f, turns * t);
    }
    return c;
}

// The coil's offset from the strand's point, in the strand's frame f (strandFrame: f[1], f[2]
// perpendicular to the tangent).
GPU_FN vec3 coilOffset(CoilShape c, mat3 f)
{
    return c.radius * (cos(c.phase) * f[1] + sin(c.phase) * f[2]);
}

// The coiled strand's unit tangent: the strand's T plus the helix's turn, d(offset)/ds =
// radius x angular x (-sin f1 + cos f2) (the frame's own turn and the radius' fade left out), so
// the coils are shaded as coils, their highlights turning with them.
GPU_FN vec3 coilTangent(CoilShape c, mat3 f)
{
    vec3 turn = c.radius * c.angular * (-sin(c.phase) * f[1] + cos(c.phase) * f[2]);
    return normalize(f[0] + turn);
}

// Point t of strand s of `guide`, before it is pushed out of the colliders: `g` is the guide's curve
// at t, `g1` and `g2` its two neighbours' (read only by multi-strand interpolation). A multi strand
// blends the three with barycentric weights; a single strand is offset in the guide's clump disc;
// then the random deviation, then the render-time coil (coilAt: `coilRadius` around, at most a
// fifteenth of the guide's length, `coilFrequency` turns per unit length, drawn with `divisions`
// segments). A short guide (`guideLength`, its rest length) takes a clump disc of at most a
// fifteenth of its length and a deviation of at most a twelfth (a crop's 5 cm strands under the
// 1 cm disc and 1.2 cm deviations for long hair were drawn as fuzz). Returns the position and the
// unit tangent. The tessellation path (hair.tese) and the compute path (strands_generate.comp)
// both place their strands with this.
GPU_FN CurvePoint placeStrandPoint(CurvePoint g, CurvePoint g1, CurvePoint g2, uint guide, uint s, float t,
                                   uint interpolation, float clumpRadius, float deviation, float guideLength,
                                   float coilRadius, float coilFrequency, uint divisions)
{
    clumpRadius = min(clumpRadius, guideLength / 15.0f);
    deviation = min(deviation, guideLength / 12.0f);
    vec3 p = g.position;
    vec3 tangent = g.tangent;
    bool multi = strandIsMulti(interpolation, s);
    if (multi) {
        vec3 w = triangleWeights(guide, s);
        p = w.x * p + w.y * g1.position + w.z * g2.position;
        tangent = w.x * tangent + w.y * g1.tangent + w.z * g2.tangent;
    }
    vec3 T = normalize(tangent);
    mat3 f = strandFrame(T);
    if (!multi) {
        vec2 d = discOffset(guide, s);
        p += clumpRadius * clumpTaper(t) * (d.x * f[1] + d.y * f[2]);
    }
    float a = deviationAngle(guide, s);
    p += deviation * deviationProfile(guide, s, t) * (cos(a) * f[1] + sin(a) * f[2]);
    CoilShape coil = coilAt(guide, s, t, min(coilRadius, guideLength / 15.0f), coilFrequency, guideLength, divisions);
    CurvePoint placed;
    placed.position = p + coilOffset(coil, f);
    placed.tangent = coil.radius > 0.0f ? coilTangent(coil, f) : T;
    return placed;
}

// ---- Drawn strands' own lengths ----------------------------------------------------------------
// Hair around a guide is not cut to one length: strand s of a guide is drawn along the first
// strandLengthFraction() of its guide's curve, cut from the tip by a share uniform in [0, jitter]
// from the strand's own hash (strand_length_jitter; 0: every strand as long as its guide), so a
// clump's tips thin out toward its end instead of stopping together. Its D + 1 points stay evenly
// spread over what is left (the strand's own t, which its width and shading read, still runs 0..1):
// point i lies at the guide's parameter i / D x the fraction (strandGuideParameter).
GPU_FN float strandLengthFraction(uint guide, uint s, float jitter)
{
    return 1.0f - jitter * hashToUnit(hashUint(guide * 4517u + s * 8263u + 71u));
}

// Where point t of a strand (its own t, 0..1 root to tip) lies along its guide's curve.
GPU_FN float strandGuideParameter(float t, float lengthFraction)
{
    return t * lengthFraction;
}

// The sample at or below x / D (x in [0, D]) of a curve sampled at t = k / D: curveBetweenSamples
// blends it with the next at f = x - k.
GPU_FN uint curveSampleBelow(float x, uint D)
{
    return min(uint(max(x, 0.0f)), D - 1u);
}

// The guide's curve between two of its points sampled D apart (a at t = k / D, b at (k + 1) / D,
// as strands_curves.comp samples it), at f in [0, 1] of the way: the cubic Hermite of the two
// points and their tangents (guideCurvePoint's, per unit of a guide segment: `segmentsPerSample` =
// (V - 1) / D of them per sample step), the tangent mixed. This is how the compute path finds a
// trimmed strand's points between the samples: within about 0.05% of the guide's length of the
// curve itself, which the tessellation path evaluates (the guide's segments join with C1, not C2),
// and exactly a and b at f = 0 and 1 (so a strand of its guide's length is drawn as before).
GPU_FN CurvePoint curveBetweenSamples(CurvePoint a, CurvePoint b, float f, float segmentsPerSample)
{
    if (f <= 0.0f)
        return a;
    if (f >= 1.0f)
        return b;
    float f2 = f * f;
    float f3 = f2 * f;
    vec3 m0 = a.tangent * segmentsPerSample;
    vec3 m1 = b.tangent * segmentsPerSample;
    CurvePoint c;
    c.position = (2.0f * f3 - 3.0f * f2 + 1.0f) * a.position + (f3 - 2.0f * f2 + f) * m0 +
                 (3.0f * f2 - 2.0f * f3) * b.position + (f3 - f2) * m1;
    c.tangent = a.tangent * (1.0f - f) + b.tangent * f;
    return c;
}

// The drawn width of a strand at t (asset units): tapering to 15% at the tip.
GPU_FN float strandWidthAt(float rootWidth, float t)
{
    return rootWidth * (1.0f - 0.85f * t);
}

// A guide's shape as its neighbour triangle's w carries it (physics/strand_set.h guideTriangles): its
// rest length and the width its strands are drawn at, as a share of the `width` setting (finer at
// the hairline), in two halves (11 bits of mantissa: a length within 0.05%).
GPU_FN uint packGuideShape(float restLength, float widthScale)
{
    return packHalf2x16(vec2(restLength, widthScale));
}
GPU_FN float guideLength(uint shape)
{
    return unpackHalf2x16(shape).x;
}
GPU_FN float guideWidthScale(uint shape)
{
    return unpackHalf2x16(shape).y;
}

// ---- Level of detail ----------------------------------------------------------------------------

// How much of strand s is drawn when lodStrands strands per guide are wanted: whole strands below
// the count, the next one fading in with the fraction (so the count changes without popping).
GPU_FN float lodAlpha(uint s, float lodStrands)
{
    return clamp(lodStrands - float(s), 0.0f, 1.0f);
}

// ---- Coverage ----------------------------------------------------------------------------------

// The MSAA samples a hair fragment covers: round(coverage x samples) of them (rounded up or down
// by a hash, so the average is right), starting at a sample chosen by the strand. Unlike
// alpha-to-coverage, whose mask depends on alpha alone, overlapping thin strands then fill
// different samples and their coverage adds up. Deterministic: a hash of strand and pixel.
GPU_FN uint coverageMask(float coverage, uint samples, uint strand, uint pixelHash)
{
    float wanted = clamp(coverage, 0.0f, 1.0f) * float(samples);
    uint k = uint(wanted);
    if (hashToUnit(hashUint(strand * 2246822519u + pixelHash)) < wanted - float(k))
        k += 1u;
    if (k == 0u)
        return 0u;
    uint all = samples >= 32u ? 0xFFFFFFFFu : (1u << samples) - 1u;
    uint run = k >= 32u ? 0xFFFFFFFFu : (1u << k) - 1u;
    uint rot = hashUint(strand * 3266489917u + 7u) % samples;
    uint mask = rot == 0u ? run : ((run << rot) | (run >> (samples - rot)));
    return mask & all;
}

GPU_NAMESPACE_END

#ifdef __cplusplus
// The layouts GLSL gives these blocks, checked where they are defined (C++ only).
static_assert(sizeof(gpu::HairPush) == 96, "HairPush must fit the 128 bytes of push constants every device has");
#endif

#endif
