// renderer/compute/mesh_raster_reference.h: the compute meshes' kernels (shaders/mesh_raster.comp and
// mesh_shade.comp) in plain C++ over the same shared math (shaders/shared/mesh_raster.h), one loop
// where a kernel has one thread (or workgroup) per item. tests/test_strand_raster.cpp runs both on
// the same input and compares. No Vulkan.
#pragma once

#include "shaders/shared/frame_params.h"
#include "shaders/shared/mesh_raster.h"

#include <glm/glm.hpp>

#include <cstdint>
#include <vector>

namespace wisp::reference {

// One object as the kernels read it: kMeshVertexFloats floats per vertex (position, normal,
// scalp weight) and three indices per triangle.
struct MeshObject {
    uint32_t object = gpu::kMeshObjectHead; // kMeshObject*: its pose and surface
    std::vector<float> vertices;
    std::vector<uint32_t> indices;
};

// Every sample's depth (float bits, kMeshDepthClear where none) and triangle (packMeshId, kNoMesh),
// pixel-major (pixel * samples + s).
struct MeshSamples {
    std::vector<uint32_t> depth;
    std::vector<uint32_t> ids;
};

// mesh_raster.comp, both phases, over the objects in order.
MeshSamples rasterMeshes(const gpu::MeshRasterPush& push, const gpu::FrameParams& frame,
                         const std::vector<MeshObject>& objects);

// mesh_shade.comp with the key light unoccluded (the twin does not sample the light's maps:
// compare with shadows off): every pixel's resolved colour, row-major. `head` and `sphere` are
// the objects' vertices and triangles (the marker and the collision sphere share the sphere's).
std::vector<glm::vec3> shadeMeshes(const gpu::MeshRasterPush& push, const gpu::FrameParams& frame,
                                   const MeshObject& head, const MeshObject& sphere, const MeshSamples& samples);

} // namespace wisp::reference
