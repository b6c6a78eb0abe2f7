// physics/scalp.h: where hair grows on a head, as a smooth field over its surface rather than a
// set of triangles. The head's scalp rule (a plane over the hairline and the face's direction,
// assets/head.h) becomes a signed distance in head units, positive on the scalp, evaluated at any
// point with its interpolated normal; the root density rises from 0 to 1 across a band inside the
// hairline, so hair thins over its last centimetre as real hairlines do. Roots are blue noise at that
// density, anywhere inside triangles; the head's painted scalp follows the same field.
#pragma once

#include "assets/head.h"

#include <cstdint>
#include <functional>
#include <vector>

namespace wisp {

struct ScalpField {
    ScalpRule rule;
    float bandWidth = 0.012f; // head units: the density goes from 0 (hairline) to 1 over this
    float faceRadius = 0.09f; // head units: turns the face rule's angle into a distance (the skull's radius)

    // Signed distance inside the hairline (head units; > 0 on the scalp): the smaller of the height
    // above the hairline plane and the face rule's margin times faceRadius, blended smoothly where
    // they meet (a polynomial smooth minimum, Quilez 2013) so the hairline has no corner.
    float distance(const glm::vec3& p, const glm::vec3& n) const;
    // Root density at a point, 0..1: a smoothstep of distance() over the band.
    float density(const glm::vec3& p, const glm::vec3& n) const;
    // How strongly the head is painted under the hair, 0..1: the density moved kPaintLead of a band
    // outward, so the skin is painted where roots are dense (partings read as partings) and fades
    // out from inside the band to just beyond the hairline, never with a hard border. (Moved a whole
    // band out, the paint ran a centimetre down the forehead: a crop combed back showed it as a
    // dark rim under the hair, a helmet's edge.)
    float paint(const glm::vec3& p, const glm::vec3& n) const;
    static constexpr float kPaintLead = 0.25f;
};

// The scalp field of a head under its rule, with the band scaled to its units.
ScalpField makeScalpField(const ScalpRule& rule, float unitsPerMetre, float bandMetres, float skullRadius);

struct RootSample {
    glm::vec3 position;
    glm::vec3 normal;
    uint32_t triangle;
    float density = 1.0f; // the scalp field's density where the root is (1 for plain sampling)
};

// Area-weighted samples on the given triangles; deterministic for a seed (blue noise with
// `poissonDisk`: dart throwing, Cook 1986).
std::vector<RootSample> sampleRoots(const Mesh& mesh, const std::vector<uint32_t>& triangles, uint32_t count,
                                    bool poissonDisk, uint32_t seed);

// A row of roots along a curve on the scalp: where `level` (a signed function of the position, in
// head units) is zero on the head, where `keep` holds; its roots are ordered along the curve by
// their angle about `axis` through the head's centre. A parting's two edges are rows a little
// apart (planes), and so are the bangs' (cones about the bangs' axis), so the scalp shows as a thin
// line between them rather than as the gap blue noise leaves between two sides combed apart.
struct RootRow {
    std::function<float(const glm::vec3&)> level;
    glm::vec3 axis{1.0f, 0.0f, 0.0f};
    std::function<bool(const glm::vec3&)> keep;
};

// The row where the plane through `point` with unit normal `normal` cuts the head.
RootRow planeRow(const glm::vec3& point, const glm::vec3& normal, std::function<bool(const glm::vec3&)> keep = {});

// The smallest distance blue-noise roots keep between them (the dart radius, head units) when
// `count` of them cover `area` (head units squared).
float rootSpacing(double area, uint32_t count);

// The scalp's area at full density (each triangle the field reaches weighted by its density).
double scalpArea(const Mesh& mesh, const ScalpField& field);

// `count` roots over the head at the field's density: first the `rows`' roots (`rowSpacing` dart
// radii apart along each row, inside the hairline; at most a quarter of `count`), then candidates
// uniform over the area of every triangle the field reaches, kept with probability density() (so
// the band is sparser), kept apart by dart throwing (blue noise) when `poissonDisk`. Throws
// UserError when the field holds no area (a head with no usable scalp).
std::vector<RootSample> sampleScalpRoots(const Mesh& mesh, const ScalpField& field, uint32_t count, bool poissonDisk,
                                         uint32_t seed, const std::vector<RootRow>& rows = {}, float rowSpacing = 1.5f);

// The painted scalp of each head vertex (ScalpField::paint at the vertex and its normal).
std::vector<float> scalpPaint(const Mesh& mesh, const ScalpField& field);

} // namespace wisp
