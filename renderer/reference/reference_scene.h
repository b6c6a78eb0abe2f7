// renderer/reference/reference_scene.h: what the path tracer traces, built on the CPU from what the
// real-time frame draws: the drawn strands (renderer/compute/strand_raster_reference.h
// placeStrands: the points strands_generate.comp places, before it projects them) as one capsule per
// segment, the meshes (the head, the collision sphere and the light's marker where the frame shows
// them, posed as mesh_raster.h meshObjectModel poses them) as triangles, and the hierarchy over
// both; and the uniform block of the path tracer for the frame. No Vulkan.
#pragma once

#include "renderer/compute/mesh_raster_reference.h"
#include "renderer/compute/strand_raster_reference.h"
#include "renderer/reference/bvh.h"
#include "shaders/shared/reference_path.h"

#include <array>
#include <cstdint>
#include <vector>

namespace wisp::reference {

struct ReferenceScene {
    std::vector<gpu::TraceSegment> segments; // (guide * drawnPerGuide + s) * D + i
    std::vector<gpu::TraceTriangle> triangles;
    Bvh bvh;
    uint32_t divisions = 1; // segments per strand
    float extent = 1.0f;    // the scene's bounding box diagonal (asset units)

    gpu::TraceBuffers buffers() const { return traceBuffers(bvh, segments, triangles); }
};

// The drawn strands (`push`: the camera's StrandRasterPush, whose strands are drawn; D + 1 vertices a
// strand), and each mesh object drawn: `meshes` gives the sphere's and the marker's placement
// (radius 0: not drawn), `frame` the head's pose.
ReferenceScene buildReferenceScene(const gpu::StrandRasterPush& push, const DrawnStrands& strands,
                                   const gpu::FrameParams& frame, const gpu::MeshRasterPush& meshes,
                                   const std::vector<MeshObject>& objects);

// The path tracer's block for a `width` x `height` frame of `frame` (its camera and lights).
gpu::ReferenceParams referenceParams(const ReferenceScene& scene, const gpu::FrameParams& frame,
                                     const gpu::MeshRasterPush& meshes, uint32_t maxBounces, uint32_t seed);

// The CPU twin of reference_trace.comp for one pixel: the sums of samples [first, first + count),
// split as the kernel splits them (sums[0] the even samples' radiance and backdrop count, sums[1] the
// odd), and the rays they cast.
struct PixelSums {
    std::array<glm::vec4, 2> sums{glm::vec4(0.0f), glm::vec4(0.0f)};
    uint32_t rays = 0;
};
PixelSums tracePixel(const ReferenceScene& scene, const gpu::ReferenceParams& params, glm::uvec2 pixel, uint32_t first,
                     uint32_t count);

} // namespace wisp::reference
