// physics/growth.h: guide strands grown on the scalp of any head. Roots are sampled area-weighted
// over the scalp triangles (optionally Poisson-disk), from a fixed seed; each strand starts along
// the surface normal and bends under a styling gravity (the Meshuggah and Nalu recipe), kept
// outside the colliders as it grows, with optional curls.
#pragma once

#include "assets/head.h"
#include "physics/strands.h"

#include <vector>

namespace wisp {

// The most guide strands Wisp simulates, grown or loaded (2e6 x 64 vertices is 10 GB of solver state).
inline constexpr uint32_t kMaxGuides = 2'000'000;

struct GrowthSettings {
    uint32_t guides = 1000;          // number of guide strands
    uint32_t verticesPerStrand = 16; // V
    float lengthMetres = 0.24f;      // mean strand length (scaled by the head's units)
    float lengthVariation = 0.15f;   // relative spread of lengths
    float styleGravity = 1.0f;       // how fast strands bend down and outward as they grow
    float curlRadiusMetres = 0.0f;   // helix radius of curls, 0 = straight
    float curlTurns = 3.0f;          // helix turns along a strand
    bool poissonDisk = false;        // blue-noise roots instead of plain area-weighted
    uint32_t seed = 1;
};

struct RootSample {
    glm::vec3 position;
    glm::vec3 normal;
    uint32_t triangle;
};

// Area-weighted samples on the given triangles; deterministic for a seed.
std::vector<RootSample> sampleRoots(const Mesh& mesh, const std::vector<uint32_t>& triangles, uint32_t count,
                                    bool poissonDisk, uint32_t seed);

// Grows guides; `colliders` (head space) keep them out of the head.
StrandSet growGuides(const Mesh& mesh, const ScalpRule& scalp, const std::vector<gpu::Ellipsoid>& colliders,
                     const GrowthSettings& settings, float unitsPerMetre);

} // namespace wisp
