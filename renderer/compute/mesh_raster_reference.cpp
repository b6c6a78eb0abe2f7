// renderer/compute/mesh_raster_reference.cpp: the compute meshes' kernels, one loop per kernel.
#include "renderer/compute/mesh_raster_reference.h"

#include <algorithm>
#include <bit>
#include <cmath>

namespace wisp::reference {

using gpu::MeshTriangle;

namespace {

glm::vec3 vertexPosition(const MeshObject& o, uint32_t v)
{
    const float* f = &o.vertices[size_t(v) * gpu::kMeshVertexFloats];
    return {f[0], f[1], f[2]};
}

MeshTriangle setup(const MeshObject& o, uint32_t triangle, const glm::mat4& model, const gpu::FrameParams& frame,
                   glm::vec2 size)
{
    glm::vec4 c[3];
    for (uint32_t k = 0; k < 3; ++k)
        c[k] = frame.viewProjection * (model * glm::vec4(vertexPosition(o, o.indices[3 * triangle + k]), 1.0f));
    return gpu::setupMeshTriangle(c[0], c[1], c[2], size);
}

} // namespace

MeshSamples rasterMeshes(const gpu::MeshRasterPush& push, const gpu::FrameParams& frame,
                         const std::vector<MeshObject>& objects)
{
    size_t count = size_t(push.width) * push.height * push.samples;
    MeshSamples out{std::vector<uint32_t>(count, gpu::kMeshDepthClear), std::vector<uint32_t>(count, gpu::kNoMesh)};
    glm::vec2 size(float(push.width), float(push.height));
    for (int phase = 0; phase < 2; ++phase) {
        for (const MeshObject& o : objects) {
            glm::mat4 model = gpu::meshObjectModel(o.object, frame.headTransform, push.sphere, push.marker);
            uint32_t triangles = uint32_t(o.indices.size() / 3);
            for (uint32_t triangle = 0; triangle < triangles; ++triangle) {
                MeshTriangle t = setup(o, triangle, model, frame, size);
                if (t.det == 0.0f)
                    continue;
                int x0 = std::max(int(std::floor(t.bounds.x)), 0), y0 = std::max(int(std::floor(t.bounds.y)), 0);
                int x1 = std::min(int(std::floor(t.bounds.z)), int(push.width) - 1);
                int y1 = std::min(int(std::floor(t.bounds.w)), int(push.height) - 1);
                uint32_t id = gpu::packMeshId(o.object, triangle);
                for (int y = y0; y <= y1; ++y)
                    for (int x = x0; x <= x1; ++x) {
                        size_t first = (size_t(y) * push.width + size_t(x)) * push.samples;
                        for (uint32_t s = 0; s < push.samples; ++s) {
                            float d = gpu::meshSampleDepth(
                                t, glm::vec2(x, y) + gpu::meshSamplePosition(s, push.samples), size);
                            if (d > 1.0f)
                                continue;
                            uint32_t bits = std::bit_cast<uint32_t>(d);
                            if (phase == 0)
                                out.depth[first + s] = std::min(out.depth[first + s], bits);
                            else if (out.depth[first + s] == bits)
                                out.ids[first + s] = std::min(out.ids[first + s], id);
                        }
                    }
            }
        }
    }
    return out;
}

std::vector<glm::vec3> shadeMeshes(const gpu::MeshRasterPush& push, const gpu::FrameParams& frame,
                                   const MeshObject& head, const MeshObject& sphere, const MeshSamples& samples)
{
    glm::vec2 size(float(push.width), float(push.height));
    std::vector<glm::vec3> out(size_t(push.width) * push.height);
    for (uint32_t y = 0; y < push.height; ++y)
        for (uint32_t x = 0; x < push.width; ++x) {
            size_t first = (size_t(y) * push.width + x) * push.samples;
            glm::vec2 centre = glm::vec2(x, y) + 0.5f;
            glm::vec3 color(0.0f);
            uint32_t covered = 0;
            for (uint32_t s = 0; s < push.samples; ++s) {
                uint32_t id = samples.ids[first + s];
                bool seen = id == gpu::kNoMesh;
                for (uint32_t e = 0; e < s; ++e)
                    seen = seen || samples.ids[first + e] == id;
                if (seen)
                    continue;
                uint32_t count = 0;
                for (uint32_t e = s; e < push.samples; ++e)
                    count += samples.ids[first + e] == id ? 1 : 0;
                uint32_t object = id >> 30, triangle = id & 0x3fffffffu;
                const MeshObject& o = object == gpu::kMeshObjectHead ? head : sphere;
                glm::mat4 model = gpu::meshObjectModel(object, frame.headTransform, push.sphere, push.marker);
                MeshTriangle t = setup(o, triangle, model, frame, size);
                glm::vec3 b = gpu::meshTriangleBarycentrics(t, centre, size);
                glm::vec3 position(0.0f), normal(0.0f);
                float scalp = 0.0f;
                for (uint32_t k = 0; k < 3; ++k) {
                    const float* f = &o.vertices[size_t(o.indices[3 * triangle + k]) * gpu::kMeshVertexFloats];
                    position += b[int(k)] * glm::vec3(f[0], f[1], f[2]);
                    normal += b[int(k)] * glm::vec3(f[3], f[4], f[5]);
                    scalp += b[int(k)] * f[6];
                }
                glm::vec3 world = glm::vec3(model * glm::vec4(position, 1.0f));
                normal = glm::transpose(glm::inverse(glm::mat3(model))) * normal;
                if (object != gpu::kMeshObjectHead)
                    scalp = 0.0f;
                glm::vec3 albedo = object == gpu::kMeshObjectHead     ? push.headAlbedo
                                   : object == gpu::kMeshObjectSphere ? gpu::kSphereAlbedo
                                                                      : gpu::kMarkerAlbedo;
                float roughness = object == gpu::kMeshObjectHead     ? push.headRoughness
                                  : object == gpu::kMeshObjectSphere ? gpu::kSphereRoughness
                                                                     : gpu::kMarkerRoughness;
                color += float(count) * gpu::meshSurfaceColor(frame, glm::normalize(normal),
                                                              glm::normalize(frame.cameraPosition - world),
                                                              1.0f, // the key's visibility: the twin has no shadows
                                                              albedo, roughness, push.scalpAlbedo,
                                                              push.scalpStrength * std::clamp(scalp, 0.0f, 1.0f));
                covered += count;
            }
            color += float(push.samples - covered) * gpu::frameBackground(frame, centre.y);
            out[size_t(y) * push.width + x] = color / float(push.samples);
        }
    return out;
}

} // namespace wisp::reference
