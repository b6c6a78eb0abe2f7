#version 460
// mesh_raster.comp: one workgroup per triangle of one object (push.object), its threads over the
// pixels of the triangle's bounds: at every sample the triangle covers, kPhase 0 keeps the nearest
// depth (atomicMin of its bits), kPhase 1 the smallest id among the triangles at that depth (the
// same winner every frame, whatever order the atomics come in). See shared/mesh_raster.h.
#extension GL_GOOGLE_include_directive : require
#include "shared/frame_params.h"
#include "shared/mesh_raster.h"

layout(local_size_x = 64) in;
layout(constant_id = 0) const uint kPhase = 0u;
layout(set = 0, binding = kMeshRasterBindingFrame) uniform FrameBlock { FrameParams frame; };
layout(push_constant) uniform PushBlock { MeshRasterPush push; };
layout(set = 0, binding = kMeshRasterBindingVertices, std430) readonly buffer Vertices { float vertices[]; };
layout(set = 0, binding = kMeshRasterBindingIndices, std430) readonly buffer Indices { uint indices[]; };
layout(set = 0, binding = kMeshRasterBindingDepth, std430) buffer Depth { uint depth[]; };
layout(set = 0, binding = kMeshRasterBindingIds, std430) buffer Ids { uint ids[]; };

vec4 clipVertex(uint index, mat4 model)
{
    uint v = index * kMeshVertexFloats;
    vec3 p = vec3(vertices[v], vertices[v + 1u], vertices[v + 2u]);
    return frame.viewProjection * (model * vec4(p, 1.0));
}

void main()
{
    uint triangle = gl_WorkGroupID.x + gl_WorkGroupID.y * gl_NumWorkGroups.x;
    if (triangle >= push.triangles)
        return;
    mat4 model = meshObjectModel(push.object, frame.headTransform, push.sphere, push.marker);
    vec2 size = vec2(push.width, push.height);
    MeshTriangle t = setupMeshTriangle(clipVertex(indices[3u * triangle], model),
                                       clipVertex(indices[3u * triangle + 1u], model),
                                       clipVertex(indices[3u * triangle + 2u], model), size);
    if (t.det == 0.0)
        return;
    int x0 = max(int(floor(t.bounds.x)), 0), y0 = max(int(floor(t.bounds.y)), 0);
    int x1 = min(int(floor(t.bounds.z)), int(push.width) - 1), y1 = min(int(floor(t.bounds.w)), int(push.height) - 1);
    if (x1 < x0 || y1 < y0)
        return;
    uint columns = uint(x1 - x0 + 1), pixels = columns * uint(y1 - y0 + 1);
    uint id = packMeshId(push.object, triangle);
    for (uint i = gl_LocalInvocationID.x; i < pixels; i += kMeshRasterGroupSize) {
        ivec2 pixel = ivec2(x0 + int(i % columns), y0 + int(i / columns));
        uint first = (uint(pixel.y) * push.width + uint(pixel.x)) * push.samples;
        for (uint s = 0u; s < push.samples; ++s) {
            float d = meshSampleDepth(t, vec2(pixel) + meshSamplePosition(s, push.samples), size);
            if (d > 1.0)
                continue;
            if (kPhase == 0u)
                atomicMin(depth[first + s], floatBitsToUint(d));
            else if (depth[first + s] == floatBitsToUint(d))
                atomicMin(ids[first + s], id);
        }
    }
}
