// physics/growth.cpp: root sampling and strand growth.
#include "physics/growth.h"

#include "core/error.h"

#include <algorithm>
#include <cmath>
#include <numeric>
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

} // namespace

std::vector<RootSample> sampleRoots(const Mesh& mesh, const std::vector<uint32_t>& triangles, uint32_t count,
                                    bool poissonDisk, uint32_t seed)
{
    if (triangles.empty())
        throw UserError("the head's scalp region holds no triangles: no hair can grow (check its scalp rule)");
    std::vector<double> cumulative(triangles.size());
    double total = 0.0;
    for (size_t k = 0; k < triangles.size(); ++k) {
        uint32_t t = triangles[k];
        glm::vec3 a = mesh.positions[mesh.indices[3 * t]];
        glm::vec3 b = mesh.positions[mesh.indices[3 * t + 1]];
        glm::vec3 c = mesh.positions[mesh.indices[3 * t + 2]];
        total += 0.5 * double(glm::length(glm::cross(b - a, c - a)));
        cumulative[k] = total;
    }
    Random rng{seed};
    auto draw = [&]() {
        double target = double(rng.next()) * total;
        size_t k = size_t(std::lower_bound(cumulative.begin(), cumulative.end(), target) - cumulative.begin());
        k = std::min(k, triangles.size() - 1);
        float u1 = rng.next();
        float u2 = rng.next();
        return pointOnTriangle(mesh, triangles[k], u1, u2);
    };

    std::vector<RootSample> out;
    out.reserve(count);
    if (!poissonDisk) {
        for (uint32_t i = 0; i < count; ++i)
            out.push_back(draw());
        return out;
    }
    // Dart throwing (Cook 1986) with a hash grid: a candidate is kept when no kept root lies within
    // r; r starts at 0.75 of the radius of N disks tiling the area and shrinks when darts keep missing.
    float radius = float(0.75 * std::sqrt(total / (double(count) * 3.14159265)));
    std::unordered_map<uint64_t, std::vector<uint32_t>> grid;
    auto key = [&](glm::ivec3 c) {
        return (uint64_t(uint32_t(c.x) & 0x1FFFFF) << 42) | (uint64_t(uint32_t(c.y) & 0x1FFFFF) << 21) |
               uint64_t(uint32_t(c.z) & 0x1FFFFF);
    };
    uint32_t misses = 0;
    while (out.size() < count) {
        RootSample s = draw();
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

StrandSet growGuides(const Mesh& mesh, const ScalpRule& scalp, const std::vector<gpu::Ellipsoid>& colliders,
                     const GrowthSettings& s, float unitsPerMetre)
{
    std::vector<RootSample> roots = sampleRoots(mesh, scalpTriangles(mesh, scalp), s.guides, s.poissonDisk, s.seed);
    StrandSet set;
    set.verticesPerStrand = s.verticesPerStrand;
    set.parts.push_back(PartSettings{});
    set.rest.reserve(size_t(s.guides) * s.verticesPerStrand);
    Random rng{s.seed ^ 0xA511E9B3u};
    const glm::vec3 down(0.0f, -1.0f, 0.0f);
    const float clearance = 0.002f * unitsPerMetre; // grown hair rests just outside the colliders
    std::vector<glm::vec3> points(s.verticesPerStrand);
    // Strands are combed down, away from the crown and back (swept off the face): the bend
    // direction is gravity plus an outward-and-back pull (straight down alone cannot bend a strand
    // that grows straight up at the crown).
    glm::vec3 crown(0.0f);
    for (const RootSample& root : roots)
        crown += root.position;
    crown /= float(std::max<size_t>(roots.size(), 1));
    for (const RootSample& root : roots) {
        glm::vec3 outward = root.position - crown;
        outward.y = 0.0f;
        outward = glm::length(outward) > 1e-6f * unitsPerMetre ? glm::normalize(outward) : glm::vec3(0.0f);
        glm::vec3 comb = glm::normalize(outward + glm::vec3(0.0f, 0.0f, -2.5f)); // the head faces +z

        float length = s.lengthMetres * unitsPerMetre * (1.0f + s.lengthVariation * (2.0f * rng.next() - 1.0f));
        float segment = length / float(s.verticesPerStrand - 1);
        float curlPhase = 6.2831853f * rng.next();
        glm::vec3 dir = root.normal;
        points[0] = root.position;
        for (uint32_t i = 1; i < s.verticesPerStrand; ++i) {
            // Near the root the comb turns the strand back and outward; further out gravity takes over.
            float u = float(i) / float(s.verticesPerStrand - 1);
            glm::vec3 bend = 1.5f * (1.0f - u) * comb + (u + 0.2f) * down;
            dir = glm::normalize(dir + s.styleGravity * bend);
            glm::vec3 p = points[i - 1] + segment * dir;
            for (const gpu::Ellipsoid& e : colliders) { // drape over the head instead of through it
                gpu::Contact c = gpu::ellipsoidContact(e, p, clearance);
                if (c.depth > 0.0f)
                    p += c.depth * c.normal;
            }
            p = gpu::ftlProject(points[i - 1], p, segment);
            dir = glm::normalize(p - points[i - 1]);
            points[i] = p;
        }
        if (s.curlRadiusMetres > 0.0f) { // a helix around the grown strand, growing from the root
            float radius = s.curlRadiusMetres * unitsPerMetre;
            for (uint32_t i = 1; i < s.verticesPerStrand; ++i) {
                glm::vec3 t = glm::normalize(points[i] - points[i - 1]);
                glm::vec3 u =
                    glm::normalize(glm::cross(t, std::abs(t.x) < 0.9f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0)));
                glm::vec3 w = glm::cross(t, u);
                float along = float(i) / float(s.verticesPerStrand - 1);
                float angle = curlPhase + 6.2831853f * s.curlTurns * along;
                points[i] += radius * std::min(1.0f, 4.0f * along) * (std::cos(angle) * u + std::sin(angle) * w);
            }
        }
        set.add(points, 0, 1, false);
    }
    return set;
}

} // namespace wisp
