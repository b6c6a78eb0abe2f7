// renderer/reference/bvh.h: the bounding-volume hierarchy the path tracer walks (shared/trace_bvh.h),
// built on the CPU over the drawn strands' segments and the meshes' triangles, flattened into the
// nodes and primitive list the GPU reads. Built on the CPU because the reference renders one fixed
// frame for seconds to minutes: a build of a few million primitives once (about a second) is
// nothing beside it, and a CPU build is deterministic and needs no kernels of its own. No Vulkan.
#pragma once

#include "shaders/shared/trace_bvh.h"

#include <cstdint>
#include <span>
#include <vector>

namespace wisp::reference {

// Leaves hold at most this many primitives; the tree is at most kBvhMaxDepth deep (the walk's stack).
inline constexpr uint32_t kBvhLeafSize = 4;
inline constexpr uint32_t kBvhMaxDepth = gpu::kTraceStackSize;

struct Bvh {
    std::vector<gpu::BvhNode> nodes; // nodes[0] the root (absent when there are no primitives)
    std::vector<uint32_t> prims;     // primitive numbers (segments first, then triangles), leaf by leaf
    uint32_t depth = 0;              // the deepest leaf's depth (root 0)
};

// Binned surface-area heuristic (Wald 2007, "On fast Construction of SAH-based Bounding Volume
// Hierarchies": 16 bins of the centroids per axis), an even split by count where every centroid
// falls into one bin, and splits at the median beyond depth 32 so the depth stays bounded.
Bvh buildBvh(std::span<const gpu::TraceSegment> segments, std::span<const gpu::TraceTriangle> triangles);

// The buffers' view of a tree and its primitives, for the shared walk on the CPU.
gpu::TraceBuffers traceBuffers(const Bvh& bvh, std::span<const gpu::TraceSegment> segments,
                               std::span<const gpu::TraceTriangle> triangles);

} // namespace wisp::reference
