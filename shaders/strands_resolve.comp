#version 460
// strands_resolve.comp: one thread per pixel: its fragments (side by side in the fragment buffer,
// from offsets[pixel] to offsets[pixel + 1], as far as the buffer holds them) kept as the list
// resolve keeps them, the nearest oit_k sorted and the rest blended as one order-independent layer
// (shared/strand_raster.h insertFragment / resolveFragments; oit_k is specialization constant 0,
// so the lists stay in registers); the pixel's premultiplied hair written once. One piece of the
// frame a dispatch (push.piece: its rows of tiles, only its pixels, their slots less the piece's
// start; shared/strand_raster.h "Pieces"); in the reserved layout ("One walk") a pixel's list starts
// at its reserved slot, or after the reserved region where it had no room there.
// hair.composite lays the picture over the target.
#extension GL_GOOGLE_include_directive : require
// The tail's clear units (tailClearUnits) of each alpha byte, filled at the workgroup's start: a
// shared-memory load where each fragment of the tail would take a logarithm.
shared uint tailClearTable[256];
#define TAIL_CLEAR_TABLE
#include "shared/strand_raster.h"

layout(local_size_x = 8, local_size_y = 8) in;
layout(constant_id = 0) const uint kOitK = 8u;
layout(push_constant) uniform PushBlock { StrandRasterPush push; };
layout(set = 0, binding = kRasterBindingOffsets, std430) readonly buffer Offsets { uint offsets[]; };
layout(set = 0, binding = kRasterBindingFragments, std430) readonly buffer Fragments { uvec2 fragments[]; };
layout(set = 0, binding = kRasterBindingCounters, std430) readonly buffer Counters { RasterCounters counters; };
layout(set = 0, binding = kRasterBindingHairColor, rgba16f) uniform writeonly image2D hairColor;
layout(set = 0, binding = kRasterBindingPieces, std430) readonly buffer Pieces { RasterPiece pieces[]; };
layout(set = 0, binding = kRasterBindingReserved, std430) readonly buffer Reserved { uint reserved[]; };

void main()
{
    for (uint a = gl_LocalInvocationIndex; a < 256u; a += gl_WorkGroupSize.x * gl_WorkGroupSize.y)
        tailClearTable[a] = tailClearUnits(a);
    barrier();
    uint stride = counters.stride;
    uint firstPixel = 0u, endPixel = 0xffffffffu, base = 0u, cap = push.fragmentCapacity;
    uvec2 origin = uvec2(0u);
    uint reservedEnd = counters.reservedEnd;
    if (stride != kRasterOnePiece) {
        RasterPiece piece = pieces[push.piece];
        firstPixel = piece.firstPixel;
        endPixel = piece.endPixel;
        origin.y = piece.resolveRow * 8u;
        base = push.piece * stride;
        cap = rasterPixelCap(push.fragmentCapacity, stride);
    }
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy + origin);
    uint p = uint(pixel.y) * push.targetWidth + uint(pixel.x);
    bool inside = pixel.x < int(push.targetWidth) && pixel.y < int(push.targetHeight) && p >= firstPixel && p < endPixel;
    if (inside) {
        // Fragment i of the list is at address i, or i + jump from `split` on: in the reserved
        // layout a pixel that spilled has its first `room` in its room and the rest after the
        // reserved region, as strands.write placed them from the spill list (or all of them
        // there, where the list was too short and the walk wrote every one).
        uint count = offsets[p + 1u] - offsets[p];
        uint begin = min(offsets[p] - base, push.fragmentCapacity);
        uint end = min(begin + min(count, cap), push.fragmentCapacity);
        uint split = 0xffffffffu, jump = 0u;
        if (reservedEnd != kRasterNotReserved) {  // (within the buffer: rasterDrawsReserved)
            uint first = reserved[p], room = reserved[p + 1u] - first;
            begin = first;
            if (count > room && counters.spilled > push.spillCapacity) {
                begin = reservedEnd + offsets[p];
            } else if (count > room) {
                split = first + room;
                jump = reservedEnd + offsets[p] - first;
            }
            end = begin + count;
        }
        const uint k = kOitK;  // 1 .. kMaxOitK (the renderer clamps it)
        PixelFragments f = emptyPixelFragments();
        // The list in batches of eight, the next batch's loads issued before this one's inserts: a
        // pixel of thousands of fragments would otherwise wait on memory once per batch. The tail's
        // sums go unguarded where the pixel's fragments cannot saturate them (every pixel, short of
        // 75000 fragments).
        const uint kAhead = 8u;  // (a batch of 16 measured slower on the H100, one of 4 too)
        bool saturate = end - begin > kTailExactFragments;
        uvec2 batch[kAhead];
        GPU_UNROLL for (uint j = 0u; j < kAhead; ++j) {
            uint at = begin + j;
            batch[j] = at < end ? fragments[at < split ? at : at + jump] : uvec2(0u);
        }
        for (uint i = begin; i < end; i += kAhead) {
            uvec2 ahead[kAhead];
            GPU_UNROLL for (uint j = 0u; j < kAhead; ++j) {
                uint at = i + kAhead + j;
                ahead[j] = at < end ? fragments[at < split ? at : at + jump] : uvec2(0u);
            }
            if (saturate) {
                GPU_UNROLL for (uint j = 0u; j < kAhead; ++j)
                    if (i + j < end)
                        insertFragmentSummed(f, k, uintBitsToFloat(batch[j].x), batch[j].y, true);
            } else {
                GPU_UNROLL for (uint j = 0u; j < kAhead; ++j)
                    if (i + j < end)
                        insertFragmentSummed(f, k, uintBitsToFloat(batch[j].x), batch[j].y, false);
            }
            batch = ahead;
        }
        imageStore(hairColor, pixel, resolveFragments(f, k));
    }
}
