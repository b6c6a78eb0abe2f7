// renderer/reference/bvh.cpp: the binned-SAH build of the path tracer's hierarchy (see bvh.h).
#include "renderer/reference/bvh.h"

#include <algorithm>
#include <array>
#include <stdexcept>

namespace wisp::reference {

namespace {

struct Box {
    glm::vec3 lo{3e38f};
    glm::vec3 hi{-3e38f};
    void grow(glm::vec3 p)
    {
        lo = glm::min(lo, p);
        hi = glm::max(hi, p);
    }
    void grow(const Box& b)
    {
        lo = glm::min(lo, b.lo);
        hi = glm::max(hi, b.hi);
    }
    float area() const
    {
        glm::vec3 e = glm::max(hi - lo, glm::vec3(0.0f));
        return 2.0f * (e.x * e.y + e.y * e.z + e.z * e.x);
    }
};

struct Prim {
    Box box;
    glm::vec3 centre;
    uint32_t id;
};

constexpr int kBins = 16;
constexpr uint32_t kSahDepth = 32; // deeper: median splits, so the depth stays within kBvhMaxDepth

class Builder {
public:
    explicit Builder(std::vector<Prim> prims) : prims_(std::move(prims)) {}

    Bvh build()
    {
        Bvh bvh;
        if (prims_.empty())
            return bvh;
        nodes_.push_back({});
        split(0, 0, uint32_t(prims_.size()), 0);
        bvh.nodes = std::move(nodes_);
        for (const Prim& p : prims_)
            bvh.prims.push_back(p.id);
        bvh.depth = depth_;
        return bvh;
    }

private:
    void split(uint32_t node, uint32_t begin, uint32_t end, uint32_t depth)
    {
        Box box, centres;
        for (uint32_t i = begin; i < end; ++i) {
            box.grow(prims_[i].box);
            centres.grow(prims_[i].centre);
        }
        nodes_[node].lo = box.lo;
        nodes_[node].hi = box.hi;
        uint32_t count = end - begin;
        depth_ = std::max(depth_, depth);
        if (count <= kBvhLeafSize) {
            nodes_[node].first = begin;
            nodes_[node].count = count;
            return;
        }
        if (depth + 1 >= kBvhMaxDepth)
            throw std::length_error("the path tracer's hierarchy would be deeper than its walk's stack");
        uint32_t mid = depth < kSahDepth ? sahSplit(begin, end, centres) : begin + count / 2;
        if (mid == begin || mid == end || depth >= kSahDepth) {
            // Every centroid in one bin, or past the SAH's depth: half the primitives each side,
            // by centroid along the widest axis.
            glm::vec3 e = centres.hi - centres.lo;
            int axis = e.x >= e.y && e.x >= e.z ? 0 : (e.y >= e.z ? 1 : 2);
            mid = begin + count / 2;
            std::nth_element(prims_.begin() + begin, prims_.begin() + mid, prims_.begin() + end,
                             [axis](const Prim& a, const Prim& b) {
                                 return a.centre[axis] != b.centre[axis] ? a.centre[axis] < b.centre[axis]
                                                                         : a.id < b.id;
                             });
        }
        uint32_t left = uint32_t(nodes_.size());
        nodes_.push_back({});
        nodes_.push_back({});
        nodes_[node].first = left;
        nodes_[node].count = 0;
        split(left, begin, mid, depth + 1);
        split(left + 1, mid, end, depth + 1);
    }

    // The cheapest of the 3 x (kBins - 1) planes between bins by the SAH cost
    // area(L) n(L) + area(R) n(R); primitives partitioned by it. Returns the split point, or begin
    // when no plane separates them.
    uint32_t sahSplit(uint32_t begin, uint32_t end, const Box& centres)
    {
        float best = 3e38f;
        int bestAxis = -1, bestPlane = 0;
        for (int axis = 0; axis < 3; ++axis) {
            float extent = centres.hi[axis] - centres.lo[axis];
            if (extent <= 0.0f)
                continue;
            std::array<Box, kBins> bins;
            std::array<uint32_t, kBins> counts{};
            for (uint32_t i = begin; i < end; ++i) {
                int b = bin(prims_[i].centre[axis], centres.lo[axis], extent);
                bins[size_t(b)].grow(prims_[i].box);
                counts[size_t(b)] += 1;
            }
            std::array<float, kBins> rightCost{};
            Box right;
            uint32_t rightCount = 0;
            for (int b = kBins - 1; b > 0; --b) {
                right.grow(bins[size_t(b)]);
                rightCount += counts[size_t(b)];
                rightCost[size_t(b)] = rightCount > 0 ? right.area() * float(rightCount) : 0.0f;
            }
            Box left;
            uint32_t leftCount = 0;
            for (int plane = 1; plane < kBins; ++plane) { // left holds bins [0, plane)
                left.grow(bins[size_t(plane - 1)]);
                leftCount += counts[size_t(plane - 1)];
                float cost = (leftCount > 0 ? left.area() * float(leftCount) : 0.0f) + rightCost[size_t(plane)];
                if (leftCount > 0 && leftCount < end - begin && cost < best) {
                    best = cost;
                    bestAxis = axis;
                    bestPlane = plane;
                }
            }
        }
        if (bestAxis < 0)
            return begin;
        float lo = centres.lo[bestAxis], extent = centres.hi[bestAxis] - lo;
        auto middle = std::stable_partition(prims_.begin() + begin, prims_.begin() + end, [&](const Prim& p) {
            return bin(p.centre[bestAxis], lo, extent) < bestPlane;
        });
        return uint32_t(middle - prims_.begin());
    }

    static int bin(float c, float lo, float extent)
    {
        return std::clamp(int(float(kBins) * (c - lo) / extent), 0, kBins - 1);
    }

    std::vector<Prim> prims_;
    std::vector<gpu::BvhNode> nodes_;
    uint32_t depth_ = 0;
};

} // namespace

Bvh buildBvh(std::span<const gpu::TraceSegment> segments, std::span<const gpu::TraceTriangle> triangles)
{
    std::vector<Prim> prims;
    prims.reserve(segments.size() + triangles.size());
    for (size_t i = 0; i < segments.size(); ++i) {
        const gpu::TraceSegment& s = segments[i];
        Prim p{.box = {}, .centre = 0.5f * (s.a + s.b), .id = uint32_t(i)};
        // Rounded outward: a capsule far thinner than its coordinates' size stays inside its box.
        glm::vec3 lo = glm::min(s.a, s.b), hi = glm::max(s.a, s.b);
        p.box.grow(lo - s.radius - (glm::abs(lo) + s.radius) * 2.4e-7f);
        p.box.grow(hi + s.radius + (glm::abs(hi) + s.radius) * 2.4e-7f);
        prims.push_back(p);
    }
    for (size_t i = 0; i < triangles.size(); ++i) {
        const gpu::TraceTriangle& t = triangles[i];
        Prim p{.box = {}, .centre = glm::vec3(t.p0 + t.p1 + t.p2) / 3.0f, .id = uint32_t(segments.size() + i)};
        p.box.grow(glm::vec3(t.p0));
        p.box.grow(glm::vec3(t.p1));
        p.box.grow(glm::vec3(t.p2));
        prims.push_back(p);
    }
    return Builder(std::move(prims)).build();
}

gpu::TraceBuffers traceBuffers(const Bvh& bvh, std::span<const gpu::TraceSegment> segments,
                               std::span<const gpu::TraceTriangle> triangles)
{
    return {.nodes = bvh.nodes.data(),
            .prims = bvh.prims.data(),
            .segments = segments.data(),
            .triangles = triangles.data(),
            .segmentCount = uint32_t(segments.size()),
            .nodeCount = uint32_t(bvh.nodes.size())};
}

} // namespace wisp::reference
