// physics/colliders.cpp: ellipsoid conversion, penetration, automatic fit.
#include "physics/colliders.h"

#include "assets/placement.h"
#include "core/rotation.h"

#include <algorithm>
#include <cmath>

namespace wisp {

gpu::Ellipsoid toGpu(const Ellipsoid& e)
{
    gpu::Ellipsoid g{};
    g.rotation = glm::mat4(rotationXyzDegrees(e.rotationDeg));
    g.center = e.center;
    g.radii = e.radii;
    return g;
}

float penetrationDepth(const std::vector<gpu::Ellipsoid>& colliders, const glm::vec3& p)
{
    float deepest = 0.0f;
    for (const gpu::Ellipsoid& e : colliders)
        deepest = std::max(deepest, gpu::ellipsoidContact(e, p, 0.0f).depth);
    return deepest;
}

namespace {

Ellipsoid fitBand(const Mesh& mesh, float yTop, float yBottom, float insideFraction, const char* name)
{
    std::vector<glm::vec3> band;
    for (const glm::vec3& p : mesh.positions)
        if (p.y <= yTop && p.y >= yBottom)
            band.push_back(p);
    Ellipsoid e;
    e.name = name;
    if (band.empty()) {
        e.center = glm::vec3(0.0f, 0.5f * (yTop + yBottom), 0.0f);
        e.radii = glm::vec3(std::max(1e-3f, 0.5f * (yTop - yBottom)));
        return e;
    }
    glm::vec3 lo = band.front(), hi = band.front();
    for (const glm::vec3& p : band) {
        lo = glm::min(lo, p);
        hi = glm::max(hi, p);
    }
    e.center = 0.5f * (lo + hi);
    e.radii = glm::max(0.5f * (hi - lo), glm::vec3(1e-4f));
    if (insideFraction > 0.0f) {
        std::vector<float> r;
        for (const glm::vec3& p : band)
            r.push_back(glm::length((p - e.center) / e.radii));
        size_t k = std::min(r.size() - 1, static_cast<size_t>(insideFraction * float(r.size())));
        std::nth_element(r.begin(), r.begin() + std::ptrdiff_t(k), r.end());
        e.radii *= std::max(r[k], 1e-3f);
    }
    return e;
}

} // namespace

std::vector<Ellipsoid> fitColliders(const Mesh& mesh)
{
    Bounds b = mesh.bounds();
    // The head's height from its top to its neck (assets/placement.h): heads of any proportion,
    // busts with shoulders or heads alone, are cut where they narrow, not at fixed fractions.
    HeadRegion region = headRegion(mesh);
    float head = std::max(region.top - region.neck, 1e-6f * b.size().y);
    float craniumCut = region.top - 0.5f * head; // above the eyes
    float neckTop = region.neck + 0.25f * head, neckBottom = std::max(region.neck - 0.15f * head, b.min.y);
    Ellipsoid cranium = fitBand(mesh, b.max.y, craniumCut, 0.0f, "cranium");
    // The skull: as wide and deep as the top band, as tall as it is wide, its top at the head's
    // top; then scaled so that 98% of the vertices above its centre (the scalp) lie inside. The
    // scalp rule is derived from this one; inscribeColliders then pulls it inside the scalp.
    cranium.radii.y = 0.55f * (cranium.radii.x + cranium.radii.z);
    cranium.center.y = b.max.y - cranium.radii.y;
    std::vector<float> r;
    for (const glm::vec3& p : mesh.positions)
        if (p.y > cranium.center.y)
            r.push_back(glm::length((p - cranium.center) / cranium.radii));
    if (!r.empty()) {
        size_t k = std::min(r.size() - 1, static_cast<size_t>(0.98f * float(r.size())));
        std::nth_element(r.begin(), r.begin() + std::ptrdiff_t(k), r.end());
        cranium.radii *= std::max(r[k], 1e-3f);
    }
    std::vector<Ellipsoid> out = {cranium, fitBand(mesh, neckTop, neckBottom, 0.9f, "neck")};
    if (neckBottom > b.min.y + 1e-6f * b.size().y) // a bust: its shoulders
        out.push_back(fitBand(mesh, neckBottom, b.min.y, 0.0f, "shoulders"));
    return out;
}

void inscribeColliders(std::vector<Ellipsoid>& colliders, const Mesh& mesh, const std::vector<uint32_t>& scalp,
                       float tolerance)
{
    std::vector<uint8_t> onScalp(mesh.positions.size(), 0);
    for (uint32_t t : scalp)
        for (int c = 0; c < 3; ++c)
            onScalp[mesh.indices[3 * t + c]] = 1;
    for (Ellipsoid& e : colliders) {
        glm::mat3 R = rotationXyzDegrees(e.rotationDeg);
        float scale = 1.0f;
        for (size_t v = 0; v < mesh.positions.size(); ++v) {
            if (!onScalp[v])
                continue;
            glm::vec3 d = mesh.positions[v] - e.center;
            float distance = glm::length(d);
            float radius = glm::length((glm::transpose(R) * d) / e.radii); // 1 on the surface
            if (radius < scale && distance > 0.0f)
                scale = std::min(scale, radius * (1.0f + tolerance / distance));
        }
        e.radii *= std::max(scale, 0.05f);
    }
}

void shrinkCollidersToRestPose(std::vector<Ellipsoid>& colliders, const StrandSet& strands)
{
    uint32_t V = strands.verticesPerStrand;
    for (Ellipsoid& e : colliders) {
        glm::mat3 R = rotationXyzDegrees(e.rotationDeg);
        std::vector<float> inside; // normalized radii of the free vertices inside this collider
        size_t free = 0;
        for (size_t s = 0; s < strands.strandCount(); ++s)
            for (uint32_t i = strands.strands[s].pinnedRoot; i < V; ++i) {
                ++free;
                float r = glm::length((glm::transpose(R) * (strands.rest[s * V + i] - e.center)) / e.radii);
                if (r < 1.0f)
                    inside.push_back(r);
            }
        size_t allowed = free / 100;
        if (inside.size() <= allowed)
            continue;
        std::sort(inside.begin(), inside.end());
        float scale = inside[allowed]; // all but `allowed` of the inside vertices end up outside
        e.radii *= std::max(scale, 0.05f);
    }
}

ScalpRule defaultScalpRule(const Ellipsoid& cranium)
{
    ScalpRule rule;
    rule.planePoint = cranium.center - glm::vec3(0.0f, 0.15f * cranium.radii.y, 0.0f);
    rule.planeNormal = glm::normalize(glm::vec3(0.0f, 1.0f, -0.7f));
    rule.faceDirection = glm::vec3(0.0f, 0.0f, 1.0f);
    rule.faceMaxDot = 0.8f;
    return rule;
}

float unitsPerMetre(const Head& head)
{
    const std::string& u = head.description.units;
    if (u == "m")
        return 1.0f;
    if (u == "cm")
        return 100.0f;
    if (u == "mm")
        return 1000.0f;
    // A bust (head, neck, shoulders) is about 0.6 m along its bounding box's diagonal.
    return std::max(head.mesh.bounds().diagonal(), 1e-6f) / 0.6f;
}

} // namespace wisp
