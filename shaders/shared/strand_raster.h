// shaders/shared/strand_raster.h: the compute strand renderer's interface and pure math, one copy
// for its kernels (shaders/strands_*.comp) and their C++ twin (renderer/strand_raster_reference.cpp).
// The frame, in compute (hair_raster=compute), after the physics:
//   generate  one thread per strand vertex: the strand's point (shared/strands.h, as hair.tese
//             places it), projected to the screen (or the light's map) with its half width in
//             pixels, shaded there (shared/strand_shading.h: shading along the strand, not per
//             pixel) and packed with its opacity
//   count     one thread per segment (two consecutive vertices): the screen tiles its ribbon
//             touches, row by row (segmentRowSpan), counted per tile with atomics
//   scan      one workgroup: each tile's first slot in the bins (exclusive prefix sum), the total
//             and the overflow against the bins' capacity; the counts become write cursors
//   bin       the same walk again, each segment's index written into its tiles' bins
//   raster    one workgroup per chunk of a tile's bin (at most chunkSegments segments: a tile with
//             thousands of segments is shared among workgroups), one thread per pixel: every
//             segment is covered analytically (segmentCoverage: the exact area of the ribbon over
//             the pixel across it, times the overlap along it), depth-tested against the meshes'
//             depth (each MSAA sample), and kept in registers as the list resolve does: the nearest
//             k sorted, the rest blended as one order-independent layer (insertFragment /
//             resolveFragments, shared with oit_resolve.comp). A tile of one chunk writes its
//             pixels' premultiplied colour; the chunks of a larger tile write their pixels' lists
//   merge     one workgroup per tile of several chunks: their lists merged (the nearest k of all,
//             the rest into the tail: exactly what one list of every segment would hold), and
//             tiles without hair cleared
//   light     from the light, the same generated segments (fewer, wider: shadow_strands) are
//             rasterized one thread per segment into the hair's depth (atomicMin) and then the
//             deep opacity layers (fixed-point atomicAdd: sums commute, so frames repeat bit for bit)
// Nothing is dropped silently: bins that outgrow their buffer count the overflow, and the renderer
// grows the buffer for the next frame. Conventions: screen positions in pixels, (0, 0) the top-left
// corner of the top-left pixel, pixel centres at + 0.5; depth as the depth buffer holds it (0 near,
// 1 far); colours tone-mapped linear RGB.
#ifndef WISP_SHARED_STRAND_RASTER_H
#define WISP_SHARED_STRAND_RASTER_H
#include "prelude.h"
#include "shadows.h"

GPU_NAMESPACE_BEGIN

#ifdef __cplusplus
#define GPU_INOUT(T) T&
#else
#define GPU_INOUT(T) inout T
#endif

GPU_CONST uint kRasterTileSize = 8u;        // pixels per tile side; the raster's workgroup is one tile
GPU_CONST uint kRasterTilePixels = kRasterTileSize * kRasterTileSize;
GPU_CONST uint kRasterGroupSize = 64u;      // threads of the per-vertex and per-segment kernels
GPU_CONST uint kRasterScanGroupSize = 1024u;
GPU_CONST uint kRasterChunkSegments = 2048u;  // segments one raster workgroup takes of a tile's bin

// Bindings (each kernel pushes the ones it reads; 4..7 are the light's maps of shared/shadows.h).
GPU_CONST uint kRasterBindingFrame = 0;        // uniform FrameParams
GPU_CONST uint kRasterBindingSim = 1;          // uniform SimParams (colliders)
GPU_CONST uint kRasterBindingPositions = 2;    // the solver's positions (interleaved slots, sim.h)
GPU_CONST uint kRasterBindingTriangles = 3;    // uvec4 per guide: the guide and its two neighbours
GPU_CONST uint kRasterBindingLut = 8;          // sampler2DArray: the lookup mode's tables
GPU_CONST uint kRasterBindingVertices = 9;     // vec4 per strand vertex: StrandVertex
GPU_CONST uint kRasterBindingColors = 10;      // uint per strand vertex: packed colour and opacity
GPU_CONST uint kRasterBindingTileCounts = 11;  // uint per tile: segments (count), then write cursors
GPU_CONST uint kRasterBindingTileOffsets = 12; // uint per tile + 1: first slot of each bin, the total last
GPU_CONST uint kRasterBindingBins = 13;        // uint per (segment, tile) pair: the segment's index
GPU_CONST uint kRasterBindingCounters = 14;    // RasterCounters
GPU_CONST uint kRasterBindingMeshDepth = 15;   // sampler2DMS: the meshes' depth (the target's)
GPU_CONST uint kRasterBindingHairColor = 16;   // image2D rgba16f: the hair, premultiplied
GPU_CONST uint kRasterBindingLightDepth = 17;  // uint per light texel: the hair's first depth (float bits)
GPU_CONST uint kRasterBindingLightOpacity = 18;// uint x 4 per light texel: opacity layers, fixed point
GPU_CONST uint kRasterBindingOpacityImage = 19;// image2D rgba16f: the deep opacity layers, as shaders read them
GPU_CONST uint kRasterBindingChunkOffsets = 20;   // uint per tile + 1: the tile's first chunk, the total last
GPU_CONST uint kRasterBindingPartialOffsets = 21; // uint per tile + 1: the first partial list of a tile of several chunks
GPU_CONST uint kRasterBindingChunkTiles = 22;     // uint per chunk: its tile
GPU_CONST uint kRasterBindingDispatch = 23;       // RasterDispatch: the raster's indirect dispatch
GPU_CONST uint kRasterBindingPartials = 24;       // uint words: each chunk's pixel lists (partialWord)

// Fixed point of the light's opacity sums (integer units per unit of opacity).
GPU_CONST float kOpacityFixedScale = 1024.0f;
// Fixed point of a pixel's blended tail (sums of alpha x colour, alpha and -log(1 - alpha)).
GPU_CONST float kTailFixedScale = 4096.0f;
GPU_CONST uint kTailSaturate = 0x7fffffffu;
GPU_CONST float kRasterFarDepth = 2.0f;  // an empty slot of the nearest list: behind everything

// Push constants of every compute-raster kernel.
struct StrandRasterPush {
    uint  guideCount;
    uint  verticesPerStrand;  // V of the guides
    uint  strandsPerGuide;    // S as set (the strand's identity: guide * S + s, as hair.tese has it)
    uint  drawnPerGuide;      // strands generated per guide this frame: ceil(LOD strands) <= S
    uint  divisions;          // D segments per strand (D + 1 vertices)
    uint  interpolation;      // kInterpolation* (strands.h)
    float clumpRadius;        // asset units
    float deviation;          // asset units
    float width;              // strand width at the root, asset units, LOD's scale included
    float lodStrands;         // strands per guide after LOD (continuous)
    uint  fromLight;          // 1: generate for the light's maps (orthographic, no shading)
    uint  segmentCount;       // guideCount * drawnPerGuide * D
    uint  tilesX;             // tiles per row of the picture (or of the light's map)
    uint  tilesY;
    uint  targetWidth;        // pixels of the picture (or texels of the light's map) per row
    uint  targetHeight;
    uint  oitK;               // nearest fragments kept sorted (<= kMaxOitK)
    uint  samples;            // MSAA samples of the meshes' depth
    uint  binCapacity;        // (segment, tile) pairs the bins hold
    uint  domLayers;          // deep opacity layers (light opacity kernel)
    uint  chunkSegments;      // segments of a tile's bin one raster workgroup takes (kRasterChunkSegments)
    uint  partialCapacity;    // partial lists the scratch buffer holds
    uint  pad0;
    uint  pad1;
};

// The raster's indirect dispatch (rows of at most 65535 workgroups, one per chunk), written by the scan.
struct RasterDispatch {
    uint x;
    uint y;
    uint z;
    uint chunks;  // chunks in all; workgroups past it return
};

// What the kernels count, copied back to the host each frame.
struct RasterCounters {
    uint pairs;      // (segment, tile) pairs the bins needed this frame
    uint capacity;   // pairs the bins hold
    uint overflow;   // pairs that did not fit (dropped this frame; the renderer grows the bins)
    uint fragments;  // (segment, pixel) overlaps that reached a pixel's list
    uint segments;   // segments binned (on screen, in front of the camera)
    uint chunks;     // raster workgroups (chunks of tiles' bins)
    uint partials;   // partial lists of tiles of several chunks
    uint maxTile;    // the most segments one tile's bin held
};

// One strand vertex as the rasterizer reads it: where it is on the screen and how wide.
// position.xy pixels, .z depth (0 near .. 1 far), .w half the ribbon's width in pixels;
// w < 0 marks a vertex that is not drawn (behind the camera, or a strand LOD left out).
// Its colour is a second word: packUnorm4x8(vec4(sqrt(rgb), opacity)), as OIT nodes store it.

// The per-vertex and per-segment kernels are dispatched in rows of at most 65535 workgroups (the
// dispatch limit every device has); a thread's number counts whole rows first.
GPU_FN uint linearInvocation(uvec3 global, uint threadsPerRow)
{
    return global.x + global.y * threadsPerRow;
}

// ---- Projection ------------------------------------------------------------------------------

// A world point seen through `viewProjection` onto a `size` pixel target, with its world width.
// Orthographic (the light) or perspective (the camera) alike: x, y in pixels, z the depth, w the
// half width in pixels; w = -1 when the point is behind the eye.
GPU_FN vec4 projectStrandVertex(mat4 viewProjection, vec2 size, vec3 world, float worldWidth, float pixelsPerUnitAtW1)
{
    vec4 c = viewProjection * vec4(world, 1.0f);
    if (c.w <= 1e-6f)
        return vec4(0.0f, 0.0f, 0.0f, -1.0f);
    vec3 ndc = vec3(c) / c.w;
    vec2 xy = (vec2(ndc) * 0.5f + 0.5f) * size;
    return vec4(xy.x, xy.y, ndc.z, 0.5f * worldWidth * pixelsPerUnitAtW1 / c.w);
}

// ---- Coverage --------------------------------------------------------------------------------

// A unit pixel seen along the unit direction n: the distribution of n . (x - centre) over the
// pixel's area is a trapezoid (the box's projection) whose support is |n.x| + |n.y| wide. This is
// its cumulative distribution at x: the share of the pixel lying on the near side of the line
// n . (x - centre) = x. Exact, so a straight ribbon's coverage below is exact too.
GPU_FN float pixelFootprintCdf(float x, float a, float b)
{
    // a >= b >= 0: the larger and smaller of |n.x|, |n.y| (a >= 1/sqrt(2)). The trapezoid's
    // density is 1 / a on its plateau (half width (a - b) / 2) and falls linearly to 0 over b on
    // each side; what lies beyond |x| is q^2 / (2ab) on the ramp plus (r - q) / a on the plateau,
    // with r = s - |x| the distance to the support's end s = (a + b) / 2 and q = min(r, b).
    float r = max(0.5f * (a + b) - abs(x), 0.0f);
    float q = min(r, b);
    float beyond = q * q / (2.0f * a * max(b, 1e-7f)) + (r - q) / a;
    return x >= 0.0f ? 1.0f - beyond : beyond;
}

// A segment prepared for coverage tests (in screen pixels).
struct RasterSegment {
    vec2  a;         // start
    vec2  dir;       // unit direction (x axis when degenerate)
    float len;       // length, pixels
    float ha;        // half width at the start and the end, pixels
    float hb;
    float footA;     // max(|dir.x|, |dir.y|) and min: the pixel's footprint across and along
    float footB;
};

GPU_FN RasterSegment makeRasterSegment(vec2 a, vec2 b, float ha, float hb)
{
    RasterSegment s;
    vec2 d = b - a;
    float len = length(d);
    s.a = a;
    s.dir = len > 1e-6f ? d / len : vec2(1.0f, 0.0f);
    s.len = len;
    s.ha = ha;
    s.hb = hb;
    s.footA = max(abs(s.dir.x), abs(s.dir.y));
    s.footB = min(abs(s.dir.x), abs(s.dir.y));
    return s;
}

// How much of the pixel centred at `pixel` the segment's ribbon covers, in [0, 1], and where along
// the segment (t in [0, 1]) the pixel's centre projects. Across the ribbon the coverage is exact
// for a straight band of the width at t (the footprint's cumulative distribution at both edges);
// along it, the pixel's footprint overlapping [0, len]; their product. The overlaps along of
// consecutive segments of a strand add up to one where they join, and the coverage integrates to
// the ribbon's area over any pixel grid (tests/test_strand_raster.cpp checks both against exact
// polygon areas).
GPU_FN vec2 segmentCoverage(RasterSegment s, vec2 pixel)
{
    vec2 d = pixel - s.a;
    float u = dot(d, s.dir);
    float v = s.dir.x * d.y - s.dir.y * d.x;
    float t = s.len > 0.0f ? clamp(u / s.len, 0.0f, 1.0f) : 0.0f;
    float h = mix(s.ha, s.hb, t);
    float across = pixelFootprintCdf(v + h, s.footA, s.footB) - pixelFootprintCdf(v - h, s.footA, s.footB);
    float along = pixelFootprintCdf(s.len - u, s.footA, s.footB) - pixelFootprintCdf(-u, s.footA, s.footB);
    return vec2(clamp(across * along, 0.0f, 1.0f), t);
}

// ---- Binning ---------------------------------------------------------------------------------

// The x range (pixels) over which the segment a..b, thickened by r on every side, crosses the
// horizontal band y0 <= y <= y1; empty (x > y) when it does not.
GPU_FN vec2 segmentRowSpan(vec2 a, vec2 b, float r, float y0, float y1)
{
    float lo = y0 - r;
    float hi = y1 + r;
    float dy = b.y - a.y;
    float t0 = 0.0f;
    float t1 = 1.0f;
    if (abs(dy) > 1e-6f) {
        float ta = (lo - a.y) / dy;
        float tb = (hi - a.y) / dy;
        t0 = max(t0, min(ta, tb));
        t1 = min(t1, max(ta, tb));
    } else if (a.y < lo || a.y > hi) {
        return vec2(1.0f, 0.0f);
    }
    if (t0 > t1)
        return vec2(1.0f, 0.0f);
    float xa = mix(a.x, b.x, t0);
    float xb = mix(a.x, b.x, t1);
    return vec2(min(xa, xb) - r, max(xa, xb) + r);
}

// Which pixels of the tile at `origin` (its top-left corner, pixels) the segment can cover: bit
// y * 8 + x for pixel (x, y) of the tile, low 32 pixels in .x. Conservative (every pixel whose
// centre lies within `reach` of the segment, measured as a square), so a pixel without its bit
// gets no coverage from the segment, and the raster skips it with one test.
GPU_FN uvec2 tilePixelMask(vec2 a, vec2 b, float reach, vec2 origin)
{
    uvec2 mask = uvec2(0u, 0u);
    for (uint row = 0u; row < kRasterTileSize; ++row) {
        float cy = origin.y + float(row) + 0.5f;
        vec2 span = segmentRowSpan(a, b, reach, cy, cy);
        if (span.x > span.y)
            continue;
        int first = max(int(ceil(span.x - origin.x - 0.5f)), 0);
        int last = min(int(floor(span.y - origin.x - 0.5f)), int(kRasterTileSize) - 1);
        if (first > last)
            continue;
        uint bits = ((2u << uint(last)) - (1u << uint(first))) << (row % 4u * 8u);
        if (row < 4u)
            mask.x |= bits;
        else
            mask.y |= bits;
    }
    return mask;
}

// How far beyond a segment's centre line its coverage can reach: its half width plus a pixel's
// half diagonal.
GPU_FN float segmentReach(float ha, float hb)
{
    return max(ha, hb) + 0.7072f;
}

// The position of the n-th (from 0) set bit of v; v must hold more than n set bits. (The raster
// hands out the pixels a segment's mask names, one per thread.)
GPU_FN uint nthSetBit(uint v, uint n)
{
    uint position = 0u;
    for (uint width = 16u; width > 0u; width >>= 1u) {
        uint low = bitCount(v & ((1u << width) - 1u));
        if (n >= low) {
            n -= low;
            v >>= width;
            position += width;
        }
    }
    return position;
}

// Word `word` of lane `lane`'s list in partial list `partial`: words 0..k-1 the depths (float bits),
// k..2k-1 the colours, then the five tail sums; lanes side by side, so a workgroup's writes coalesce.
GPU_FN uint partialWord(uint partial, uint word, uint lane, uint k)
{
    return (partial * (2u * k + 5u) + word) * kRasterTilePixels + lane;
}

// ---- Order-independent blending (the nearest k sorted, the rest as one layer) ----------------

// Fragments order by depth, ties by their colour bits, so equal depths sort the same whatever
// order they arrive in.
GPU_FN bool fragmentFarther(float da, uint ca, float db, uint cb)
{
    return da != db ? da > db : ca > cb;
}

GPU_FN vec4 unpackFragmentColor(uint c)
{
    vec4 v = unpackUnorm4x8(c);
    return vec4(vec3(v) * vec3(v), v.w);  // stored as sqrt(rgb)
}

GPU_FN uint packFragmentColor(vec3 rgb, float alpha)
{
    return packUnorm4x8(vec4(sqrt(clamp(rgb, vec3(0.0f), vec3(1.0f))), clamp(alpha, 0.0f, 1.0f)));
}

// A pixel's fragments so far: the nearest kMaxOitK (sorted, nearest first; empty slots at
// kRasterFarDepth), and the tail behind them as fixed-point sums (integer sums commute, so the
// result does not depend on the order the fragments came in).
struct PixelFragments {
    float depth[kMaxOitK];
    uint color[kMaxOitK];
    uint tailR;       // sum of alpha * r
    uint tailG;
    uint tailB;
    uint tailAlpha;   // sum of alpha
    uint tailClear;   // sum of -log(1 - alpha): the tail lets exp(-sum) through
};

GPU_FN PixelFragments emptyPixelFragments()
{
    PixelFragments f;
    for (uint i = 0u; i < kMaxOitK; ++i) {
        f.depth[i] = kRasterFarDepth;
        f.color[i] = 0u;
    }
    f.tailR = 0u;
    f.tailG = 0u;
    f.tailB = 0u;
    f.tailAlpha = 0u;
    f.tailClear = 0u;
    return f;
}

GPU_FN uint saturatingAdd(uint sum, float value)
{
    uint v = uint(clamp(value, 0.0f, 65536.0f) * kTailFixedScale + 0.5f);
    return min(sum, kTailSaturate - v) + v;
}

GPU_FN void addToTail(GPU_INOUT(PixelFragments) f, uint color)
{
    vec4 c = unpackFragmentColor(color);
    f.tailR = saturatingAdd(f.tailR, c.w * c.x);
    f.tailG = saturatingAdd(f.tailG, c.w * c.y);
    f.tailB = saturatingAdd(f.tailB, c.w * c.z);
    f.tailAlpha = saturatingAdd(f.tailAlpha, c.w);
    f.tailClear = saturatingAdd(f.tailClear, -log(1.0f - min(c.w, 0.999f)));
}

// Adds a fragment: it bubbles into the nearest k (each kept one farther than it swaps places with
// it), and whatever comes out of the last kept slot joins the tail.
GPU_FN void insertFragment(GPU_INOUT(PixelFragments) f, uint k, float depth, uint color)
{
    if (!fragmentFarther(f.depth[k - 1u], f.color[k - 1u], depth, color)) {
        addToTail(f, color);  // behind all k kept: no swap would happen (most fragments, once k are kept)
        return;
    }
    float d = depth;
    uint c = color;
    for (uint i = 0u; i < kMaxOitK; ++i) {
        if (i < k && fragmentFarther(f.depth[i], f.color[i], d, c)) {
            float keptDepth = f.depth[i];
            uint keptColor = f.color[i];
            f.depth[i] = d;
            f.color[i] = c;
            d = keptDepth;
            c = keptColor;
        }
    }
    if (d < kRasterFarDepth)
        addToTail(f, c);
}

// The pixel's hair, premultiplied: the nearest k front to back, then the tail as one layer whose
// colour is its alpha-weighted mean and whose opacity is 1 - prod(1 - alpha).
// Adds another list's tail (its fixed-point sums) to this one's.
GPU_FN void addTailSums(GPU_INOUT(PixelFragments) f, uint r, uint g, uint b, uint alpha, uint clear)
{
    f.tailR = min(f.tailR, kTailSaturate - min(r, kTailSaturate)) + min(r, kTailSaturate);
    f.tailG = min(f.tailG, kTailSaturate - min(g, kTailSaturate)) + min(g, kTailSaturate);
    f.tailB = min(f.tailB, kTailSaturate - min(b, kTailSaturate)) + min(b, kTailSaturate);
    f.tailAlpha = min(f.tailAlpha, kTailSaturate - min(alpha, kTailSaturate)) + min(alpha, kTailSaturate);
    f.tailClear = min(f.tailClear, kTailSaturate - min(clear, kTailSaturate)) + min(clear, kTailSaturate);
}

GPU_FN vec4 resolveFragments(PixelFragments f, uint k)
{
    vec3 color = vec3(0.0f);
    float transmittance = 1.0f;
    for (uint i = 0u; i < kMaxOitK; ++i) {
        if (i < k && f.depth[i] < kRasterFarDepth) {
            vec4 c = unpackFragmentColor(f.color[i]);
            color += transmittance * c.w * vec3(c);
            transmittance *= 1.0f - c.w;
        }
    }
    if (f.tailAlpha > 0u) {
        vec3 mean = vec3(float(f.tailR), float(f.tailG), float(f.tailB)) / float(f.tailAlpha);
        float clear = exp(-float(f.tailClear) / kTailFixedScale);
        color += transmittance * (1.0f - clear) * mean;
        transmittance *= clear;
    }
    return vec4(color, 1.0f - transmittance);
}

GPU_NAMESPACE_END

#endif
