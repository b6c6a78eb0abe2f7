#version 460
// mesh_sdf_splat.comp: one thread per work item (a triangle and a box of nodes around it): each
// node of the box within the band of the triangle takes the smaller of its key and the node's
// (shared/mesh_sdf.h). CPU twin: physics/mesh_sdf.cpp.
#extension GL_GOOGLE_include_directive : require
#include "shared/mesh_sdf.h"

layout(local_size_x = SDF_GROUP_SIZE) in;
layout(std430, set = 0, binding = kSdfBindingTriangles) readonly buffer Triangles { SdfTriangle triangles[]; };
layout(std430, set = 0, binding = kSdfBindingItems) readonly buffer Items { uvec4 items[]; };
layout(std430, set = 0, binding = kSdfBindingKeys) buffer Keys { uint keys[]; };
layout(push_constant) uniform Push { SdfGrid grid; };

void main()
{
    uint i = gl_GlobalInvocationID.x;
    if (i >= grid.counts.x)
        return;
    uvec4 item = items[i];
    SdfTriangle t = triangles[item.x];
    uvec3 lo = sdfItemLow(item), hi = sdfItemHigh(item);
    for (uint z = lo.z; z <= hi.z; ++z)
        for (uint y = lo.y; y <= hi.y; ++y)
            for (uint x = lo.x; x <= hi.x; ++x) {
                uvec3 node = uvec3(x, y, z);
                uint key = sdfSplatKey(grid, t, item.x, node);
                if (key != kSdfNoKey)
                    atomicMin(keys[sdfNodeIndex(grid, node)], key);
            }
}
