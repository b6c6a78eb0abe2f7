// physics/colliders.h: the head's collision ellipsoids: conversion to the GPU form, the deepest
// penetration of a point, and the automatic fit for meshes that come without any.
#pragma once

#include "assets/head.h"
#include "physics/strand_set.h"
#include "shaders/shared/sim.h"

#include <string>
#include <vector>

namespace wisp {

gpu::Ellipsoid toGpu(const Ellipsoid& e);

// How far `p` (head space) lies inside the deepest collider; 0 when outside all.
float penetrationDepth(const std::vector<gpu::Ellipsoid>& colliders, const glm::vec3& p);

// Fits ellipsoids to a bust-like mesh with no description (y up, face toward +z), cut where the
// head narrows into the neck (assets/placement.h headRegion), not at fixed fractions of the height:
//  - "cranium": as wide and deep as the vertices in the top half of the head, as tall as it is
//    wide, its top at the mesh's top, then scaled uniformly so that 98% of the vertices above its
//    centre lie inside (inscribeColliders then pulls it inside the scalp);
//  - "neck": the vertices around the neck, fitted the same way to hold 90% of them;
//  - "shoulders" (a bust): everything below, fitted the same way but not scaled up.
std::vector<Ellipsoid> fitColliders(const Mesh& mesh);

// What makes `mesh` a poor head for colliders fitted to it, one line each (none for a head): it is
// inside-out (its signed volume is negative: its triangles face inward), or open on the upper half
// of its head (edges of one triangle only, as long in all as a quarter of its width: hair falls
// through), or the colliders fitted to it hold its scalp badly (measureColliderFit past the limits
// below: a mesh that is no head, such as a cube).
std::vector<std::string> fittedColliderWarnings(const Mesh& mesh, const std::vector<Ellipsoid>& colliders,
                                                const std::vector<uint32_t>& scalpTriangles);

// How well colliders hold a mesh's scalp, in shares of the mesh's bounding-box diagonal, its
// triangles sampled on a barycentric grid (not only at their corners):
//  - intrusion: the deepest a point of the scalp lies inside a collider (roots start there: the
//    solver pushes them out from the first step, and the hair stands off the mesh);
//  - exposed: the share of the scalp's area lying farther than `gap` outside every collider (hair
//    falls onto the mesh there and sinks into it: nothing stops it before the collider).
struct ColliderFit {
    float intrusion = 0.0f;
    float exposed = 0.0f;
};
ColliderFit measureColliderFit(const std::vector<Ellipsoid>& colliders, const Mesh& mesh,
                               const std::vector<uint32_t>& scalpTriangles, float gap);
// Fitted colliders leaving more than kFitExposedLimit of the scalp kFitExposedGap outside them all
// are said to hold it badly (a cube: 68% of its scalp; heads: at most 3%, Sintel's busts).
inline constexpr float kFitExposedGap = 0.05f;
inline constexpr float kFitExposedLimit = 0.10f;

// Hair grows from the scalp, so the scalp must lie outside every collider, or grown roots start
// inside one and the solver pushes their first segments against FTL from the first step (loose
// fitted colliders: penetration 4% of the diagonal on a scan head). Each collider shrinks
// (uniformly about its centre) until no point of the scalp triangles (their corners and points
// across them, as measureColliderFit samples them) lies deeper than `tolerance` inside it.
void inscribeColliders(std::vector<Ellipsoid>& colliders, const Mesh& mesh, const std::vector<uint32_t>& scalpTriangles,
                       float tolerance);
inline constexpr float kInscribedTolerance = 0.0025f; // of the head's bounding-box diagonal

// A styled groom's rest pose must start outside the colliders, or they fight its style: each
// collider shrinks (uniformly about its centre) until 99% of the strands' free rest vertices lie
// outside it (a percentile, so that a few strands tucked into the head do not collapse it).
void shrinkCollidersToRestPose(std::vector<Ellipsoid>& colliders, const StrandSet& strands);

// A scalp rule for a bare mesh, derived from the fitted cranium: above a plane a little below its
// centre, tilted so the hairline is higher at the front, excluding the face.
ScalpRule defaultScalpRule(const Ellipsoid& cranium);

// Scene scale in asset units per metre: from the description's units, else from the bust's size.
float unitsPerMetre(const Head& head);

} // namespace wisp
