#version 460
// strands_pieces.comp (strands.pieces): one workgroup, one thread per recorded piece (push.piece
// of them): the piece's pixels, found by binary search in the scan's offsets (the first pixel
// whose offset reaches p * stride), the rows they span, and the indirect dispatches of its walk
// (strands.write) and its resolve (strands.resolve); none where the piece is empty or past the
// pieces the frame needs; in the reserved layout (shared/strand_raster.h "One walk") a walk of the
// segments that spilled, none where every pixel's fragments fit their room. When the frame needs more pieces than were recorded, the fragments of
// the pixels left out are counted as not drawn (the renderer records more for the next frame).
#extension GL_GOOGLE_include_directive : require
#include "shared/strand_raster.h"

layout(local_size_x = 64) in;
layout(push_constant) uniform PushBlock { StrandRasterPush push; };
layout(set = 0, binding = kRasterBindingOffsets, std430) readonly buffer Offsets { uint offsets[]; };
layout(set = 0, binding = kRasterBindingCounters, std430) buffer Counters { RasterCounters counters; };
layout(set = 0, binding = kRasterBindingPieces, std430) writeonly buffer Pieces { RasterPiece pieces[]; };

// The first pixel in [0, pixels] whose offset is at least `target` (offsets[pixels] is the total).
uint firstPixelFrom(uint target, uint pixels)
{
    uint lo = 0u, hi = pixels;
    while (lo < hi) {
        uint mid = (lo + hi) / 2u;
        if (offsets[mid] < target)
            lo = mid + 1u;
        else
            hi = mid;
    }
    return lo;
}

void main()
{
    uint width = push.targetWidth;
    uint pixels = width * push.targetHeight;
    uint needed = counters.pieces;
    uint stride = counters.stride;
    uint recorded = push.piece;
    for (uint p = gl_LocalInvocationIndex; p < recorded; p += gl_WorkGroupSize.x) {
        RasterPiece r;
        r.firstPixel = 0u;
        r.endPixel = 0u;
        if (p < needed) {
            r.firstPixel = p == 0u ? 0u : firstPixelFrom(p * stride, pixels);
            r.endPixel = p + 1u < needed ? firstPixelFrom((p + 1u) * stride, pixels) : pixels;
        }
        bool drawn = r.firstPixel < r.endPixel;
        r.firstRow = drawn ? r.firstPixel / width : 0u;
        r.endRow = drawn ? (r.endPixel - 1u) / width + 1u : 0u;
        uint walked = counters.reservedEnd == kRasterNotReserved
                          ? push.segmentCount
                          : rasterSpillWriteThreads(counters.spilled, push.spillCapacity, push.segmentCount);
        uvec2 walk = drawn ? rasterLinearGroups(walked, kRasterGroupSize) : uvec2(0u);
        r.walkGroups[0] = walk.x;
        r.walkGroups[1] = walk.y;
        r.walkGroups[2] = 1u;
        r.resolveRow = r.firstRow / 8u;
        r.resolveGroups[0] = drawn ? (width + 7u) / 8u : 0u;
        r.resolveGroups[1] = drawn ? (r.endRow + 7u) / 8u - r.resolveRow : 0u;
        r.resolveGroups[2] = 1u;
        r.pad0 = 0u;
        pieces[p] = r;
        if (p + 1u == recorded && needed > recorded) {
            uint left = offsets[firstPixelFrom(recorded * stride, pixels)];
            atomicAdd(counters.overflow, offsets[pixels] - left);
        }
    }
}
