// physics/strands.cpp: the strand set's bookkeeping.
#include "physics/strands.h"

#include "core/error.h"

#include <algorithm>
#include <stdexcept>

namespace wisp {

void StrandSet::add(const std::vector<glm::vec3>& points, uint32_t part, uint32_t pinnedRoot, bool pinnedTip)
{
    if (points.size() != verticesPerStrand)
        throw std::logic_error("StrandSet::add: strand has " + std::to_string(points.size()) + " points, expected " +
                               std::to_string(verticesPerStrand));
    for (size_t i = 1; i < points.size(); ++i)
        if (!(glm::length(points[i] - points[i - 1]) > 0.0f))
            throw UserError("hair strand " + std::to_string(strands.size()) + " has a zero-length segment (" +
                            std::to_string(i - 1) + " to " + std::to_string(i) + "): cannot simulate it");
    uint32_t index = static_cast<uint32_t>(strands.size());
    strands.push_back({.part = part,
                       .pinnedRoot = std::clamp<uint32_t>(pinnedRoot, 1, verticesPerStrand - 1),
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

}  // namespace wisp
