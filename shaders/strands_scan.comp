#version 460
// strands_scan.comp: the exclusive prefix sum of the pixels' fragment counts (and one count past
// the last pixel, always 0, so its offset is the total), in three dispatches; specialization
// constant 0 chooses the phase:
//   0 (strands.scan.blocks)  one workgroup per block of kRasterScanBlock counts: its total, and
//                            the largest count into the counters (maxPixel)
//   1 (strands.scan.totals)  one workgroup: the blocks' totals scanned into their offsets; the
//                            grand total, the capacity, whether the frame is drawn in the
//                            reserved layout (rasterDrawsReserved: one piece) or else the pieces
//                            it takes with their stride (rasterPieceStride, rasterPieces) into
//                            the counters
//   2 (strands.scan.offsets) one workgroup per block: each count's offset (its block's plus its
//                            own within the block); each pixel's count becomes its write cursor,
//                            starting at its offset (strands.write takes its slots from it); the
//                            fragments a pixel holds past rasterPixelCap (more than half the
//                            buffer in one pixel) are counted as not drawn
#extension GL_GOOGLE_include_directive : require
#include "shared/strand_raster.h"

layout(local_size_x_id = 1) in;  // 256 for the blocks, kRasterScanGroupSize for the totals
layout(constant_id = 0) const uint kPhase = 0u;
layout(push_constant) uniform PushBlock { StrandRasterPush push; };
layout(set = 0, binding = kRasterBindingCounts, std430) buffer Counts { uint counts[]; };
layout(set = 0, binding = kRasterBindingOffsets, std430) writeonly buffer Offsets { uint offsets[]; };
layout(set = 0, binding = kRasterBindingBlockSums, std430) buffer BlockSums { uint blockSums[]; };
layout(set = 0, binding = kRasterBindingCounters, std430) buffer Counters { RasterCounters counters; };
layout(set = 0, binding = kRasterBindingReserved, std430) readonly buffer Reserved { uint reserved[]; };

shared uint sums[kRasterScanGroupSize];
shared uint groupMost;

// The exclusive prefix of `value` over the workgroup; `total` gets the sum of all.
uint exclusiveScan(uint lane, uint value, out uint total)
{
    sums[lane] = value;
    barrier();
    for (uint step = 1u; step < gl_WorkGroupSize.x; step *= 2u) {
        uint add = lane >= step ? sums[lane - step] : 0u;
        barrier();
        sums[lane] += add;
        barrier();
    }
    total = sums[gl_WorkGroupSize.x - 1u];
    return sums[lane] - value;
}

void main()
{
    uint lane = gl_LocalInvocationIndex;
    uint count = push.targetWidth * push.targetHeight + 1u;
    if (kPhase == 1u) {
        uint run = (push.scanBlocks + gl_WorkGroupSize.x - 1u) / gl_WorkGroupSize.x;
        uint first = min(lane * run, push.scanBlocks);
        uint last = min(first + run, push.scanBlocks);
        uint sum = 0u;
        for (uint i = first; i < last; ++i)
            sum += blockSums[i];
        uint total;
        uint offset = exclusiveScan(lane, sum, total);
        for (uint i = first; i < last; ++i) {
            uint s = blockSums[i];
            blockSums[i] = offset;
            offset += s;
        }
        if (lane == 0u) {
            uint reservedEnd = reserved[push.targetWidth * push.targetHeight];
            bool inReserved = push.reserving != 0u && rasterDrawsReserved(reservedEnd, total, push.fragmentCapacity);
            uint stride =
                inReserved ? kRasterOnePiece : rasterPieceStride(total, push.fragmentCapacity, counters.maxPixel);
            counters.reservedEnd = inReserved ? reservedEnd : kRasterNotReserved;
            counters.fragments = total;
            counters.capacity = push.fragmentCapacity;
            counters.stride = stride;
            counters.pieces = rasterPieces(total, stride);
        }
        return;
    }
    uint block = gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x;
    if (block >= push.scanBlocks)
        return;  // (whole workgroups)
    if (lane == 0u)
        groupMost = 0u;
    barrier();
    uint per = kRasterScanBlock / gl_WorkGroupSize.x;
    uint first = block * kRasterScanBlock + lane * per;
    uint values[4];
    uint sum = 0u;
    for (uint i = 0u; i < 4u; ++i) {
        values[i] = i < per && first + i < count ? counts[first + i] : 0u;
        sum += values[i];
    }
    uint total;
    uint offset = exclusiveScan(lane, sum, total);
    if (kPhase == 0u) {
        atomicMax(groupMost, max(max(values[0], values[1]), max(values[2], values[3])));
        barrier();
        if (lane == 0u) {
            blockSums[block] = total;
            if (groupMost > 0u)
                atomicMax(counters.maxPixel, groupMost);
        }
        return;
    }
    offset += blockSums[block];
    uint cap = rasterPixelCap(counters.capacity, counters.stride);
    uint notDrawn = 0u;
    for (uint i = 0u; i < 4u; ++i) {
        if (i < per && first + i < count) {
            offsets[first + i] = offset;
            if (first + i + 1u < count)
                counts[first + i] = offset;  // the pixel's write cursor (the count past the last stays 0)
            notDrawn += values[i] > cap ? values[i] - cap : 0u;
            offset += values[i];
        }
    }
    if (notDrawn > 0u)
        atomicAdd(counters.overflow, notDrawn);
}
