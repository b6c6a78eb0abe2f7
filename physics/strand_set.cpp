// physics/strand_set.cpp: the strand set's bookkeeping.
#include "physics/strand_set.h"

#include "core/error.h"
#include "shaders/shared/strands.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace wisp {

void StrandSet::add(const std::vector<glm::vec3>& points, uint32_t part, uint32_t pinnedRoot, bool pinnedTip)
{
    if (points.size() != verticesPerStrand)
        throw std::logic_error("StrandSet::add: strand has " + std::to_string(points.size()) + " points, expected " +
                               std::to_string(verticesPerStrand));
    for (size_t i = 1; i < points.size(); ++i) {
        float length = glm::length(points[i] - points[i - 1]);
        if (!(length > 0.0f))
            throw UserError("hair strand " + std::to_string(strands.size()) + " has a zero-length segment (" +
                            std::to_string(i - 1) + " to " + std::to_string(i) + "): cannot simulate it");
        if (!std::isfinite(length))
            throw UserError("hair strand " + std::to_string(strands.size()) + " has a segment too long for floats (" +
                            std::to_string(i - 1) + " to " + std::to_string(i) + "): cannot simulate it");
    }
    uint32_t index = static_cast<uint32_t>(strands.size());
    strands.push_back({.part = part,
                       .pinnedRoot = std::clamp<uint32_t>(pinnedRoot, 1, verticesPerStrand), // V: rigid
                       .pinnedTip = pinnedTip ? 1u : 0u,
                       .seed = gpu::hashUint(index * 2654435761u + 17u)});
    rest.insert(rest.end(), points.begin(), points.end());
}

float StrandSet::maxLength() const
{
    float longest = 0.0f;
    for (size_t s = 0; s < strandCount(); ++s) {
        float len = 0.0f;
        for (uint32_t i = 1; i < verticesPerStrand; ++i)
            len += glm::length(rest[s * verticesPerStrand + i] - rest[s * verticesPerStrand + i - 1]);
        longest = std::max(longest, len);
    }
    return longest;
}

Bounds StrandSet::bounds() const
{
    Bounds b;
    if (rest.empty())
        return b;
    b.min = b.max = rest.front();
    for (const glm::vec3& p : rest) {
        b.min = glm::min(b.min, p);
        b.max = glm::max(b.max, p);
    }
    return b;
}

std::vector<glm::uvec4> guideTriangles(const StrandSet& strands)
{
    size_t n = strands.strandCount();
    uint32_t V = strands.verticesPerStrand;
    std::vector<glm::uvec4> out(n);
    if (n == 0)
        return out;
    Bounds b;
    b.min = b.max = strands.rest[0];
    for (size_t s = 0; s < n; ++s) {
        b.min = glm::min(b.min, strands.rest[s * V]);
        b.max = glm::max(b.max, strands.rest[s * V]);
    }
    // About two roots per cell: cell = (volume of the roots' box / n)^(1/3), at least a tiny size.
    glm::vec3 size = glm::max(b.size(), glm::vec3(1e-6f));
    float cell = std::max(std::cbrt(2.0f * size.x * size.y * size.z / float(n)), 1e-3f * glm::length(size));
    glm::ivec3 dims = glm::ivec3(size / cell) + 1;
    auto cellOf = [&](const glm::vec3& p) {
        return glm::clamp(glm::ivec3((p - b.min) / cell), glm::ivec3(0), dims - 1);
    };
    auto key = [&](glm::ivec3 c) {
        return (size_t(c.z) * size_t(dims.y) + size_t(c.y)) * size_t(dims.x) + size_t(c.x);
    };
    std::vector<std::vector<uint32_t>> grid(size_t(dims.x) * dims.y * dims.z);
    for (uint32_t s = 0; s < n; ++s)
        grid[key(cellOf(strands.rest[size_t(s) * V]))].push_back(s);
    // A neighbour whose strand parts from this one (across a parting, or left and right at the front
    // hairline) would draw the strands between them across the gap: over the scalp, over the face.
    // It is skipped when, a third of the way along, the two strands are farther apart than three times
    // their roots' distance plus a tenth of the strand's length.
    uint32_t probe = std::max(1u, (V - 1) / 3);
    std::vector<float> lengths(n, 0.0f);
    for (size_t s = 0; s < n; ++s)
        for (uint32_t i = 1; i < V; ++i)
            lengths[s] += glm::length(strands.rest[s * V + i] - strands.rest[s * V + i - 1]);
    auto parts = [&](uint32_t s, uint32_t o, float rootDistance) {
        float apart = glm::length(strands.rest[size_t(s) * V + probe] - strands.rest[size_t(o) * V + probe]);
        return apart > 3.0f * rootDistance + 0.1f * lengths[s];
    };
    for (uint32_t s = 0; s < n; ++s) {
        glm::vec3 p = strands.rest[size_t(s) * V];
        glm::ivec3 c = cellOf(p);
        bool skipped = false;
        uint32_t best[2] = {s, s};
        float bestD[2] = {1e30f, 1e30f};
        size_t seen = 0; // other guides looked at: once all of them, nothing closer is left
        // Grow the search ring until two neighbours are found and no closer one can lie outside it
        // (the ring clamped to the grid: roots on a line or a plane make a grid one cell thick).
        for (int r = 1;; ++r) {
            for (int z = std::max(c.z - r, 0); z <= std::min(c.z + r, dims.z - 1); ++z)
                for (int y = std::max(c.y - r, 0); y <= std::min(c.y + r, dims.y - 1); ++y)
                    for (int x = std::max(c.x - r, 0); x <= std::min(c.x + r, dims.x - 1); ++x) {
                        int ring = std::max({std::abs(x - c.x), std::abs(y - c.y), std::abs(z - c.z)});
                        if (r > 1 && ring < r - 1)
                            continue;                     // inner cells were searched in earlier rings
                        bool first = r == 1 || ring == r; // a cell of ring r - 1 is looked at again
                        for (uint32_t o : grid[key({x, y, z})]) {
                            if (o == s)
                                continue;
                            seen += first ? 1 : 0;
                            float d = glm::length(strands.rest[size_t(o) * V] - p);
                            if (d < bestD[1] && parts(s, o, d)) {
                                skipped = true;
                                continue;
                            }
                            if (d < bestD[0] && o != best[0] && o != best[1]) {
                                best[1] = best[0];
                                bestD[1] = bestD[0];
                                best[0] = o;
                                bestD[0] = d;
                            } else if (d < bestD[1] && o != best[0] && o != best[1]) {
                                best[1] = o;
                                bestD[1] = d;
                            }
                        }
                    }
            bool covered = c.x - r <= 0 && c.y - r <= 0 && c.z - r <= 0 && c.x + r >= dims.x - 1 &&
                           c.y + r >= dims.y - 1 && c.z + r >= dims.z - 1;
            // Where parting neighbours were skipped, the search stops a few rings out (a guide whose
            // every neighbour parts from it is its own neighbour: its strands follow it alone).
            if ((bestD[1] < 1e29f && bestD[1] <= float(r - 1) * cell) || covered || seen + 1 >= n ||
                (skipped && r >= 4))
                break;
        }
        out[s] = glm::uvec4(s, bestD[0] < 1e29f ? best[0] : s, bestD[1] < 1e29f ? best[1] : s,
                            gpu::packGuideShape(lengths[s], strands.widthScale.empty() ? 1.0f : strands.widthScale[s]));
    }
    return out;
}

} // namespace wisp
