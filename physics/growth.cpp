// physics/growth.cpp: the groom generator's steps and growGuides, which runs them in order.
#include "physics/growth.h"

#include "core/error.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numeric>

namespace wisp {

namespace {

constexpr float kPi = 3.14159265f;

// A deterministic stream of uniform numbers in [0, 1) (PCG hash of a counter), identical on
// every platform, unlike std:: distributions.
struct Random {
    uint32_t state;
    float next() { return gpu::hashToUnit(state++ * 0x9E3779B9u + 0x7F4A7C15u); }
    float signedNext() { return 2.0f * next() - 1.0f; }
};

float smoothstep(float a, float b, float x)
{
    float t = std::clamp((x - a) / (b - a), 0.0f, 1.0f);
    return t * t * (3.0f - 2.0f * t);
}

glm::vec3 safeNormalize(const glm::vec3& v, const glm::vec3& fallback)
{
    float l = glm::length(v);
    return l > 1e-12f ? v / l : fallback;
}

// Any unit vector perpendicular to the unit vector t.
glm::vec3 perpendicular(const glm::vec3& t)
{
    return glm::normalize(glm::cross(t, std::abs(t.y) < 0.9f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0)));
}

// The nearest collider surface's outward normal at p (the collider p is deepest in, or nearest).
glm::vec3 surfaceNormal(const std::vector<gpu::Ellipsoid>& colliders, const glm::vec3& p, const glm::vec3& fallback,
                        float* height = nullptr)
{
    float best = -1e30f;
    glm::vec3 n = fallback;
    for (const gpu::Ellipsoid& e : colliders) {
        gpu::Contact c = gpu::ellipsoidContact(e, p, 0.0f);
        if (c.depth > best) {
            best = c.depth;
            // The ellipsoid's gradient direction (ellipsoidContact leaves the normal out outside it).
            glm::mat3 R(e.rotation);
            glm::vec3 local = glm::transpose(R) * (p - e.center);
            n = safeNormalize(R * (local / (e.radii * e.radii)), fallback);
        }
    }
    if (height)
        *height = -best; // above the nearest collider's surface (radially, as ellipsoidContact measures)
    return n;
}

// 1D value noise in [-1, 1] along x with smooth (smoothstep) interpolation, one lattice per seed.
float valueNoise(float x, uint32_t seed)
{
    float i = std::floor(x);
    float f = x - i;
    uint32_t k = uint32_t(int32_t(i));
    float a = 2.0f * gpu::hashToUnit(gpu::hashUint(k * 747796405u + seed)) - 1.0f;
    float b = 2.0f * gpu::hashToUnit(gpu::hashUint((k + 1u) * 747796405u + seed)) - 1.0f;
    return a + (b - a) * f * f * (3.0f - 2.0f * f);
}

// How far from the root a strand takes to come out of the colliders to its clearance.
constexpr float kEmergeMetres = 0.02f;

// The colliders' margin for a strand point `run` along from a root `rootDepth` inside them: as deep
// as the root at the root (the colliders are fitted inside the scalp, so roots lie inside them),
// rising smoothly (no slope at the root, so a strand leaves at its root lift) to `clearance` outside
// them over `emergeLength`.
float emergeMargin(float rootDepth, float clearance, float run, float emergeLength)
{
    return -rootDepth + (rootDepth + clearance) * smoothstep(0.0f, emergeLength, run);
}

// Arc length at each point of a polyline, from the root.
std::vector<float> arcLengths(const std::vector<glm::vec3>& points)
{
    std::vector<float> s(points.size(), 0.0f);
    for (size_t i = 1; i < points.size(); ++i)
        s[i] = s[i - 1] + glm::length(points[i] - points[i - 1]);
    return s;
}

} // namespace

namespace groom {

float partingX(const GrowthSettings& s, const HeadFrame& head)
{
    return head.centre.x + (s.parting == Parting::Side ? s.partingOffsetMetres * head.unitsPerMetre : 0.0f);
}

float partingReach(const HeadFrame& head, const glm::vec3& p)
{
    float R = head.skullRadius;
    return smoothstep(head.crown.z - 0.3f * R, head.crown.z + 0.2f * R, p.z) *
           smoothstep(head.centre.y + 0.2f * R, head.centre.y + 0.6f * R, p.y);
}

float bangsEdgeDistance(const HeadFrame& head, const glm::vec3& p)
{
    // The edge's cone: 51 degrees about the axis (its cosine 0.63, as the first bangs' blend's middle).
    const float edge = std::acos(0.63f);
    glm::vec3 dir = safeNormalize(p - head.centre, glm::vec3(0.0f, 0.0f, 1.0f));
    float angle = std::acos(std::clamp(glm::dot(dir, glm::normalize(glm::vec3(0.0f, 0.45f, 1.0f))), -1.0f, 1.0f));
    return (edge - angle) * head.skullRadius;
}

float bangsWeight(const GrowthSettings& s, const HeadFrame& head, const glm::vec3& p)
{
    float half = 0.003f * head.unitsPerMetre;
    return s.bangs * smoothstep(-half, half, bangsEdgeDistance(head, p));
}

glm::vec3 flowDirection(const GrowthSettings& s, const HeadFrame& head, const glm::vec3& p, const glm::vec3& n)
{
    const glm::vec3 down(0.0f, -1.0f, 0.0f), front(0.0f, 0.0f, 1.0f);
    float R = head.skullRadius;
    // Combed away from the face: from a point in front of the forehead, so hair at the front
    // hairline goes up and over, on top toward the back, and down behind the ears.
    glm::vec3 source = head.centre + glm::vec3(0.0f, 0.2f * R, 1.8f * R);
    glm::vec3 v = s.fallBack * safeNormalize(p - source, -front);
    // Gravity takes over below the top of the skull.
    float below = smoothstep(0.1f * R, 0.9f * R, head.centre.y + 0.5f * R - p.y);
    v += (0.35f + below) * down;
    // A parting: along the top, from the front hairline back to the crown, hair is combed away
    // from the line to either side.
    if (s.parting != Parting::None) {
        // Every strand goes to its own side, those at the line too (a dead band there laid strands
        // along the parting), the more the farther from it.
        float side = p.x - partingX(s, head);
        float sweep = s.partingSweep * partingReach(head, p) *
                      (0.6f + 0.4f * smoothstep(0.0f, 0.004f * head.unitsPerMetre, std::abs(side)));
        v += (side >= 0.0f ? 1.0f : -1.0f) * sweep * glm::vec3(1.0f, 0.0f, 0.0f);
    }
    // The crown whorl: around the crown, hair spirals outward (a clockwise whorl seen from above).
    glm::vec3 d = p - head.crown;
    float r = glm::length(d) / (0.45f * R);
    float whorl = s.crownWhorl * std::exp(-r * r);
    if (whorl > 1e-4f) {
        glm::vec3 radial = safeNormalize(d - glm::dot(d, n) * n, -front);
        glm::vec3 swirl = glm::cross(n, radial);
        v = glm::mix(v, glm::length(v) * safeNormalize(radial + 1.5f * swirl, radial), whorl);
    }
    // Bangs: the front of the scalp combed forward and down over the forehead.
    float bangs = bangsWeight(s, head, p);
    v = glm::mix(v, glm::length(v) * glm::normalize(front + 0.6f * down), bangs);
    glm::vec3 tangent = v - glm::dot(v, n) * n;
    return safeNormalize(tangent, perpendicular(n));
}

std::vector<glm::vec3> growCentreline(const GrowthSettings& s, const HeadFrame& head,
                                      const std::vector<gpu::Ellipsoid>& colliders, const RootSample& root,
                                      float length, float step)
{
    const glm::vec3 down(0.0f, -1.0f, 0.0f);
    // Hair at the hairline lies flatter than behind it (a lifted edge reads as a cap's rim).
    float lift = glm::radians(s.rootLiftDeg) * (0.35f + 0.65f * root.density);
    glm::vec3 flow = flowDirection(s, head, root.position, root.normal);
    glm::vec3 dir = glm::normalize(std::cos(lift) * flow + std::sin(lift) * root.normal);
    // The comb holds a strand to the flow over its first few centimetres; then gravity turns it down
    // over a bend length that styleGravity shortens. The hair lies in layers: a strand keeps farther
    // off the head the longer it has run over it (strands from the crown lie over those below).
    float combLength = 0.06f * head.unitsPerMetre;
    float bendLength = 0.05f * head.unitsPerMetre / std::max(s.styleGravity, 1e-3f);
    float baseClearance = 0.002f * head.unitsPerMetre;
    float layerLength = 2.0f * head.skullRadius;
    // Roots lie inside the colliders (they are fitted inside the scalp): see emergeMargin.
    float rootDepth = 0.0f;
    for (const gpu::Ellipsoid& e : colliders)
        rootDepth = std::max(rootDepth, gpu::ellipsoidContact(e, root.position, 0.0f).depth);
    float emergeLength = kEmergeMetres * head.unitsPerMetre;
    std::vector<glm::vec3> points{root.position};
    size_t steps = size_t(std::ceil(length / step));
    float h = length / float(std::max<size_t>(steps, 1));
    glm::vec3 p = root.position;
    float run = 0.0f;
    for (size_t i = 0; i < steps; ++i) {
        float height = 0.0f;
        glm::vec3 n = surfaceNormal(colliders, p, root.normal, &height);
        float comb = std::exp(-run / combLength);
        // The comb lays the hair along the head: where the head curves away under a strand (over the
        // forehead, at the crown) it is drawn back down toward its layer instead of flying off.
        float layer = baseClearance + s.volumeMetres * head.unitsPerMetre * std::min(run / layerLength, 1.0f);
        // (Hair lifted off the scalp on purpose, an afro's, stands out: the less lift, the more it lies.)
        float hug = std::clamp(1.0f - s.rootLiftDeg / 30.0f, 0.0f, 1.0f);
        float above = hug * std::clamp((height - layer) / (0.01f * head.unitsPerMetre), 0.0f, 1.0f);
        glm::vec3 combed = flowDirection(s, head, p, n) - above * n;
        glm::vec3 target = safeNormalize(comb * combed + (1.0f - comb) * down + 1e-3f * n, down);
        if (s.styleGravity > 0.0f)
            dir = glm::normalize(glm::mix(dir, target, std::min(1.0f, h / bendLength)));
        glm::vec3 next = p + h * dir;
        // Within the comb, a strand above its layer is laid down toward it (at most a third of a
        // step's length each step), past the emergence from the root.
        if (run > emergeLength && height > layer)
            next -= hug * comb * std::min(height - layer, h / 3.0f) * n;
        float clearance = emergeMargin(
            rootDepth, baseClearance + s.volumeMetres * head.unitsPerMetre * std::min(run / layerLength, 1.0f), run + h,
            emergeLength);
        for (int pass = 0; pass < 2; ++pass)
            for (const gpu::Ellipsoid& e : colliders) {
                gpu::Contact c = gpu::ellipsoidContact(e, next, clearance);
                if (c.depth > 0.0f)
                    next += c.depth * c.normal;
            }
        next = gpu::ftlProject(p, next, h);
        dir = safeNormalize(next - p, dir);
        p = next;
        run += h;
        points.push_back(p);
    }
    return points;
}

float trimJitter(const GrowthSettings& s, const HeadFrame& head, const glm::vec3& root, float random)
{
    // The angle from the back (the noise's seam is at the front, under the face, where no hem is).
    float around = std::atan2(root.x - head.centre.x, head.centre.z - root.z) / (2.0f * kPi) + 0.5f;
    float wave = valueNoise(10.0f * around, s.seed ^ 0x3C6EF372u);
    return 0.5f * s.trimJitterMetres * head.unitsPerMetre * (wave + std::clamp(random, -1.0f, 1.0f));
}

void trim(std::vector<glm::vec3>& points, const GrowthSettings& s, const HeadFrame& head, float jitter, float shortest)
{
    if (s.trimLevelMetres <= 0.0f || points.size() < 2)
        return;
    std::vector<float> arc = arcLengths(points);
    for (size_t i = 1; i < points.size(); ++i) {
        const glm::vec3& p = points[i];
        float line = head.top - s.trimLevelMetres * head.unitsPerMetre - s.trimSlope * (p.z - head.centre.z) + jitter;
        if (p.y < line && arc[i] >= shortest) {
            points.resize(i + 1);
            return;
        }
    }
}

void clump(std::vector<glm::vec3>& points, const std::vector<glm::vec3>& centre, float strength, float shape)
{
    if (strength <= 0.0f || centre.size() < 2 || points.size() < 2)
        return;
    std::vector<float> arc = arcLengths(points), centreArc = arcLengths(centre);
    float total = arc.back(), centreTotal = centreArc.back();
    size_t j = 0;
    for (size_t i = 1; i < points.size(); ++i) {
        float t = arc[i] / total;
        // The centre's point at the same share of its length.
        float target = t * centreTotal;
        while (j + 2 < centre.size() && centreArc[j + 1] < target)
            ++j;
        float span = std::max(centreArc[j + 1] - centreArc[j], 1e-12f);
        glm::vec3 c = glm::mix(centre[j], centre[j + 1], std::clamp((target - centreArc[j]) / span, 0.0f, 1.0f));
        points[i] = glm::mix(points[i], c, strength * std::pow(t, shape));
    }
}

void curl(std::vector<glm::vec3>& points, float radius, float turns, float phase, float rampLength)
{
    if (radius <= 0.0f || points.size() < 3)
        return;
    std::vector<float> arc = arcLengths(points);
    float total = arc.back();
    std::vector<glm::vec3> out = points;
    // Parallel transport of a normal along the centreline (no twist of its own, unlike a Frenet frame).
    glm::vec3 t = glm::normalize(points[1] - points[0]);
    glm::vec3 u = perpendicular(t);
    for (size_t i = 1; i < points.size(); ++i) {
        glm::vec3 tNext = safeNormalize(points[std::min(i + 1, points.size() - 1)] - points[i - 1], t);
        u = safeNormalize(u - glm::dot(u, tNext) * tNext, perpendicular(tNext));
        t = tNext;
        glm::vec3 w = glm::cross(t, u);
        float angle = phase + 2.0f * kPi * turns * arc[i] / total;
        float ramp = std::min(1.0f, arc[i] / std::max(rampLength, 1e-12f));
        out[i] = points[i] + radius * ramp * (std::cos(angle) * u + std::sin(angle) * w);
    }
    points = out;
}

void wave(std::vector<glm::vec3>& points, const glm::vec3& side, float amplitude, float wavelength, float phase)
{
    if (amplitude <= 0.0f || points.size() < 3)
        return;
    std::vector<float> arc = arcLengths(points);
    std::vector<glm::vec3> out = points;
    for (size_t i = 1; i < points.size(); ++i) {
        glm::vec3 t = safeNormalize(points[std::min(i + 1, points.size() - 1)] - points[i - 1], side);
        glm::vec3 across = safeNormalize(side - glm::dot(side, t) * t, perpendicular(t));
        float ramp = smoothstep(0.0f, 0.5f * wavelength, arc[i]);
        out[i] += amplitude * ramp * std::sin(2.0f * kPi * arc[i] / wavelength + phase) * across;
    }
    points = out;
}

void frizz(std::vector<glm::vec3>& points, float amplitude, float scale, uint32_t seed)
{
    if (amplitude <= 0.0f || points.size() < 2)
        return;
    std::vector<float> arc = arcLengths(points);
    float total = arc.back();
    for (size_t i = 1; i < points.size(); ++i) {
        float t = arc[i] / total;
        float x = arc[i] / scale;
        glm::vec3 noise(valueNoise(x, seed), valueNoise(x, seed ^ 0x5bd1e995u), valueNoise(x, seed ^ 0x27d4eb2fu));
        points[i] += amplitude * t * t * noise;
    }
}

void keepOutside(std::vector<glm::vec3>& points, const std::vector<gpu::Ellipsoid>& colliders, float clearance,
                 float emergeLength)
{
    std::vector<float> rest(points.size(), 0.0f);
    for (size_t i = 1; i < points.size(); ++i)
        rest[i] = glm::length(points[i] - points[i - 1]);
    float rootDepth = 0.0f;
    for (const gpu::Ellipsoid& e : colliders)
        rootDepth = std::max(rootDepth, gpu::ellipsoidContact(e, points[0], 0.0f).depth);
    float run = 0.0f;
    for (size_t i = 1; i < points.size(); ++i) {
        run += rest[i];
        float margin = emergeMargin(rootDepth, clearance, run, emergeLength);
        auto pushOut = [&](glm::vec3 p) {
            for (int pass = 0; pass < 2; ++pass)
                for (const gpu::Ellipsoid& e : colliders) {
                    gpu::Contact c = gpu::ellipsoidContact(e, p, margin);
                    if (c.depth > 0.0f)
                        p += c.depth * c.normal;
                }
            return p;
        };
        // Out, back to the parent's distance, and out again: where the strand dives into the head,
        // the point pushed out lands near its parent and the projection along them points inward;
        // the second push wins over the length (the rest pose defines the lengths).
        points[i] = pushOut(gpu::ftlProject(points[i - 1], pushOut(points[i]), rest[i]));
    }
}

std::vector<glm::vec3> resample(const std::vector<glm::vec3>& points, uint32_t count)
{
    std::vector<float> arc = arcLengths(points);
    float total = arc.back();
    std::vector<glm::vec3> out(count);
    size_t j = 0;
    for (uint32_t k = 0; k < count; ++k) {
        float target = total * float(k) / float(count - 1);
        while (j + 2 < points.size() && arc[j + 1] < target)
            ++j;
        float span = std::max(arc[j + 1] - arc[j], 1e-12f);
        out[k] = glm::mix(points[j], points[j + 1], std::clamp((target - arc[j]) / span, 0.0f, 1.0f));
    }
    return out;
}

float polylineLength(const std::vector<glm::vec3>& points)
{
    return arcLengths(points).back();
}

} // namespace groom

void checkGrowth(const GrowthSettings& s)
{
    // A helix needs about four vertices a turn to be a helix once resampled (fewer alias into zigzags).
    if (s.curlRadiusMetres > 0.0f) {
        float turns = s.curlTurns * (1.0f + 0.5f * s.curlRandomness);
        uint32_t needed = uint32_t(std::ceil(4.0f * turns)) + 1u;
        if (needed > s.verticesPerStrand) {
            char given[64];
            std::snprintf(given, sizeof(given), "curl_turns %g", double(s.curlTurns));
            std::string randomness;
            if (s.curlRandomness > 0.0f) {
                char r[64];
                std::snprintf(r, sizeof(r), " with curl_randomness %g", double(s.curlRandomness));
                randomness = r;
            }
            std::string head = std::string(given) + randomness + " needs about " + std::to_string(needed) +
                               " vertices a strand (4 a turn): ";
            if (needed <= kMaxVerticesPerStrand)
                throw UserError(head + "vertices_per_strand is " + std::to_string(s.verticesPerStrand) +
                                " (raise vertices_per_strand to " + std::to_string(needed) + " or lower curl_turns)");
            // Past what any strand holds: only fewer turns (or less randomness) can do.
            float most = float(kMaxVerticesPerStrand - 1) / 4.0f / (1.0f + 0.5f * s.curlRandomness);
            char advice[160];
            std::snprintf(advice, sizeof(advice),
                          "at most %u vertices a strand hold %.1f such turns (lower curl_turns%s)",
                          kMaxVerticesPerStrand, double(std::floor(most * 10.0f) / 10.0f),
                          s.curlRandomness > 0.0f ? " or curl_randomness" : "");
            throw UserError(head + advice);
        }
    }
    if (s.trimLevelMetres > 0.0f && s.trimLevelMetres < 0.02f)
        throw UserError("trim_level " + std::to_string(s.trimLevelMetres) +
                        " m cuts every strand at the top of the head (at least 0.02, or 0 for no trim)");
}

StrandSet growGuides(const Mesh& mesh, const ScalpRule& scalp, const std::vector<gpu::Ellipsoid>& colliders,
                     const GrowthSettings& s, float unitsPerMetre)
{
    checkGrowth(s);
    const float upm = unitsPerMetre;
    groom::HeadFrame head;
    head.unitsPerMetre = upm;
    Bounds bounds = mesh.bounds();
    head.top = bounds.max.y;
    if (!colliders.empty()) {
        head.centre = colliders.front().center;
        glm::vec3 r = colliders.front().radii;
        head.skullRadius = (r.x + r.y + r.z) / 3.0f;
    } else {
        head.centre = bounds.center();
        head.skullRadius = 0.09f * upm;
    }
    ScalpField field = makeScalpField(scalp, upm, s.hairlineBandMetres, head.skullRadius);
    // The crown: the scalp's top toward the back (where the whorl is), on the head where the field
    // is full.
    glm::vec3 crownward = glm::normalize(glm::vec3(0.0f, 1.0f, -0.6f));
    float crownReach = -1e30f;
    for (size_t v = 0; v < mesh.positions.size(); ++v) {
        float along = glm::dot(mesh.positions[v] - head.centre, crownward);
        if (field.density(mesh.positions[v], mesh.normals[v]) > 0.5f && along > crownReach) {
            crownReach = along;
            head.crown = mesh.positions[v];
        }
    }
    if (crownReach == -1e30f)
        head.crown = head.centre + head.skullRadius * crownward;
    // A parting's edges are rows of roots a little either side of its line, so the scalp shows
    // there as a thin straight line, not as the ragged gap blue noise leaves between two sides.
    std::vector<RootRow> rows;
    const float offset = 0.35f * rootSpacing(scalpArea(mesh, field), s.guides);
    if (s.parting != Parting::None && s.poissonDisk) {
        for (float sign : {-1.0f, 1.0f})
            rows.push_back(planeRow(glm::vec3(partingX(s, head) + sign * offset, 0.0f, 0.0f),
                                    glm::vec3(1.0f, 0.0f, 0.0f), [&s, &head](const glm::vec3& p) {
                                        return groom::partingReach(head, p) > 0.5f &&
                                               groom::bangsWeight(s, head, p) < 0.5f * s.bangs + 1e-3f;
                                    }));
    }
    // The bangs' edge likewise: a row just in front of it (combed forward) and one just behind
    // (combed back), the one behind leaving the parting's rows where they meet it.
    if (s.bangs > 0.0f && s.poissonDisk) {
        float line = s.parting != Parting::None ? partingX(s, head) : 1e30f;
        for (float sign : {-1.0f, 1.0f}) {
            RootRow row;
            row.level = [&head, sign, offset](const glm::vec3& p) {
                return groom::bangsEdgeDistance(head, p) - sign * offset;
            };
            row.axis = glm::normalize(glm::vec3(0.0f, 0.45f, 1.0f));
            row.keep = [sign, line, offset](const glm::vec3& p) {
                return sign > 0.0f || std::abs(p.x - line) > 1.5f * offset;
            };
            rows.push_back(std::move(row));
        }
    }
    std::vector<RootSample> roots = sampleScalpRoots(mesh, field, s.guides, s.poissonDisk, s.seed, rows);

    // 2 and 3: each strand's centreline, grown and trimmed.
    Random rng{s.seed ^ 0xA511E9B3u};
    const float step = 0.003f * upm;
    const float shortest = 0.03f * upm;
    const float meanLength = s.lengthMetres * upm;
    std::vector<std::vector<glm::vec3>> lines(roots.size());
    std::vector<float> jitter(roots.size());
    for (size_t k = 0; k < roots.size(); ++k) {
        float edge = s.hairlineLength + (1.0f - s.hairlineLength) * roots[k].density;
        float length = meanLength * (1.0f + s.lengthVariation * rng.signedNext()) * edge;
        float bangs = groom::bangsWeight(s, head, roots[k].position);
        length =
            glm::mix(length, s.bangsLengthMetres * upm * (1.0f + 0.5f * s.lengthVariation * rng.signedNext()), bangs);
        length = std::max(length, 0.5f * shortest);
        jitter[k] = groom::trimJitter(s, head, roots[k].position, rng.signedNext());
        lines[k] = groom::growCentreline(s, head, colliders, roots[k], length, step);
        groom::trim(lines[k], s, head, jitter[k], std::min(shortest, 0.9f * groom::polylineLength(lines[k])));
    }

    // 4: clumps. The centres are blue noise in their own right: the first roots (dart order is
    // random over the scalp) kept at least clumpSize apart; every strand joins its nearest centre.
    if (s.clumpSizeMetres > 0.0f && s.clumpStrength > 0.0f) {
        float spacing = s.clumpSizeMetres * upm;
        std::vector<uint32_t> centres;
        for (uint32_t k = 0; k < roots.size(); ++k) {
            bool apart = true;
            for (uint32_t c : centres)
                if (glm::length(roots[c].position - roots[k].position) < spacing) {
                    apart = false;
                    break;
                }
            if (apart)
                centres.push_back(k);
        }
        std::vector<std::vector<glm::vec3>> clumped = lines;
        for (size_t k = 0; k < roots.size(); ++k) {
            uint32_t best = centres.front();
            float bestD = 1e30f;
            for (uint32_t c : centres) {
                float d = glm::length(roots[c].position - roots[k].position);
                if (d < bestD) {
                    bestD = d;
                    best = c;
                }
            }
            if (best != k)
                groom::clump(clumped[k], lines[best], s.clumpStrength, s.clumpShape);
        }
        lines = std::move(clumped);
    }

    // 5 and 6: curl, wave, frizz and flyaways, then outside the colliders and resampled.
    StrandSet set;
    set.verticesPerStrand = s.verticesPerStrand;
    PartSettings part;
    part.globalStiffness = s.globalStiffness;
    part.localStiffness = s.localStiffness;
    set.parts.push_back(part);
    set.rest.reserve(size_t(s.guides) * s.verticesPerStrand);
    const float clearance = 0.002f * upm;
    for (size_t k = 0; k < roots.size(); ++k) {
        std::vector<glm::vec3>& line = lines[k];
        float length = groom::polylineLength(line);
        float spread = s.curlRandomness;
        float radius = s.curlRadiusMetres * upm * (1.0f + spread * rng.signedNext());
        float turns = s.curlTurns * (length / std::max(meanLength, 1e-12f)) * (1.0f + 0.5f * spread * rng.signedNext());
        float phase = 2.0f * kPi * rng.next();
        groom::curl(line, radius, turns, phase, 0.015f * upm);
        glm::vec3 outward = glm::normalize(roots[k].position - head.centre);
        glm::vec3 tangent = safeNormalize(line.back() - line.front(), glm::vec3(0, -1, 0));
        glm::vec3 layerSide = safeNormalize(glm::cross(tangent, outward), perpendicular(tangent));
        groom::wave(line, layerSide, s.waveMetres * upm * (1.0f + 0.3f * rng.signedNext()),
                    s.waveLengthMetres * upm * (1.0f + 0.15f * rng.signedNext()), 2.0f * kPi * rng.next());
        bool flyaway = rng.next() < s.flyaways;
        uint32_t noiseSeed = gpu::hashUint(uint32_t(k) * 2654435761u + s.seed);
        // The noise's features at least two of the simulated segments long: finer ones alias into
        // zigzags once resampled to V vertices (flyaways drew scribbles round the outline).
        float segment = length / float(std::max(s.verticesPerStrand - 1u, 1u));
        float scale = std::max(0.02f * upm, 2.0f * segment);
        groom::frizz(line, (flyaway ? 2.0f : 1.0f) * s.frizzMetres * upm, (flyaway ? 2.0f : 1.0f) * scale, noiseSeed);
        if (flyaway) { // strays: lifted off the hair's surface toward the tip in a smooth arc
            std::vector<float> arc = arcLengths(line);
            float lift = (0.005f + 0.01f * rng.next()) * upm;
            for (size_t i = 1; i < line.size(); ++i) {
                float t = arc[i] / arc.back();
                line[i] += lift * t * t * t * outward;
            }
        }
        groom::keepOutside(line, colliders, clearance, kEmergeMetres * upm);
        // The first segment follows the head rigidly, as TressFX pins two vertices: a root lies inside
        // the colliders (fitted inside the scalp) and its first segment emerges from them. A strand
        // too short to sway (the nape's and the hairline's shortest) is rigid.
        float rigidBelow = kRigidStrandMetres * upm;
        set.add(groom::resample(line, s.verticesPerStrand), 0,
                groom::polylineLength(line) < rigidBelow ? s.verticesPerStrand : 2u, false);
        // Vellus-like at the edge: the hairline's hairs are finer as well as shorter, so the
        // hair's border fades instead of ending in a line of full-width strands.
        set.widthScale.push_back(s.hairlineWidth + (1.0f - s.hairlineWidth) * roots[k].density);
    }
    set.scalpPaint = scalpPaint(mesh, field);
    return set;
}

} // namespace wisp
