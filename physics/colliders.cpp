// physics/colliders.cpp: ellipsoid conversion, penetration, automatic fit.
#include "physics/colliders.h"

#include "assets/placement.h"
#include "core/rotation.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <map>

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

std::vector<std::string> fittedColliderWarnings(const Mesh& mesh, const std::vector<Ellipsoid>& colliders,
                                                const std::vector<uint32_t>& scalpTriangles)
{
    std::vector<std::string> out;
    if (mesh.positions.empty())
        return out;
    char text[512];
    // Signed volume (the divergence theorem over the triangles, counter-clockwise seen from outside).
    double volume = 0.0;
    for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
        glm::dvec3 a = mesh.positions[mesh.indices[t]], b = mesh.positions[mesh.indices[t + 1]],
                   c = mesh.positions[mesh.indices[t + 2]];
        volume += glm::dot(a, glm::cross(b, c)) / 6.0;
    }
    Bounds bounds = mesh.bounds();
    double box = double(bounds.size().x) * bounds.size().y * bounds.size().z;
    if (volume < -1e-3 * box) {
        std::snprintf(text, sizeof text,
                      "the mesh is inside-out (its signed volume is %.3g, negative: its triangles face inward); "
                      "the scalp and the colliders take its inside for its outside",
                      volume);
        out.push_back(text);
    }
    // Edges of one triangle only, by position (the mesh's vertices are split by normal), on the upper
    // half of the head: a hole there as long as a quarter of the mesh's width lets hair through (a
    // bust's neck or a few stray edges are no such hole).
    HeadRegion region = headRegion(mesh);
    float upper = region.neck + 0.5f * (region.top - region.neck);
    std::map<std::array<float, 3>, uint32_t> weld;
    std::vector<uint32_t> id(mesh.positions.size());
    for (size_t v = 0; v < mesh.positions.size(); ++v) {
        const glm::vec3& p = mesh.positions[v];
        id[v] = weld.emplace(std::array<float, 3>{p.x, p.y, p.z}, uint32_t(weld.size())).first->second;
    }
    std::map<std::pair<uint32_t, uint32_t>, int> edges;
    for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3)
        for (size_t k = 0; k < 3; ++k) {
            uint32_t a = id[mesh.indices[t + k]], b = id[mesh.indices[t + (k + 1) % 3]];
            ++edges[{std::min(a, b), std::max(a, b)}];
        }
    size_t openAbove = 0;
    double openLength = 0.0;
    for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3)
        for (size_t k = 0; k < 3; ++k) {
            uint32_t va = mesh.indices[t + k], vb = mesh.indices[t + (k + 1) % 3];
            uint32_t a = id[va], b = id[vb];
            const glm::vec3 &pa = mesh.positions[va], &pb = mesh.positions[vb];
            if (a != b && edges[{std::min(a, b), std::max(a, b)}] == 1 && std::min(pa.y, pb.y) > upper) {
                ++openAbove;
                openLength += double(glm::length(pa - pb));
            }
        }
    if (openLength > 0.25 * double(bounds.size().x)) {
        std::snprintf(text, sizeof text,
                      "the mesh is open on the upper half of its head (%zu edges of one triangle only, %.3g long in "
                      "all): hair passes through the hole",
                      openAbove, openLength);
        out.push_back(text);
    }
    ColliderFit fit = measureColliderFit(colliders, mesh, scalpTriangles, kFitExposedGap);
    if (fit.exposed > kFitExposedLimit) {
        std::snprintf(text, sizeof text,
                      "the colliders fitted to it hold its scalp badly, as they do a mesh that is no head: %.0f%% of "
                      "the scalp lies more than %.0f%% of its diagonal outside them all (hair sinks into the mesh "
                      "there); a head description with its own colliders avoids the fit",
                      100.0 * double(fit.exposed), 100.0 * double(kFitExposedGap));
        out.push_back(text);
    }
    return out;
}

namespace {

// Points of the scalp: each triangle on a barycentric grid (its corners, edges and inside), each
// point weighted by its share of the triangle's area. A coarse mesh's faces are sampled, not only
// its corners: a cube's 8 corners can lie outside a collider that reaches through its faces.
struct ScalpSamples {
    std::vector<glm::vec3> points;
    std::vector<double> weights;
};
ScalpSamples sampleScalp(const Mesh& mesh, const std::vector<uint32_t>& scalp)
{
    constexpr int kSteps = 4;
    constexpr int kPerTriangle = (kSteps + 1) * (kSteps + 2) / 2;
    ScalpSamples out;
    for (uint32_t t : scalp) {
        glm::vec3 a = mesh.positions[mesh.indices[3 * t]], b = mesh.positions[mesh.indices[3 * t + 1]],
                  c = mesh.positions[mesh.indices[3 * t + 2]];
        double area = 0.5 * double(glm::length(glm::cross(b - a, c - a)));
        for (int i = 0; i <= kSteps; ++i)
            for (int j = 0; i + j <= kSteps; ++j) {
                out.points.push_back(a + (b - a) * (float(i) / float(kSteps)) + (c - a) * (float(j) / float(kSteps)));
                out.weights.push_back(area / kPerTriangle);
            }
    }
    return out;
}

// How far `p` lies outside `e`, along the ray from its centre (0 inside): an upper bound of the
// distance to its surface, exact on a sphere.
float radialGap(const Ellipsoid& e, const glm::mat3& R, glm::vec3 p)
{
    glm::vec3 d = p - e.center;
    float r = glm::length((glm::transpose(R) * d) / e.radii);
    return r <= 1.0f ? 0.0f : glm::length(d) * (1.0f - 1.0f / r);
}

} // namespace

ColliderFit measureColliderFit(const std::vector<Ellipsoid>& colliders, const Mesh& mesh,
                               const std::vector<uint32_t>& scalp, float gap)
{
    ColliderFit fit;
    float diagonal = std::max(mesh.bounds().diagonal(), 1e-30f);
    if (mesh.indices.empty() || colliders.empty())
        return fit;
    std::vector<gpu::Ellipsoid> gpuColliders;
    for (const Ellipsoid& e : colliders)
        gpuColliders.push_back(toGpu(e));
    std::vector<glm::mat3> rotations;
    for (const Ellipsoid& e : colliders)
        rotations.push_back(rotationXyzDegrees(e.rotationDeg));
    ScalpSamples samples = sampleScalp(mesh, scalp);
    double area = 0.0, exposedArea = 0.0;
    for (size_t i = 0; i < samples.points.size(); ++i) {
        glm::vec3 p = samples.points[i];
        fit.intrusion = std::max(fit.intrusion, penetrationDepth(gpuColliders, p) / diagonal);
        float nearest = 1e30f;
        for (size_t k = 0; k < colliders.size(); ++k)
            nearest = std::min(nearest, radialGap(colliders[k], rotations[k], p));
        area += samples.weights[i];
        exposedArea += nearest > gap * diagonal ? samples.weights[i] : 0.0;
    }
    fit.exposed = area > 0.0 ? float(exposedArea / area) : 0.0f;
    return fit;
}

void inscribeColliders(std::vector<Ellipsoid>& colliders, const Mesh& mesh, const std::vector<uint32_t>& scalp,
                       float tolerance)
{
    const std::vector<glm::vec3> points = sampleScalp(mesh, scalp).points;
    for (Ellipsoid& e : colliders) {
        glm::mat3 R = rotationXyzDegrees(e.rotationDeg);
        float scale = 1.0f;
        for (const glm::vec3& p : points) {
            glm::vec3 d = p - e.center;
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
