#version 460
// strands_scan.comp: one workgroup of kRasterScanGroupSize threads turns the tiles' segment
// counts into the first slot of each tile's bin (an exclusive prefix sum: each thread sums a run
// of tiles, the workgroup scans those sums, each thread writes its run's offsets), the total
// after the last tile, and the frame's counters: the pairs needed, the bins' capacity and what
// does not fit. The counts are zeroed to serve as the bin pass's write cursors.
#extension GL_GOOGLE_include_directive : require
#include "shared/strand_raster.h"

layout(local_size_x = 1024) in;  // kRasterScanGroupSize
layout(push_constant) uniform PushBlock { StrandRasterPush push; };
layout(set = 0, binding = kRasterBindingTileCounts, std430) buffer TileCounts { uint tileCounts[]; };
layout(set = 0, binding = kRasterBindingTileOffsets, std430) writeonly buffer TileOffsets { uint tileOffsets[]; };
layout(set = 0, binding = kRasterBindingCounters, std430) buffer Counters { RasterCounters counters; };

shared uint sums[1024];

void main()
{
    uint lane = gl_LocalInvocationIndex;
    uint tiles = push.tilesX * push.tilesY;
    uint run = (tiles + kRasterScanGroupSize - 1u) / kRasterScanGroupSize;
    uint first = min(lane * run, tiles);
    uint last = min(first + run, tiles);
    uint sum = 0u;
    for (uint i = first; i < last; ++i)
        sum += tileCounts[i];
    sums[lane] = sum;
    barrier();
    // Hillis-Steele inclusive scan of the runs' sums.
    for (uint step = 1u; step < kRasterScanGroupSize; step *= 2u) {
        uint add = lane >= step ? sums[lane - step] : 0u;
        barrier();
        sums[lane] += add;
        barrier();
    }
    uint offset = sums[lane] - sum;
    for (uint i = first; i < last; ++i) {
        uint count = tileCounts[i];
        tileOffsets[i] = offset;
        tileCounts[i] = 0u;
        offset += count;
    }
    if (lane == kRasterScanGroupSize - 1u) {
        uint total = sums[lane];
        tileOffsets[tiles] = total;
        counters.pairs = total;
        counters.capacity = push.binCapacity;
        counters.overflow = total > push.binCapacity ? total - push.binCapacity : 0u;
    }
}
