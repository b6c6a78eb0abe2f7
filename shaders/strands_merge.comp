#version 460
// strands_merge.comp: one workgroup per screen tile, one thread per pixel. A tile whose bin was
// shared among several raster workgroups (chunks) merges their pixel lists: each list's kept
// fragments are inserted into one (the nearest k of them all stay, the rest join the tail) and the
// tails' fixed-point sums added, which is exactly the list of every segment at once. Tiles of one
// chunk were written by the raster; tiles without hair are cleared here. oit_k is specialization
// constant 0, as in strands_raster.comp.
#extension GL_GOOGLE_include_directive : require
#include "shared/strand_raster.h"

layout(local_size_x = 8, local_size_y = 8) in;  // kRasterTileSize
layout(constant_id = 0) const uint kOitK = 8u;
layout(push_constant) uniform PushBlock { StrandRasterPush push; };
layout(set = 0, binding = kRasterBindingChunkOffsets, std430) readonly buffer ChunkOffsets { uint chunkOffsets[]; };
layout(set = 0, binding = kRasterBindingPartialOffsets, std430) readonly buffer PartialOffsets { uint partialOffsets[]; };
layout(set = 0, binding = kRasterBindingPartials, std430) readonly buffer Partials { uint partials[]; };
layout(set = 0, binding = kRasterBindingHairColor, rgba16f) uniform writeonly image2D hairColor;

void main()
{
    uint tile = gl_WorkGroupID.y * push.tilesX + gl_WorkGroupID.x;
    uint parts = chunkOffsets[tile + 1u] - chunkOffsets[tile];
    if (parts == 1u)
        return;
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (pixel.x >= int(push.targetWidth) || pixel.y >= int(push.targetHeight))
        return;
    uint lane = gl_LocalInvocationIndex;
    const uint k = kOitK;  // 1 .. kMaxOitK (the renderer clamps it)
    PixelFragments f = emptyPixelFragments();
    for (uint j = 0u; j < parts; ++j) {
        uint p = partialOffsets[tile] + j;
        for (uint i = 0u; i < k; ++i) {
            float depth = uintBitsToFloat(partials[partialWord(p, i, lane, k)]);
            if (depth < kRasterFarDepth)
                insertFragment(f, k, depth, partials[partialWord(p, k + i, lane, k)]);
        }
        addTailSums(f, partials[partialWord(p, 2u * k, lane, k)], partials[partialWord(p, 2u * k + 1u, lane, k)],
                    partials[partialWord(p, 2u * k + 2u, lane, k)], partials[partialWord(p, 2u * k + 3u, lane, k)],
                    partials[partialWord(p, 2u * k + 4u, lane, k)]);
    }
    imageStore(hairColor, pixel, resolveFragments(f, k));
}
