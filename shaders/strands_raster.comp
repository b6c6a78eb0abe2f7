#version 460
// strands_raster.comp: one workgroup per screen tile, one thread per pixel. The tile's bin is
// read in batches of 64 segments into shared memory, each with the mask of the tile's pixels it
// can reach (tilePixelMask: a pixel outside it skips the segment with one test); every pixel the
// segment reaches covers it analytically
// (shared/strand_raster.h segmentCoverage), tests the point's depth against each MSAA sample of
// the meshes' depth (the share of samples in front scales the coverage, so the head's silhouette
// stays antialiased), and keeps what passes as the list resolve does: the nearest oit_k sorted,
// the rest as one order-independent layer (insertFragment). The colour and opacity at the point
// interpolate the two vertices' (shaded along the strand by strands_generate.comp). Each pixel
// writes its premultiplied hair once; hair.composite lays it over the target. With
// RASTER_SINGLE_SAMPLE (strands_raster_single.comp) the meshes' depth has one sample.
#extension GL_GOOGLE_include_directive : require
#include "shared/strand_raster.h"

layout(local_size_x = 8, local_size_y = 8) in;  // kRasterTileSize
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

const uint kBatch = 64u;  // kRasterTilePixels: each thread loads one segment per batch
const uint kMaxSamples = 8u;
shared vec4 segmentLine[kBatch];    // a.xy, dir.xy
shared vec4 segmentShape[kBatch];   // len, ha, hb, footA
shared vec4 segmentDepth[kBatch];   // footB, za, zb
shared vec4 segmentColorA[kBatch];  // unpacked colour and opacity at the start
shared vec4 segmentColorB[kBatch];  // and at the end
shared uvec2 segmentMask[kBatch];  // the tile's pixels it can cover (tilePixelMask)
shared uint groupFragments;

void main()
{
    uint lane = gl_LocalInvocationIndex;
    if (lane == 0u)
        groupFragments = 0u;
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    bool inside = pixel.x < int(push.targetWidth) && pixel.y < int(push.targetHeight);
    vec2 centre = vec2(pixel) + 0.5;
    uint tile = gl_WorkGroupID.y * push.tilesX + gl_WorkGroupID.x;

    float sampleDepth[kMaxSamples];
    uint samples = min(push.samples, kMaxSamples);
    for (uint s = 0u; s < kMaxSamples; ++s) {
#ifdef RASTER_SINGLE_SAMPLE
        sampleDepth[s] = inside && s == 0u ? texelFetch(meshDepth, pixel, 0).r : 1.0;
#else
        sampleDepth[s] = inside && s < samples ? texelFetch(meshDepth, pixel, int(s)).r : 1.0;
#endif
    }
#ifdef RASTER_SINGLE_SAMPLE
    samples = 1u;
#endif

    uint begin = min(tileOffsets[tile], push.binCapacity);
    uint end = min(tileOffsets[tile + 1u], push.binCapacity);
    uint k = min(push.oitK, kMaxOitK);
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
            vec2 origin = vec2(gl_WorkGroupID.xy * kRasterTileSize);
            segmentMask[lane] = tilePixelMask(a.xy, b.xy, segmentReach(a.w, b.w), origin);
            segmentLine[lane] = vec4(s.a, s.dir);
            segmentShape[lane] = vec4(s.len, s.ha, s.hb, s.footA);
            segmentDepth[lane] = vec4(s.footB, a.z, b.z, 0.0);
            segmentColorA[lane] = unpackFragmentColor(colors[v]);
            segmentColorB[lane] = unpackFragmentColor(colors[v + 1u]);
        }
        barrier();
        if (!inside)
            continue;
        uint bit = 1u << (lane % 32u);
        for (uint j = 0u; j < n; ++j) {
            if (((lane < 32u ? segmentMask[j].x : segmentMask[j].y) & bit) == 0u)
                continue;  // cannot reach this pixel
            RasterSegment s;
            s.a = segmentLine[j].xy;
            s.dir = segmentLine[j].zw;
            s.len = segmentShape[j].x;
            s.ha = segmentShape[j].y;
            s.hb = segmentShape[j].z;
            s.footA = segmentShape[j].w;
            s.footB = segmentDepth[j].x;
            vec2 hit = segmentCoverage(s, centre);
            if (hit.x <= 0.0)
                continue;
            float depth = mix(segmentDepth[j].y, segmentDepth[j].z, hit.y);
            uint front = 0u;
            for (uint m = 0u; m < kMaxSamples; ++m)
                front += m < samples && depth <= sampleDepth[m] ? 1u : 0u;
            if (front == 0u)
                continue;
            vec4 c = mix(segmentColorA[j], segmentColorB[j], hit.y);
            float alpha = c.w * hit.x * float(front) / float(samples);
            if (alpha < 0.5 / 255.0)
                continue;  // below what the fragment's 8 bits of alpha hold
            insertFragment(f, k, depth, packFragmentColor(c.rgb, alpha));
            ++fragments;
        }
    }
    if (inside)
        imageStore(hairColor, pixel, resolveFragments(f, k));
    if (fragments > 0u)
        atomicAdd(groupFragments, fragments);
    barrier();
    if (lane == 0u && groupFragments > 0u)
        atomicAdd(counters.fragments, groupFragments);
}
