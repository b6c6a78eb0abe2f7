// physics/groom_metrics.cpp: the side standoff (segments and triangle edges clipped to horizontal
// bands, their z extents per band) and the tip lag meter (least-squares yaw of the tips about the
// head's turn axis against the head's own yaw), and the hair inside the mesh (each vertex's exact
// signed distance).
#include "physics/groom_metrics.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>

namespace wisp {

namespace {

// The z extent of everything added to each band.
struct BandExtents {
    double top = 0.0, height = 1.0;
    std::vector<double> minZ, maxZ;

    BandExtents(double top_, double height_, uint32_t rows)
        : top(top_), height(height_), minZ(rows, std::numeric_limits<double>::infinity()),
          maxZ(rows, -std::numeric_limits<double>::infinity())
    {
    }
    bool holds(uint32_t k) const { return minZ[k] <= maxZ[k]; }
    double extent(uint32_t k) const { return maxZ[k] - minZ[k]; }

    // The part of segment pq inside each band it crosses: its end points' z (z is linear along
    // the segment, so they are its extremes). Band k is [top - (k + 1) height, top - k height].
    void addSegment(glm::dvec3 p, glm::dvec3 q)
    {
        double lowY = std::min(p.y, q.y), highY = std::max(p.y, q.y);
        double rows = double(minZ.size());
        double first = std::floor((top - highY) / height), last = std::floor((top - lowY) / height);
        if (last < 0.0 || first >= rows)
            return;
        auto begin = uint32_t(std::max(first, 0.0)), end = uint32_t(std::min(last, rows - 1.0));
        for (uint32_t k = begin; k <= end; ++k) {
            double hi = top - double(k) * height, lo = hi - height;
            double t0 = 0.0, t1 = 1.0;
            if (p.y == q.y) {
                if (p.y < lo || p.y > hi)
                    continue;
            } else {
                double a = (lo - p.y) / (q.y - p.y), b = (hi - p.y) / (q.y - p.y);
                t0 = std::max(0.0, std::min(a, b));
                t1 = std::min(1.0, std::max(a, b));
                if (t0 > t1)
                    continue;
            }
            for (double t : {t0, t1}) {
                double z = p.z + t * (q.z - p.z);
                minZ[k] = std::min(minZ[k], z);
                maxZ[k] = std::max(maxZ[k], z);
            }
        }
    }
};

double wrapRadians(double a)
{
    constexpr double kTwoPi = 2.0 * std::numbers::pi;
    a = std::fmod(a + std::numbers::pi, kTwoPi);
    if (a < 0.0)
        a += kTwoPi;
    return a - std::numbers::pi;
}

} // namespace

SideStandoff sideStandoff(const Mesh& head, const std::vector<glm::vec3>& positions, uint32_t verticesPerStrand,
                          float unitsPerMetre)
{
    SideStandoff out;
    if (head.positions.empty() || verticesPerStrand < 2)
        return out;
    double top = double(head.bounds().max.y);
    double height = double(kSideStandoffDepthMetres) * double(unitsPerMetre) / double(kSideStandoffRows);
    // The triangles' parts inside a band have their corners on the triangles' edges.
    BandExtents skull(top, height, kSideStandoffRows);
    for (size_t t = 0; t + 2 < head.indices.size(); t += 3)
        for (int e = 0; e < 3; ++e)
            skull.addSegment(glm::dvec3(head.positions[head.indices[t + e]]),
                             glm::dvec3(head.positions[head.indices[t + (e + 1) % 3]]));
    BandExtents hair(top, height, kSideStandoffRows);
    for (size_t s = 0; s + verticesPerStrand <= positions.size(); s += verticesPerStrand)
        for (uint32_t i = 0; i + 1 < verticesPerStrand; ++i)
            hair.addSegment(glm::dvec3(positions[s + i]), glm::dvec3(positions[s + i + 1]));

    double sum = 0.0;
    for (uint32_t k = 0; k < kSideStandoffRows; ++k) {
        if (!skull.holds(k) || !hair.holds(k))
            continue;
        sum += std::max(0.0, skull.minZ[k] - hair.minZ[k]) + std::max(0.0, hair.maxZ[k] - skull.maxZ[k]);
        out.headWidth = std::max(out.headWidth, skull.extent(k));
        ++out.rows;
    }
    if (out.rows == 0 || !(out.headWidth > 0.0))
        return out;
    out.meanBeyond = sum / double(out.rows);
    out.value = out.meanBeyond / out.headWidth;
    return out;
}

SideStandoff sideStandoff(const Mesh& head, const StrandSet& strands, float unitsPerMetre)
{
    return sideStandoff(head, strands.rest, strands.verticesPerStrand, unitsPerMetre);
}

TipLagMeter::TipLagMeter(const StrandSet& strands, glm::vec3 pivot) : pivot_(pivot)
{
    uint32_t V = strands.verticesPerStrand;
    for (size_t s = 0; s < strands.strandCount(); ++s) {
        const gpu::StrandInfo& info = strands.strands[s];
        if (info.pinnedRoot < V && info.pinnedTip == 0u)
            tips_.push_back(s * V + V - 1);
    }
    lag_.tips = tips_.size();
}

void TipLagMeter::sample(double seconds, const std::vector<glm::vec4>& positions, const glm::mat4& head)
{
    glm::mat3 rotation(head);
    glm::dvec3 centre = glm::dvec3(glm::vec3(head * glm::vec4(pivot_, 1.0f)));
    if (lag_.samples == 0) {
        axis_ = glm::normalize(rotation * glm::vec3(0.0f, 1.0f, 0.0f));
        startRotation_ = rotation;
    }
    glm::dvec3 axis(axis_);
    auto across = [&](glm::dvec3 r) { return r - axis * glm::dot(axis, r); };

    // The head's yaw against the start: where the rotation between them takes a vector across the axis.
    glm::dvec3 u = glm::normalize(glm::cross(axis, std::abs(axis.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 0, 1)));
    glm::dvec3 v = across(glm::dvec3(rotation * glm::transpose(startRotation_) * glm::vec3(u)));
    double headYaw = std::atan2(glm::dot(axis, glm::cross(u, v)), glm::dot(u, v));

    double sine = 0.0, cosine = 0.0;
    for (size_t k = 0; k < tips_.size(); ++k) {
        glm::dvec3 r = across(glm::dvec3(glm::vec3(positions[tips_[k]])) - centre);
        if (lag_.samples == 0) {
            start_.push_back(r);
            continue;
        }
        const glm::dvec3& r0 = start_[k];
        sine += glm::dot(axis, glm::cross(r0, r));
        cosine += glm::dot(r0, r);
    }
    double tipYaw = lag_.samples == 0 || (sine == 0.0 && cosine == 0.0) ? 0.0 : std::atan2(sine, cosine);

    headYaw_ += wrapRadians(headYaw - headYaw_);
    tipYaw_ += wrapRadians(tipYaw - tipYaw_);
    double lag = std::abs(glm::degrees(headYaw_ - tipYaw_));
    lag_.largestHeadYawDeg = std::max(lag_.largestHeadYawDeg, std::abs(glm::degrees(headYaw_)));
    if (lag > lag_.peakDeg) {
        lag_.peakDeg = lag;
        lag_.peakAtSeconds = seconds;
    }
    lag_.finalDeg = lag;
    ++lag_.samples;
}

// ---- Inside the mesh -------------------------------------------------------------------------------

InsideMesh insideMesh(const MeshSignedDistance& head, float diagonal, const std::vector<glm::vec3>& positions,
                      uint32_t verticesPerStrand)
{
    InsideMesh out;
    uint32_t V = verticesPerStrand;
    if (V == 0 || !(diagonal > 0.0f))
        return out;
    out.strands = positions.size() / V;
    float depthLimit = kInsideDepth * diagonal;
    for (size_t s = 0; s < out.strands; ++s) {
        bool inside = false;
        for (uint32_t i = kInsideSkippedVertices; i < V; ++i) {
            float depth = -head(positions[s * V + i]);
            ++out.vertices;
            out.deepest = std::max(out.deepest, double(depth) / double(diagonal));
            if (depth > depthLimit) {
                ++out.verticesInside;
                inside = true;
            }
        }
        out.strandsInside += inside;
    }
    return out;
}

nlohmann::json InsideMesh::toJson() const
{
    return {{"strands", strandShare()}, {"vertices", vertexShare()}, {"deepest", deepest}};
}

std::string InsideMesh::describe() const
{
    char text[160];
    std::snprintf(text, sizeof text, "%.1f%% of strands, %.2f%% of vertices, deepest %.3g of the diagonal",
                  100.0 * strandShare(), 100.0 * vertexShare(), deepest);
    return text;
}

InsideMesh insideMesh(const MeshSignedDistance& head, float diagonal, const StrandSet& strands)
{
    return insideMesh(head, diagonal, strands.rest, strands.verticesPerStrand);
}

} // namespace wisp
