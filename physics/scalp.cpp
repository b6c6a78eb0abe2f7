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

// Dart throwing (Cook 1986) with a hash grid: a candidate from `draw` is kept when no kept root lies
// within r; r starts at 0.75 of the radius of `count` disks tiling `area` and shrinks when darts keep
// missing. `draw` may refuse a candidate (nullopt), which counts as a miss only once `count` of them
// in a row were refused (a sparse field is not a full one).
std::vector<RootSample> throwDarts(const std::function<std::optional<RootSample>()>& draw, uint32_t count, double area,
                                   bool poissonDisk)
{
    std::vector<RootSample> out;
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
        for (uint32_t i = 0; i < count; ++i)
            out.push_back(next());
        return out;
    }
    float radius = float(0.75 * std::sqrt(area / (double(count) * 3.14159265)));
    std::unordered_map<uint64_t, std::vector<uint32_t>> grid;
    auto key = [&](glm::ivec3 c) {
        return (uint64_t(uint32_t(c.x) & 0x1FFFFF) << 42) | (uint64_t(uint32_t(c.y) & 0x1FFFFF) << 21) |
               uint64_t(uint32_t(c.z) & 0x1FFFFF);
    };
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
    return smoothstep01((distance(p, n) + bandWidth) / bandWidth);
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

std::vector<RootSample> sampleScalpRoots(const Mesh& mesh, const ScalpField& field, uint32_t count, bool poissonDisk,
                                         uint32_t seed)
{
    // The triangles the field reaches: any vertex within a band of the hairline's inside.
    std::vector<float> vertexDistance(mesh.positions.size());
    for (size_t v = 0; v < mesh.positions.size(); ++v)
        vertexDistance[v] = field.distance(mesh.positions[v], mesh.normals[v]);
    std::vector<uint32_t> triangles;
    std::vector<double> cumulative;
    double total = 0.0, weighted = 0.0;
    for (uint32_t t = 0; t < mesh.triangleCount(); ++t) {
        float reach = std::max({vertexDistance[mesh.indices[3 * t]], vertexDistance[mesh.indices[3 * t + 1]],
                                vertexDistance[mesh.indices[3 * t + 2]]});
        float area = triangleArea(mesh, t);
        if (reach <= -field.bandWidth || !(area > 0.0f))
            continue;
        triangles.push_back(t);
        total += double(area);
        cumulative.push_back(total);
        glm::vec3 c = (mesh.positions[mesh.indices[3 * t]] + mesh.positions[mesh.indices[3 * t + 1]] +
                       mesh.positions[mesh.indices[3 * t + 2]]) /
                      3.0f;
        glm::vec3 n = mesh.normals[mesh.indices[3 * t]] + mesh.normals[mesh.indices[3 * t + 1]] +
                      mesh.normals[mesh.indices[3 * t + 2]];
        weighted += double(area) * double(field.density(c, glm::length(n) > 0.0f ? glm::normalize(n) : n));
    }
    if (triangles.empty() || !(weighted > 0.0))
        throw UserError("the head has no usable scalp: its scalp field (the rule's plane and face direction) covers "
                        "none of its surface, so no hair can grow (check the head description's scalp rule)");
    Random rng{seed};
    auto draw = [&]() -> std::optional<RootSample> {
        RootSample s = drawOnTriangles(mesh, triangles, cumulative, rng);
        float keep = rng.next();
        s.density = field.density(s.position, s.normal);
        if (keep >= s.density)
            return std::nullopt;
        return s;
    };
    // The dart radius follows the area the hair covers at full density.
    return throwDarts(draw, count, weighted, poissonDisk);
}

std::vector<float> scalpPaint(const Mesh& mesh, const ScalpField& field)
{
    std::vector<float> out(mesh.positions.size());
    for (size_t v = 0; v < mesh.positions.size(); ++v)
        out[v] = field.paint(mesh.positions[v], mesh.normals[v]);
    return out;
}

} // namespace wisp
