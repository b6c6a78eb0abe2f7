// physics/scalp.cpp: the scalp field and the roots sampled at its density.
#include "physics/scalp.h"

#include "core/error.h"
#include "shaders/shared/sim.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <optional>
#include <unordered_map>

namespace wisp {

namespace {

// A deterministic stream of uniform numbers in [0, 1) (PCG hash of a counter), identical on
// every platform, unlike std:: distributions.
struct Random {
    uint32_t state;
    float next() { return gpu::hashToUnit(state++ * 0x9E3779B9u + 0x7F4A7C15u); }
};

RootSample pointOnTriangle(const Mesh& mesh, uint32_t t, float u1, float u2)
{
    // Uniform barycentrics: (1 - sqrt(u1), sqrt(u1) (1 - u2), sqrt(u1) u2) (Osada et al. 2002).
    float r = std::sqrt(u1);
    float a = 1.0f - r, b = r * (1.0f - u2), c = r * u2;
    uint32_t i0 = mesh.indices[3 * t], i1 = mesh.indices[3 * t + 1], i2 = mesh.indices[3 * t + 2];
    glm::vec3 p = a * mesh.positions[i0] + b * mesh.positions[i1] + c * mesh.positions[i2];
    glm::vec3 n = a * mesh.normals[i0] + b * mesh.normals[i1] + c * mesh.normals[i2];
    glm::vec3 face = glm::cross(mesh.positions[i1] - mesh.positions[i0], mesh.positions[i2] - mesh.positions[i0]);
    if (glm::dot(n, face) < 0.0f)
        n = -n;
    float len = glm::length(n);
    return {p, len > 0.0f ? n / len : glm::normalize(face), t};
}

// A point uniform over the area of `triangles` (`cumulative`: their running areas), from three
// numbers of the stream.
RootSample drawOnTriangles(const Mesh& mesh, const std::vector<uint32_t>& triangles,
                           const std::vector<double>& cumulative, Random& rng)
{
    double target = double(rng.next()) * cumulative.back();
    size_t k = size_t(std::lower_bound(cumulative.begin(), cumulative.end(), target) - cumulative.begin());
    k = std::min(k, triangles.size() - 1);
    float u1 = rng.next();
    float u2 = rng.next();
    return pointOnTriangle(mesh, triangles[k], u1, u2);
}

float triangleArea(const Mesh& mesh, uint32_t t)
{
    glm::vec3 a = mesh.positions[mesh.indices[3 * t]];
    glm::vec3 b = mesh.positions[mesh.indices[3 * t + 1]];
    glm::vec3 c = mesh.positions[mesh.indices[3 * t + 2]];
    return 0.5f * glm::length(glm::cross(b - a, c - a));
}

// Dart throwing (Cook 1986) with a hash grid, after the roots `placed` already: a candidate from
// `draw` is kept when no kept root lies within r; r starts at rootSpacing(area, count) and shrinks
// when darts keep missing. `draw` may refuse a candidate (nullopt), which counts as a miss only once
// `count` of them in a row were refused (a sparse field is not a full one).
std::vector<RootSample> throwDarts(const std::function<std::optional<RootSample>()>& draw, uint32_t count, double area,
                                   bool poissonDisk, std::vector<RootSample> placed = {})
{
    std::vector<RootSample> out = std::move(placed);
    out.reserve(count);
    uint64_t refusedInARow = 0;
    auto next = [&]() -> RootSample {
        for (;;) {
            if (std::optional<RootSample> s = draw()) {
                refusedInARow = 0;
                return *s;
            }
            if (++refusedInARow > 1000ull * std::max<uint32_t>(count, 1000))
                throw UserError("the head's scalp field holds almost no area where hair can grow (check its scalp "
                                "rule)");
        }
    };
    if (!poissonDisk) {
        while (out.size() < count)
            out.push_back(next());
        return out;
    }
    float radius = rootSpacing(area, count);
    std::unordered_map<uint64_t, std::vector<uint32_t>> grid;
    auto key = [&](glm::ivec3 c) {
        return (uint64_t(uint32_t(c.x) & 0x1FFFFF) << 42) | (uint64_t(uint32_t(c.y) & 0x1FFFFF) << 21) |
               uint64_t(uint32_t(c.z) & 0x1FFFFF);
    };
    for (uint32_t j = 0; j < out.size(); ++j)
        grid[key(glm::ivec3(glm::floor(out[j].position / radius)))].push_back(j);
    uint32_t misses = 0;
    while (out.size() < count) {
        RootSample s = next();
        glm::ivec3 cell(glm::floor(s.position / radius));
        bool free = true;
        for (int dz = -1; dz <= 1 && free; ++dz)
            for (int dy = -1; dy <= 1 && free; ++dy)
                for (int dx = -1; dx <= 1 && free; ++dx) {
                    auto it = grid.find(key(cell + glm::ivec3(dx, dy, dz)));
                    if (it == grid.end())
                        continue;
                    for (uint32_t j : it->second)
                        if (glm::length(out[j].position - s.position) < radius) {
                            free = false;
                            break;
                        }
                }
        if (free) {
            grid[key(cell)].push_back(uint32_t(out.size()));
            out.push_back(s);
            misses = 0;
        } else if (++misses > 64) {
            radius *= 0.9f; // too dense for this radius: rebuild the grid at the new cell size
            grid.clear();
            for (uint32_t j = 0; j < out.size(); ++j)
                grid[key(glm::ivec3(glm::floor(out[j].position / radius)))].push_back(j);
            misses = 0;
        }
    }
    return out;
}

// The triangles the field reaches (any vertex within a band of the hairline's inside), their
// running areas, and the area they hold weighted by the field's density.
struct ScalpTriangles {
    std::vector<uint32_t> triangles;
    std::vector<double> cumulative;
    double weighted = 0.0;
};

ScalpTriangles scalpTriangles(const Mesh& mesh, const ScalpField& field)
{
    std::vector<float> vertexDistance(mesh.positions.size());
    for (size_t v = 0; v < mesh.positions.size(); ++v)
        vertexDistance[v] = field.distance(mesh.positions[v], mesh.normals[v]);
    ScalpTriangles out;
    double total = 0.0;
    for (uint32_t t = 0; t < mesh.triangleCount(); ++t) {
        float reach = std::max({vertexDistance[mesh.indices[3 * t]], vertexDistance[mesh.indices[3 * t + 1]],
                                vertexDistance[mesh.indices[3 * t + 2]]});
        float area = triangleArea(mesh, t);
        if (reach <= -field.bandWidth || !(area > 0.0f))
            continue;
        out.triangles.push_back(t);
        total += double(area);
        out.cumulative.push_back(total);
        glm::vec3 c = (mesh.positions[mesh.indices[3 * t]] + mesh.positions[mesh.indices[3 * t + 1]] +
                       mesh.positions[mesh.indices[3 * t + 2]]) /
                      3.0f;
        glm::vec3 n = mesh.normals[mesh.indices[3 * t]] + mesh.normals[mesh.indices[3 * t + 1]] +
                      mesh.normals[mesh.indices[3 * t + 2]];
        out.weighted += double(area) * double(field.density(c, glm::length(n) > 0.0f ? glm::normalize(n) : n));
    }
    return out;
}

// A row's roots: points where its level crosses zero in the scalp's triangles (found on the edges
// by linear interpolation of the level, exact for a plane; then every spacing / 8 along each cut),
// inside the hairline (density above one half) where the row keeps them, ordered along the cut by
// their angle about the row's axis through the head's centre (from the head's up, so a row over the
// top has no seam), then taken one `spacing` on from the last.
std::vector<RootSample> rowRoots(const Mesh& mesh, const ScalpField& field, const std::vector<uint32_t>& triangles,
                                 const RootRow& row, float spacing)
{
    glm::vec3 n = glm::normalize(row.axis);
    glm::vec3 up = glm::vec3(0.0f, 1.0f, 0.0f) - n.y * n;
    glm::vec3 e1 = glm::length(up) > 1e-3f ? glm::normalize(up) : glm::normalize(glm::cross(n, glm::vec3(1, 0, 0)));
    glm::vec3 e2 = glm::cross(n, e1);
    glm::vec3 centre = mesh.bounds().center();
    std::vector<std::pair<float, RootSample>> cut;
    for (uint32_t t : triangles) {
        uint32_t idx[3] = {mesh.indices[3 * t], mesh.indices[3 * t + 1], mesh.indices[3 * t + 2]};
        float d[3];
        for (int k = 0; k < 3; ++k)
            d[k] = row.level(mesh.positions[idx[k]]);
        // The cut's ends as barycentric coordinates on the edges the plane crosses.
        glm::vec3 ends[2];
        int found = 0;
        for (int k = 0; k < 3 && found < 2; ++k) {
            int a = k, b = (k + 1) % 3;
            if ((d[a] < 0.0f) == (d[b] < 0.0f))
                continue;
            float u = d[a] / (d[a] - d[b]);
            glm::vec3 bary(0.0f);
            bary[a] = 1.0f - u;
            bary[b] = u;
            ends[found++] = bary;
        }
        if (found < 2)
            continue;
        auto at = [&](const glm::vec3& bary) {
            return bary.x * mesh.positions[idx[0]] + bary.y * mesh.positions[idx[1]] + bary.z * mesh.positions[idx[2]];
        };
        float length = glm::length(at(ends[1]) - at(ends[0]));
        int steps = std::max(1, int(std::ceil(8.0f * length / spacing)));
        for (int k = 0; k <= steps; ++k) {
            glm::vec3 bary = glm::mix(ends[0], ends[1], float(k) / float(steps));
            glm::vec3 p = at(bary);
            glm::vec3 normal =
                bary.x * mesh.normals[idx[0]] + bary.y * mesh.normals[idx[1]] + bary.z * mesh.normals[idx[2]];
            if (!(glm::length(normal) > 0.0f))
                continue;
            normal = glm::normalize(normal);
            float density = field.density(p, normal);
            if (density < 0.5f || (row.keep && !row.keep(p)))
                continue;
            glm::vec3 r = p - centre;
            cut.push_back({std::atan2(glm::dot(r, e2), glm::dot(r, e1)), RootSample{p, normal, t, density}});
        }
    }
    std::sort(cut.begin(), cut.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
    std::vector<RootSample> out;
    for (const auto& [angle, s] : cut)
        if (out.empty() || glm::length(s.position - out.back().position) >= spacing)
            out.push_back(s);
    return out;
}

float smoothstep01(float x)
{
    x = std::clamp(x, 0.0f, 1.0f);
    return x * x * (3.0f - 2.0f * x);
}

} // namespace

float ScalpField::distance(const glm::vec3& p, const glm::vec3& n) const
{
    float plane = glm::dot(p - rule.planePoint, rule.planeNormal);
    float face = (rule.faceMaxDot - glm::dot(n, rule.faceDirection)) * faceRadius;
    // Polynomial smooth minimum (Quilez 2013) over half a band: the two rules meet in a curve.
    float k = 0.5f * bandWidth;
    float h = std::clamp(0.5f + 0.5f * (face - plane) / k, 0.0f, 1.0f);
    return face + (plane - face) * h - k * h * (1.0f - h);
}

float ScalpField::density(const glm::vec3& p, const glm::vec3& n) const
{
    return smoothstep01(distance(p, n) / bandWidth);
}

float ScalpField::paint(const glm::vec3& p, const glm::vec3& n) const
{
    return smoothstep01((distance(p, n) + kPaintLead * bandWidth) / bandWidth);
}

ScalpField makeScalpField(const ScalpRule& rule, float unitsPerMetre, float bandMetres, float skullRadius)
{
    ScalpField f;
    f.rule = rule;
    f.bandWidth = std::max(bandMetres * unitsPerMetre, 1e-6f * unitsPerMetre);
    f.faceRadius = skullRadius;
    return f;
}

std::vector<RootSample> sampleRoots(const Mesh& mesh, const std::vector<uint32_t>& triangles, uint32_t count,
                                    bool poissonDisk, uint32_t seed)
{
    if (triangles.empty())
        throw UserError("the head's scalp region holds no triangles: no hair can grow (check its scalp rule)");
    std::vector<double> cumulative(triangles.size());
    double total = 0.0;
    for (size_t k = 0; k < triangles.size(); ++k) {
        total += double(triangleArea(mesh, triangles[k]));
        cumulative[k] = total;
    }
    Random rng{seed};
    auto draw = [&]() -> std::optional<RootSample> { return drawOnTriangles(mesh, triangles, cumulative, rng); };
    return throwDarts(draw, count, total, poissonDisk);
}

float rootSpacing(double area, uint32_t count)
{
    return float(0.75 * std::sqrt(area / (double(std::max<uint32_t>(count, 1)) * 3.14159265)));
}

double scalpArea(const Mesh& mesh, const ScalpField& field)
{
    return scalpTriangles(mesh, field).weighted;
}

RootRow planeRow(const glm::vec3& point, const glm::vec3& normal, std::function<bool(const glm::vec3&)> keep)
{
    RootRow row;
    row.level = [point, normal](const glm::vec3& p) { return glm::dot(p - point, normal); };
    row.axis = normal;
    row.keep = std::move(keep);
    return row;
}

std::vector<RootSample> sampleScalpRoots(const Mesh& mesh, const ScalpField& field, uint32_t count, bool poissonDisk,
                                         uint32_t seed, const std::vector<RootRow>& rows, float rowSpacing)
{
    ScalpTriangles scalp = scalpTriangles(mesh, field);
    if (scalp.triangles.empty() || !(scalp.weighted > 0.0))
        throw UserError("the head has no usable scalp: its scalp field (the rule's plane and face direction) covers "
                        "none of its surface, so no hair can grow (check the head description's scalp rule)");
    std::vector<RootSample> placed;
    float spacing = rowSpacing * rootSpacing(scalp.weighted, count);
    for (const RootRow& row : rows) {
        std::vector<RootSample> r = rowRoots(mesh, field, scalp.triangles, row, spacing);
        placed.insert(placed.end(), r.begin(), r.end());
    }
    if (placed.size() > count / 4)
        placed.clear(); // too few roots for rows: blue noise alone
    Random rng{seed};
    auto draw = [&]() -> std::optional<RootSample> {
        RootSample s = drawOnTriangles(mesh, scalp.triangles, scalp.cumulative, rng);
        float keep = rng.next();
        s.density = field.density(s.position, s.normal);
        if (keep >= s.density)
            return std::nullopt;
        return s;
    };
    // The dart radius follows the area the hair covers at full density.
    return throwDarts(draw, count, scalp.weighted, poissonDisk, std::move(placed));
}

std::vector<float> scalpPaint(const Mesh& mesh, const ScalpField& field)
{
    std::vector<float> out(mesh.positions.size());
    for (size_t v = 0; v < mesh.positions.size(); ++v)
        out[v] = field.paint(mesh.positions[v], mesh.normals[v]);
    return out;
}

} // namespace wisp
