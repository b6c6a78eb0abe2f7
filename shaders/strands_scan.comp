#version 460
// strands_scan.comp: one workgroup of kRasterScanGroupSize threads lays out the bins and the
// raster's work. Each thread takes a run of tiles; three exclusive prefix sums over the workgroup
// (each thread sums its run, the workgroup scans the sums, each thread writes its run) give:
//   tileOffsets     each tile's first bin slot (from the counts), the total pairs last
//   chunkOffsets    each tile's first chunk: its bin (as far as the capacity holds it) cut into
//                   runs of chunkSegments, one raster workgroup each; chunkTiles names each
//                   chunk's tile, and the raster's indirect dispatch covers them all
//   partialOffsets  where the chunks of a tile of several chunks leave their pixels' lists
// and the frame's counters: pairs needed, capacity, overflow, chunks, partials, the largest bin.
// The counts are zeroed to serve as the bin pass's write cursors.
#extension GL_GOOGLE_include_directive : require
#include "shared/strand_raster.h"

layout(local_size_x = 1024) in;  // kRasterScanGroupSize
layout(push_constant) uniform PushBlock { StrandRasterPush push; };
layout(set = 0, binding = kRasterBindingTileCounts, std430) buffer TileCounts { uint tileCounts[]; };
layout(set = 0, binding = kRasterBindingTileOffsets, std430) writeonly buffer TileOffsets { uint tileOffsets[]; };
layout(set = 0, binding = kRasterBindingChunkOffsets, std430) writeonly buffer ChunkOffsets { uint chunkOffsets[]; };
layout(set = 0, binding = kRasterBindingPartialOffsets, std430) writeonly buffer PartialOffsets { uint partialOffsets[]; };
layout(set = 0, binding = kRasterBindingChunkTiles, std430) writeonly buffer ChunkTiles { uint chunkTiles[]; };
layout(set = 0, binding = kRasterBindingDispatch, std430) writeonly buffer Dispatch { RasterDispatch dispatch; };
layout(set = 0, binding = kRasterBindingCounters, std430) buffer Counters { RasterCounters counters; };

shared uint sums[1024];
shared uint largest;

// The exclusive prefix of `value` over the workgroup's lanes; `total` gets the sum of all.
uint exclusiveScan(uint lane, uint value, out uint total)
{
    barrier();
    sums[lane] = value;
    barrier();
    for (uint step = 1u; step < kRasterScanGroupSize; step *= 2u) {
        uint add = lane >= step ? sums[lane - step] : 0u;
        barrier();
        sums[lane] += add;
        barrier();
    }
    total = sums[kRasterScanGroupSize - 1u];
    return sums[lane] - value;
}

// The chunks of a tile whose bin holds `n` segments, and the partial lists they leave.
uint chunksOf(uint n)
{
    return (n + push.chunkSegments - 1u) / push.chunkSegments;
}

void main()
{
    uint lane = gl_LocalInvocationIndex;
    if (lane == 0u)
        largest = 0u;
    uint tiles = push.tilesX * push.tilesY;
    uint run = (tiles + kRasterScanGroupSize - 1u) / kRasterScanGroupSize;
    uint first = min(lane * run, tiles);
    uint last = min(first + run, tiles);

    uint pairs = 0u;
    uint most = 0u;
    for (uint i = first; i < last; ++i) {
        pairs += tileCounts[i];
        most = max(most, tileCounts[i]);
    }
    uint totalPairs;
    uint offset = exclusiveScan(lane, pairs, totalPairs);
    atomicMax(largest, most);

    // What the capacity holds of each tile's bin, cut into chunks.
    uint chunks = 0u, partials = 0u;
    uint o = offset;
    for (uint i = first; i < last; ++i) {
        uint count = tileCounts[i];
        uint held = min(o + count, push.binCapacity) - min(o, push.binCapacity);
        uint c = chunksOf(held);
        chunks += c;
        partials += c > 1u ? c : 0u;
        o += count;
    }
    uint totalChunks, totalPartials;
    uint chunk = exclusiveScan(lane, chunks, totalChunks);
    uint partial = exclusiveScan(lane, partials, totalPartials);

    o = offset;
    for (uint i = first; i < last; ++i) {
        uint count = tileCounts[i];
        uint held = min(o + count, push.binCapacity) - min(o, push.binCapacity);
        uint c = chunksOf(held);
        tileOffsets[i] = o;
        chunkOffsets[i] = chunk;
        partialOffsets[i] = partial;
        for (uint j = 0u; j < c; ++j)
            chunkTiles[chunk + j] = i;
        tileCounts[i] = 0u;
        o += count;
        chunk += c;
        partial += c > 1u ? c : 0u;
    }
    barrier();
    if (lane == kRasterScanGroupSize - 1u) {
        tileOffsets[tiles] = totalPairs;
        chunkOffsets[tiles] = totalChunks;
        partialOffsets[tiles] = totalPartials;
        uint x = min(totalChunks, 65535u);
        dispatch.x = x;
        dispatch.y = x == 0u ? 0u : (totalChunks + x - 1u) / x;
        dispatch.z = 1u;
        dispatch.chunks = totalChunks;
        counters.pairs = totalPairs;
        counters.capacity = push.binCapacity;
        counters.overflow = totalPairs > push.binCapacity ? totalPairs - push.binCapacity : 0u;
        counters.chunks = totalChunks;
        counters.partials = totalPartials;
        counters.maxTile = largest;
    }
}
