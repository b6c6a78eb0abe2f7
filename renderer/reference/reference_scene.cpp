// renderer/reference/reference_scene.cpp: the path tracer's scene and block, and its CPU twin (see
// the header). The twin's loop body is reference_trace.comp's: referenceSample of the shared header.
#include "renderer/reference/reference_scene.h"

#include <glm/gtc/matrix_inverse.hpp>

namespace wisp::reference {

ReferenceScene buildReferenceScene(const gpu::StrandRasterPush& push, const DrawnStrands& strands,
                                   const gpu::FrameParams& frame, const gpu::MeshRasterPush& meshes,
                                   const std::vector<MeshObject>& objects)
{
    ReferenceScene scene;
    scene.divisions = push.divisions;
    uint32_t perStrand = push.divisions + 1;
    uint32_t drawn = uint32_t(strands.positions.size() / perStrand);
    scene.segments.reserve(size_t(drawn) * push.divisions);
    for (uint32_t k = 0; k < drawn; ++k) {
        uint32_t guide = k / push.drawnPerGuide, s = k % push.drawnPerGuide;
        for (uint32_t i = 0; i < push.divisions; ++i) {
            size_t a = size_t(k) * perStrand + i;
            // The capsule's radius: half the mean of the ends' drawn widths (trace.h says why).
            scene.segments.push_back({.a = strands.positions[a],
                                      .radius = 0.25f * (strands.widths[a] + strands.widths[a + 1]),
                                      .b = strands.positions[a + 1],
                                      .strand = guide * push.strandsPerGuide + s});
        }
    }
    for (const MeshObject& o : objects) {
        if (o.object == gpu::kMeshObjectSphere && meshes.sphere.w <= 0.0f)
            continue;
        if (o.object == gpu::kMeshObjectMarker && meshes.marker.w <= 0.0f)
            continue;
        glm::mat4 model = gpu::meshObjectModel(o.object, frame.headTransform, meshes.sphere, meshes.marker);
        glm::mat3 normalMatrix = glm::inverseTranspose(glm::mat3(model));
        auto corner = [&](uint32_t v, glm::vec4& p, glm::vec4& n) {
            const float* x = &o.vertices[size_t(v) * gpu::kMeshVertexFloats];
            p = glm::vec4(glm::vec3(model * glm::vec4(x[0], x[1], x[2], 1.0f)), x[6]);
            n = glm::vec4(glm::normalize(normalMatrix * glm::vec3(x[3], x[4], x[5])), float(o.object));
        };
        for (size_t i = 0; i + 2 < o.indices.size(); i += 3) {
            gpu::TraceTriangle t{};
            corner(o.indices[i], t.p0, t.n0);
            corner(o.indices[i + 1], t.p1, t.n1);
            corner(o.indices[i + 2], t.p2, t.n2);
            scene.triangles.push_back(t);
        }
    }
    scene.bvh = buildBvh(scene.segments, scene.triangles);
    if (!scene.bvh.nodes.empty())
        scene.extent = glm::length(scene.bvh.nodes[0].hi - scene.bvh.nodes[0].lo);
    return scene;
}

gpu::ReferenceParams referenceParams(const ReferenceScene& scene, const gpu::FrameParams& frame,
                                     const gpu::MeshRasterPush& meshes, uint32_t maxBounces, uint32_t seed)
{
    return {.frame = frame,
            .inverseViewProjection = glm::inverse(frame.viewProjection),
            .headAlbedo = meshes.headAlbedo,
            .headRoughness = meshes.headRoughness,
            .scalpAlbedo = meshes.scalpAlbedo,
            .scalpStrength = meshes.scalpStrength,
            .width = uint32_t(frame.viewportWidth),
            .height = uint32_t(frame.viewportHeight),
            .segmentCount = uint32_t(scene.segments.size()),
            .nodeCount = uint32_t(scene.bvh.nodes.size()),
            .divisions = scene.divisions,
            .maxBounces = maxBounces,
            .seed = seed,
            // A path leaving a mesh starts this far off it: well above float's resolution at the
            // scene's size, far below any detail drawn.
            .surfaceOffset = 1e-5f * scene.extent};
}

PixelSums tracePixel(const ReferenceScene& scene, const gpu::ReferenceParams& params, glm::uvec2 pixel, uint32_t first,
                     uint32_t count)
{
    gpu::TraceBuffers buffers = scene.buffers();
    PixelSums out;
    for (uint32_t k = 0; k < count; ++k) {
        uint32_t sample = first + k;
        out.sums[sample & 1u] += gpu::referenceSample(buffers, params, pixel, sample, out.rays);
    }
    return out;
}

} // namespace wisp::reference
