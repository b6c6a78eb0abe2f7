#version 460
// strands_raster.comp: one workgroup per chunk of a screen tile's bin (at most chunkSegments of
// its segments; a tile of more is shared among workgroups, so the dense crown of a head does not
// hold up the frame), 64 threads. The chunk is read in batches of 32 segments into shared memory,
// each with the mask of the tile's pixels it can reach (tilePixelMask); two threads take each
// segment, one per half of the tile, and cover the pixels the mask names (a strand segment
// touches a few pixels of a tile: with a thread per pixel, most threads would idle while a few
// covered it), each analytically
// (shared/strand_raster.h segmentCoverage), tests the point's depth against each MSAA sample of
// the meshes' depth (the share of samples in front scales the coverage, so the head's silhouette
// stays antialiased); what passes waits in shared memory for its pixel's thread, which keeps it
// as the list resolve does: the nearest oit_k sorted, the rest as one order-independent layer
// (insertFragment). The colour and opacity at the point
// interpolate the two vertices' (shaded along the strand by strands_generate.comp). A tile of one
// chunk writes its premultiplied hair; the chunks of a larger one leave their pixels' lists for
// strands_merge.comp. hair.composite lays the picture over the target. oit_k is specialization
// constant 0 (so the lists stay in registers). With
// RASTER_SINGLE_SAMPLE (strands_raster_single.comp) the meshes' depth has one sample.
#extension GL_GOOGLE_include_directive : require
#include "shared/strand_raster.h"

layout(local_size_x = 8, local_size_y = 8) in;  // kRasterTileSize
layout(constant_id = 0) const uint kOitK = 8u;
layout(push_constant) uniform PushBlock { StrandRasterPush push; };
layout(set = 0, binding = kRasterBindingVertices, std430) readonly buffer Vertices { vec4 vertices[]; };
layout(set = 0, binding = kRasterBindingColors, std430) readonly buffer Colors { uint colors[]; };
layout(set = 0, binding = kRasterBindingTileOffsets, std430) readonly buffer TileOffsets { uint tileOffsets[]; };
layout(set = 0, binding = kRasterBindingBins, std430) readonly buffer Bins { uint bins[]; };
layout(set = 0, binding = kRasterBindingCounters, std430) buffer Counters { RasterCounters counters; };
#ifdef RASTER_SINGLE_SAMPLE
layout(set = 0, binding = kRasterBindingMeshDepth) uniform sampler2D meshDepth;
#else
layout(set = 0, binding = kRasterBindingMeshDepth) uniform sampler2DMS meshDepth;
#endif
layout(set = 0, binding = kRasterBindingHairColor, rgba16f) uniform writeonly image2D hairColor;
layout(set = 0, binding = kRasterBindingChunkOffsets, std430) readonly buffer ChunkOffsets { uint chunkOffsets[]; };
layout(set = 0, binding = kRasterBindingPartialOffsets, std430) readonly buffer PartialOffsets { uint partialOffsets[]; };
layout(set = 0, binding = kRasterBindingChunkTiles, std430) readonly buffer ChunkTiles { uint chunkTiles[]; };
layout(set = 0, binding = kRasterBindingDispatch, std430) readonly buffer Dispatch { RasterDispatch dispatch; };
layout(set = 0, binding = kRasterBindingPartials, std430) writeonly buffer Partials { uint partials[]; };

const uint kBatch = 32u;            // segments per batch
const uint kMaxSamples = 8u;
shared vec4 segmentLine[kBatch];    // a.xy, dir.xy
shared vec4 segmentShape[kBatch];   // len, ha, hb, footA
shared vec4 segmentDepth[kBatch];   // footB, za, zb
shared vec4 segmentColorA[kBatch];  // unpacked colour and opacity at the start
shared vec4 segmentColorB[kBatch];  // and at the end
shared uvec2 segmentMask[kBatch];   // the tile's pixels it can cover (tilePixelMask)
// (Arrays of pixels side by side, so that the threads of a warp read neighbouring banks.)
shared float pixelDepth[kMaxSamples * kRasterTilePixels];  // the meshes' depth: sample s of pixel p at s * 64 + p
shared uint pixelCount[kRasterTilePixels];                 // fragments waiting for each pixel
shared float waitingDepth[kBatch * kRasterTilePixels];     // waiting fragment i of pixel p at i * 64 + p
shared uint waitingColor[kBatch * kRasterTilePixels];
shared uint groupFragments;

void main()
{
    uint chunk = gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x;
    if (chunk >= dispatch.chunks)
        return;  // the last row of workgroups runs past the chunks (the whole workgroup returns)
    uint lane = gl_LocalInvocationIndex;
    if (lane == 0u)
        groupFragments = 0u;
    pixelCount[lane] = 0u;
    uint tile = chunkTiles[chunk];
    uint part = chunk - chunkOffsets[tile];
    uint parts = chunkOffsets[tile + 1u] - chunkOffsets[tile];
    uvec2 tileXY = uvec2(tile % push.tilesX, tile / push.tilesX);
    vec2 origin = vec2(tileXY * kRasterTileSize);
    ivec2 pixel = ivec2(tileXY * kRasterTileSize + gl_LocalInvocationID.xy);
    bool inside = pixel.x < int(push.targetWidth) && pixel.y < int(push.targetHeight);

    uint samples = min(push.samples, kMaxSamples);
#ifdef RASTER_SINGLE_SAMPLE
    samples = 1u;
#endif
    for (uint s = 0u; s < kMaxSamples; ++s) {
        float d = 1.0;
#ifdef RASTER_SINGLE_SAMPLE
        if (inside && s == 0u)
            d = texelFetch(meshDepth, pixel, 0).r;
#else
        if (inside && s < samples)
            d = texelFetch(meshDepth, pixel, int(s)).r;
#endif
        pixelDepth[s * kRasterTilePixels + lane] = d;
    }

    uint binEnd = min(tileOffsets[tile + 1u], push.binCapacity);
    uint begin = min(min(tileOffsets[tile], push.binCapacity) + part * push.chunkSegments, binEnd);
    uint end = min(begin + push.chunkSegments, binEnd);
    const uint k = kOitK;  // 1 .. kMaxOitK (the renderer clamps it)
    PixelFragments f = emptyPixelFragments();
    uint fragments = 0u;
    for (uint base = begin; base < end; base += kBatch) {
        uint n = min(kBatch, end - base);
        barrier();  // the last batch has been read
        if (lane < n) {
            uint segment = bins[base + lane];
            uint v = segment / push.divisions * (push.divisions + 1u) + segment % push.divisions;
            vec4 a = vertices[v];
            vec4 b = vertices[v + 1u];
            RasterSegment s = makeRasterSegment(a.xy, b.xy, a.w, b.w);
            segmentLine[lane] = vec4(s.a, s.dir);
            segmentShape[lane] = vec4(s.len, s.ha, s.hb, s.footA);
            segmentDepth[lane] = vec4(s.footB, a.z, b.z, 0.0);
            segmentColorA[lane] = unpackFragmentColor(colors[v]);
            segmentColorB[lane] = unpackFragmentColor(colors[v + 1u]);
            segmentMask[lane] = tilePixelMask(a.xy, b.xy, segmentReach(a.w, b.w), origin);
        }
        barrier();

        // Two threads a segment, one for each half of the tile (rows 0-3, 4-7), each covering the
        // pixels its half of the mask names.
        uint j = lane / 2u;
        uint side = lane % 2u;
        uint bits = j < n ? (side == 0u ? segmentMask[j].x : segmentMask[j].y) : 0u;
        RasterSegment s;
        if (bits != 0u) {
            s.a = segmentLine[j].xy;
            s.dir = segmentLine[j].zw;
            s.len = segmentShape[j].x;
            s.ha = segmentShape[j].y;
            s.hb = segmentShape[j].z;
            s.footA = segmentShape[j].w;
            s.footB = segmentDepth[j].x;
        }
        while (bits != 0u) {
            uint p = uint(findLSB(bits)) + 32u * side;
            bits &= bits - 1u;
            vec2 centre = origin + vec2(float(p % kRasterTileSize), float(p / kRasterTileSize)) + 0.5;
            if (centre.x > float(push.targetWidth) || centre.y > float(push.targetHeight))
                continue;
            vec2 hit = segmentCoverage(s, centre);
            if (hit.x <= 0.0)
                continue;
            float depth = mix(segmentDepth[j].y, segmentDepth[j].z, hit.y);
            uint front = 0u;
            for (uint m = 0u; m < kMaxSamples; ++m)
                front += m < samples && depth <= pixelDepth[m * kRasterTilePixels + p] ? 1u : 0u;
            if (front == 0u)
                continue;
            vec4 c = mix(segmentColorA[j], segmentColorB[j], hit.y);
            float alpha = c.w * hit.x * float(front) / float(samples);
            if (alpha < 0.5 / 255.0)
                continue;  // below what the fragment's 8 bits of alpha hold
            uint slot = atomicAdd(pixelCount[p], 1u);  // < kBatch: one fragment per segment and pixel
            waitingDepth[slot * kRasterTilePixels + p] = depth;
            waitingColor[slot * kRasterTilePixels + p] = packFragmentColor(c.rgb, alpha);
        }
        barrier();
        uint waiting = pixelCount[lane];
        for (uint i = 0u; i < waiting; ++i)
            insertFragment(f, k, waitingDepth[i * kRasterTilePixels + lane], waitingColor[i * kRasterTilePixels + lane]);
        fragments += waiting;
        pixelCount[lane] = 0u;  // (read again only after the next batch's barriers)
    }
    if (parts == 1u) {
        if (inside)
            imageStore(hairColor, pixel, resolveFragments(f, k));
    } else {
        uint p = partialOffsets[tile] + part;
        for (uint i = 0u; i < k; ++i) {
            partials[partialWord(p, i, lane, k)] = floatBitsToUint(f.depth[i]);
            partials[partialWord(p, k + i, lane, k)] = f.color[i];
        }
        partials[partialWord(p, 2u * k, lane, k)] = f.tailR;
        partials[partialWord(p, 2u * k + 1u, lane, k)] = f.tailG;
        partials[partialWord(p, 2u * k + 2u, lane, k)] = f.tailB;
        partials[partialWord(p, 2u * k + 3u, lane, k)] = f.tailAlpha;
        partials[partialWord(p, 2u * k + 4u, lane, k)] = f.tailClear;
    }
    if (fragments > 0u)
        atomicAdd(groupFragments, fragments);
    barrier();
    if (lane == 0u && groupFragments > 0u)
        atomicAdd(counters.fragments, groupFragments);
}
