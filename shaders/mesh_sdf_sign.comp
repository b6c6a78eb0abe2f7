#version 460
// mesh_sdf_sign.comp: one thread per row of nodes along x: the nodes holding a key take their
// triangle's exact signed distance, the others +-band, signed as the row's previous node with a
// key (the next before any; none: outside) (shared/mesh_sdf.h). CPU twin: physics/mesh_sdf.cpp.
#extension GL_GOOGLE_include_directive : require
#include "shared/mesh_sdf.h"

layout(local_size_x = SDF_GROUP_SIZE) in;
layout(std430, set = 0, binding = kSdfBindingTriangles) readonly buffer Triangles { SdfTriangle triangles[]; };
layout(std430, set = 0, binding = kSdfBindingKeys) readonly buffer Keys { uint keys[]; };
layout(std430, set = 0, binding = kSdfBindingField) writeonly buffer Field { float field[]; };
layout(push_constant) uniform Push { SdfGrid grid; };

void main()
{
    uint row = gl_GlobalInvocationID.x;
    if (row >= grid.dims.y * grid.dims.z)
        return;
    uint y = row % grid.dims.y, z = row / grid.dims.y;
    float sign = 0.0;
    float first = 1.0; // the sign before the row's first node with a key: that node's
    for (uint x = 0u; x < grid.dims.x; ++x) {
        uvec3 node = uvec3(x, y, z);
        uint key = keys[sdfNodeIndex(grid, node)];
        if (key == kSdfNoKey)
            continue;
        float d = sdfBandValue(grid, triangles[sdfKeyTriangle(grid, key)], node);
        first = d < 0.0 ? -1.0 : 1.0;
        break;
    }
    sign = first;
    for (uint x = 0u; x < grid.dims.x; ++x) {
        uvec3 node = uvec3(x, y, z);
        uint index = sdfNodeIndex(grid, node);
        uint key = keys[index];
        if (key == kSdfNoKey) {
            field[index] = sign * grid.band.x;
            continue;
        }
        float d = sdfBandValue(grid, triangles[sdfKeyTriangle(grid, key)], node);
        sign = d < 0.0 ? -1.0 : 1.0;
        field[index] = d;
    }
}
