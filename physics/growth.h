// physics/growth.h: the groom generator. Guide strands grown on any head the way artists' groom
// tools build hair (Blender's hair node assets, Houdini's groom SOPs, XGen's modifiers), as ordered,
// seeded steps:
//   1. roots: blue noise at the scalp field's density (physics/scalp.h), thinning over the hairline;
//   2. flow: a combing field on the scalp (parting, crown whorl, fall back or forward for bangs);
//      each strand leaves the scalp near tangent along it with a little root lift, then falls under
//      gravity, sliding over the head's colliders, layered outward the farther it has run;
//   3. length and trim: a mean length with variation, shorter at the hairline, cut at a trim line;
//   4. clumps: strands gather toward clump centres toward the tips;
//   5. curl and wave: a helix around the strand and a wave in the hair's layer, with randomness;
//   6. frizz and noise, stronger toward the tips, and a few flyaways;
// then kept outside the colliders and resampled to V vertices of equal length. Named styles
// (physics/hair_style.h) are sets of these parameters. Everything is deterministic for a seed.
#pragma once

#include "assets/head.h"
#include "physics/scalp.h"
#include "physics/strand_set.h"

#include <vector>

namespace wisp {

// The most guide strands Wisp simulates, grown or loaded (2e6 x 64 vertices is 10 GB of solver state).
inline constexpr uint32_t kMaxGuides = 2'000'000;

enum class Parting { None, Centre, Side };

// Lengths are in metres, scaled by the head's units. The defaults are the bob (physics/hair_style.h).
struct GrowthSettings {
    uint32_t guides = 2200;          // guide strands
    uint32_t verticesPerStrand = 16; // V
    uint32_t seed = 1;
    bool poissonDisk = true; // blue-noise roots (else plain area-weighted)
    // 1. Scalp
    float hairlineBandMetres = 0.012f; // the density rises from 0 to 1 over this inside the hairline
    // 2. Flow
    Parting parting = Parting::Side;
    float partingOffsetMetres = 0.03f; // a side parting's distance from the middle (+: the head's left, +x)
    float partingSweep = 1.0f;         // how strongly the hair is combed away from the parting, 0..2
    float fallBack = 0.6f;             // how far the hair on top is combed toward the back, 0..2
    float crownWhorl = 0.6f;           // the swirl around the crown, 0..1
    float bangs = 0.0f;                // how much of the front is combed forward over the forehead, 0..1
    float bangsLengthMetres = 0.09f;   // the length of the hair combed forward (bangs are cut short)
    float rootLiftDeg = 12.0f;         // angle above the scalp a strand leaves at
    float styleGravity = 1.0f;         // how fast strands turn down once they leave the scalp, 0..4
    float volumeMetres = 0.012f;       // how far a strand lies off the head once it has run a head's length
    // 3. Length and trim
    float lengthMetres = 0.3f;       // mean strand length before the trim
    float lengthVariation = 0.1f;    // relative spread of lengths
    float trimLevelMetres = 0.19f;   // strands are cut this far below the head's top (0: no trim)
    float trimSlope = 0.35f;         // the trim line drops this much per unit toward the face (an A-line bob)
    float trimJitterMetres = 0.016f; // the trim line's spread (trimJitter)
    float hairlineLength = 0.5f;     // a hair at the very hairline is this share of the length
    float hairlineWidth = 0.4f;      // and is drawn this share of the `width` setting wide (finer)
    // 4. Clumps
    float clumpSizeMetres = 0.012f; // spacing of the clump centres (0: no clumps)
    float clumpStrength = 0.45f;    // how far a strand's tip gathers to its clump's centre, 0..1
    float clumpShape = 1.5f;        // profile exponent along the strand: higher gathers later, 0.2..6
    // 5. Curl and wave
    float curlRadiusMetres = 0.0f;  // helix radius (0: no curl)
    float curlTurns = 3.0f;         // helix turns along a strand of the mean length
    float curlRandomness = 0.25f;   // per-strand spread of the curl's radius and frequency, 0..1
    float waveMetres = 0.0f;        // wave amplitude in the hair's layer (0: no wave)
    float waveLengthMetres = 0.08f; // wavelength along the strand
    // 6. Frizz and flyaways
    float frizzMetres = 0.002f; // noise amplitude at the tips (grows as t^2 from the root)
    float flyaways = 0.01f;     // share of strands that stray from the hair's surface, 0..0.2
    // The shape constraints of the grown part (PartSettings): how stiffly it keeps its style.
    float globalStiffness = 0.008f;
    float localStiffness = 0.12f;

    bool operator==(const GrowthSettings&) const = default;
};

// Each step on its own, for tests and for reading: these are what growGuides runs, in order.
namespace groom {

// The head's frame for the flow: its centre (the skull's), crown and the hair's parting line.
struct HeadFrame {
    glm::vec3 centre{0.0f};    // the skull's centre, head space
    glm::vec3 crown{0.0f};     // the crown (the whorl's centre): the scalp's top toward the back
    float skullRadius = 0.09f; // head units
    float top = 0.25f;         // the head's highest point (y)
    float unitsPerMetre = 1.0f;
};

// A parting's line: x in head space (GrowthSettings::parting, partingOffsetMetres).
float partingX(const GrowthSettings& s, const HeadFrame& head);

// How much of the parting's sweep reaches a point, 0..1: from a little behind the crown forward,
// on the top of the head.
float partingReach(const HeadFrame& head, const glm::vec3& p);

// The bangs' edge: where the front of the scalp combed forward meets the rest. A point's side of
// it: roughly its distance on the head from the edge (head units, > 0 in front): the angle about
// the skull's centre from the cone whose axis points forward and a little up, times the skull's
// radius. Hair within a few millimetres of the edge is combed half one way, half the other.
float bangsEdgeDistance(const HeadFrame& head, const glm::vec3& p);
// How much a point is combed forward for bangs (0..1, times GrowthSettings::bangs): a smoothstep
// over 3 mm either side of the edge (a strand half combed forward at full length would hang over
// the face, and a wide blend lays strands sideways along the edge).
float bangsWeight(const GrowthSettings& s, const HeadFrame& head, const glm::vec3& p);

// The combing direction at a root: a unit vector in the tangent plane of `n`.
glm::vec3 flowDirection(const GrowthSettings& s, const HeadFrame& head, const glm::vec3& p, const glm::vec3& n);

// A strand's centreline grown from a root along the flow, under gravity, over the colliders, in
// steps of `step` (head units) to `length`: a dense polyline.
std::vector<glm::vec3> growCentreline(const GrowthSettings& s, const HeadFrame& head,
                                      const std::vector<gpu::Ellipsoid>& colliders, const RootSample& root,
                                      float length, float step);

// The trim line's offset for a strand from `root` (head units, within +-trimJitterMetres): half a
// slow wave along the hem (value noise over the angle about the head's vertical axis, about ten
// features around the head, so a bob's back is cut blunt but not ruled), half `random` (-1..1).
float trimJitter(const GrowthSettings& s, const HeadFrame& head, const glm::vec3& root, float random);

// The polyline cut where it first falls below the trim line (never shorter than `shortest`).
void trim(std::vector<glm::vec3>& points, const GrowthSettings& s, const HeadFrame& head, float jitter, float shortest);

// Strand `points` pulled toward its clump centre's polyline `centre` (the same share of the length
// at each point): by strength * t^shape at t along the strand.
void clump(std::vector<glm::vec3>& points, const std::vector<glm::vec3>& centre, float strength, float shape);

// A helix of `radius` and `turns` around the polyline (parallel-transport frame), starting at
// `phase`, its radius growing in over the first `rampLength` from the root.
void curl(std::vector<glm::vec3>& points, float radius, float turns, float phase, float rampLength);

// A wave of `amplitude` and `wavelength` across the polyline along `side` (kept perpendicular).
void wave(std::vector<glm::vec3>& points, const glm::vec3& side, float amplitude, float wavelength, float phase);

// Smooth noise of `amplitude` at the tip, t^2 from the root, `scale` its feature length.
void frizz(std::vector<glm::vec3>& points, float amplitude, float scale, uint32_t seed);

// Points moved out of the colliders (with `clearance`) and put back at their parents' distance
// (follow-the-leader), root first. Within `emergeLength` of the root a point may be as deep as the
// root itself is (roots lie inside the colliders), the allowance fading along that length.
void keepOutside(std::vector<glm::vec3>& points, const std::vector<gpu::Ellipsoid>& colliders, float clearance,
                 float emergeLength);

// The polyline resampled to `count` points equally spaced along it.
std::vector<glm::vec3> resample(const std::vector<glm::vec3>& points, uint32_t count);

float polylineLength(const std::vector<glm::vec3>& points);

} // namespace groom

// Throws UserError for parameters that contradict each other (more curl turns than the vertices
// can hold, a trim at the top of the head).
void checkGrowth(const GrowthSettings& settings);

// Grown strands shorter than this are rigid: they follow the head and are drawn, not simulated
// (GroomedHead::loaded.rigid counts them, and the commands report it). Twice the length a strand
// takes to come out of the colliders (the emergence, growth.cpp): a strand of 2 to 4 cm, pinned at
// its first two vertices, has too little length left to leave a collider that passes over it (the
// sphere swept through the hair, tests/test_physics_scenes.cpp, leaves such strands 1.7% of the
// head's diagonal inside it), so it follows the head instead.
inline constexpr float kRigidStrandMetres = 0.04f;

// Grows guides; `colliders` (head space) keep them off the head. The strand set also carries the
// head's painted scalp (StrandSet::scalpPaint) from the same field.
StrandSet growGuides(const Mesh& mesh, const ScalpRule& scalp, const std::vector<gpu::Ellipsoid>& colliders,
                     const GrowthSettings& settings, float unitsPerMetre);

} // namespace wisp
