#version 460
// strands_bin.comp: one thread per strand segment; the screen tiles (kRasterTileSize square) its
// ribbon touches, walked row by row (shared/strand_raster.h segmentRowSpan), so a long diagonal
// segment visits the tiles along it, not its bounding box. Specialization constant 0 chooses:
//   false (strands.count): counts the segment in each tile (tileCounts) and the segments drawn
//   true  (strands.bin):   writes the segment's index into each tile's bin at tileOffsets[tile] +
//                          a cursor (tileCounts, zeroed by the scan); slots past the bins'
//                          capacity are skipped (the scan has counted them as overflow)
// Segments with an end behind the camera or outside the depth range are not drawn.
#extension GL_GOOGLE_include_directive : require
#include "shared/strand_raster.h"

layout(local_size_x = 64) in;  // kRasterGroupSize
layout(constant_id = 0) const bool kWrite = false;
layout(push_constant) uniform PushBlock { StrandRasterPush push; };
layout(set = 0, binding = kRasterBindingVertices, std430) readonly buffer Vertices { vec4 vertices[]; };
layout(set = 0, binding = kRasterBindingTileCounts, std430) buffer TileCounts { uint tileCounts[]; };
layout(set = 0, binding = kRasterBindingTileOffsets, std430) readonly buffer TileOffsets { uint tileOffsets[]; };
layout(set = 0, binding = kRasterBindingBins, std430) writeonly buffer Bins { uint bins[]; };
layout(set = 0, binding = kRasterBindingCounters, std430) buffer Counters { RasterCounters counters; };

shared uint groupSegments;

void main()
{
    if (gl_LocalInvocationIndex == 0u)
        groupSegments = 0u;
    barrier();

    uint segment = linearInvocation(gl_GlobalInvocationID, gl_NumWorkGroups.x * gl_WorkGroupSize.x);
    bool drawn = false;
    if (segment < push.segmentCount) {
        uint v = segment / push.divisions * (push.divisions + 1u) + segment % push.divisions;
        vec4 a = vertices[v];
        vec4 b = vertices[v + 1u];
        drawn = a.w >= 0.0 && b.w >= 0.0 && min(a.z, b.z) >= 0.0 && max(a.z, b.z) <= 1.0;
        if (drawn) {
            float r = segmentReach(a.w, b.w);
            float size = float(kRasterTileSize);
            int ty0 = max(int(floor((min(a.y, b.y) - r) / size)), 0);
            int ty1 = min(int(floor((max(a.y, b.y) + r) / size)), int(push.tilesY) - 1);
            drawn = false;
            for (int ty = ty0; ty <= ty1; ++ty) {
                vec2 span = segmentRowSpan(a.xy, b.xy, r, float(ty) * size, float(ty + 1) * size);
                if (span.x > span.y)
                    continue;
                int tx0 = max(int(floor(span.x / size)), 0);
                int tx1 = min(int(floor(span.y / size)), int(push.tilesX) - 1);
                for (int tx = tx0; tx <= tx1; ++tx) {
                    uint tile = uint(ty) * push.tilesX + uint(tx);
                    drawn = true;
                    if (kWrite) {
                        uint slot = tileOffsets[tile] + atomicAdd(tileCounts[tile], 1u);
                        if (slot < push.binCapacity)
                            bins[slot] = segment;
                    } else {
                        atomicAdd(tileCounts[tile], 1u);
                    }
                }
            }
        }
    }
    if (!kWrite && drawn)
        atomicAdd(groupSegments, 1u);
    barrier();
    if (!kWrite && gl_LocalInvocationIndex == 0u && groupSegments > 0u)
        atomicAdd(counters.segments, groupSegments);
}
