// shaders/shared/strand_raster.h: the compute strand renderer's interface and pure math, one copy
// for its kernels (shaders/strands_*.comp) and their C++ twin (renderer/compute/strand_raster_reference.cpp).
// The frame, in compute (hair_raster=compute), after the physics and the meshes' depth:
//   curves     one thread per guide point of the strands' parameters (t = i / D): the guide's C1
//              curve there (shared/strands.h guideCurvePoint), which every strand of the guide (and
//              of its neighbours, multi) would otherwise evaluate again
//   generate   one thread per strand vertex: the strand's point (shared/strands.h, as hair.tese
//              places it), projected to the screen (or the light's map) with its half width in
//              pixels, shaded there (shared/strand_shading.h: shading along the strand, not per
//              pixel) and packed with its opacity
//   depth      one thread per pixel: the nearest and farthest of the meshes' depth samples; the
//              pixel's fragment count zeroed; each 8 x 8 tile's farthest sample (a coarse depth)
//   count      one thread per segment (two consecutive vertices), unless the segment lies behind
//              the farthest sample of every tile it reaches (hidden: none of its fragments could
//              pass the depth test, so its walk is skipped; the hair behind a head is about half
//              of what a front view's walks would visit): every pixel its ribbon can reach
//              (ribbonRowSpan, row by row) covered analytically (segmentCoverage: the exact area of
//              the ribbon over the pixel across it, times the overlap along it) and depth-tested
//              against the meshes (each MSAA sample); each fragment that stays counted at its pixel
//              and written at once into the room the last frame's layout reserved for the pixel
//              (see "One walk" below), where there is room
//   scan       the counts' exclusive prefix sum (blocks, their totals, the offsets): each pixel's
//              first slot in one fragment buffer, the total against its capacity; the counts
//              become write cursors
//   pieces     one workgroup: the pieces of the frame that fit the buffer (one where it fits
//              whole), each piece's pixels and its walk's and resolve's indirect dispatches
//   write      only where the reserved room was short: per piece, the same walk again over the
//              piece's rows, each fragment of its pixels (depth, colour and opacity) written to its
//              slot: every pixel's fragments side by side, binned by prefix sums (in the reserved
//              layout, only the pixels that had no room, after the reserved region)
//   resolve    per piece, one thread per pixel: its fragments kept as the list resolve keeps them, the
//              nearest k sorted and the rest blended as one order-independent layer
//              (insertFragment / resolveFragments, shared with oit_resolve.comp); one write
//   reserve    one thread per pixel: the next frame's room, from this frame's offsets
//   light      from the light, the same generated segments (fewer, wider: shadow_strands) are
//              rasterized one thread per segment into the hair's depth (atomicMin) and then the
//              deep opacity layers (fixed-point atomicAdd: sums commute, so frames repeat bit for bit)
// The buffer grows to what a frame needs within a budget; a frame past it is drawn in pieces that
// fit (see "Pieces" below), the same picture. Conventions: screen positions in pixels, (0, 0) the top-left
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

GPU_CONST uint kRasterGroupSize = 64u;       // threads of the per-vertex and per-segment kernels
GPU_CONST uint kRasterScanBlock = 1024u;     // counts one scan workgroup sums (256 threads, 4 each)
GPU_CONST uint kRasterScanGroupSize = 1024u; // threads of the scan of the blocks' totals

// Bindings (each kernel pushes the ones it reads; 4..7 are the light's maps of shared/shadows.h).
GPU_CONST uint kRasterBindingFrame = 0;       // uniform FrameParams
GPU_CONST uint kRasterBindingSim = 1;         // uniform SimParams (colliders)
GPU_CONST uint kRasterBindingPositions = 2;   // the solver's positions (interleaved slots, sim.h)
GPU_CONST uint kRasterBindingTriangles = 3;   // uvec4 per guide: the guide and its two neighbours
GPU_CONST uint kRasterBindingLut = 8;         // sampler2DArray: the lookup mode's tables
GPU_CONST uint kRasterBindingVertices = 9;    // vec4 per strand vertex: StrandVertex
GPU_CONST uint kRasterBindingColors = 10;     // uint per strand vertex: packed colour and opacity
GPU_CONST uint kRasterBindingCounts = 11;     // uint per pixel: fragments (count), then write cursors (from its offset)
GPU_CONST uint kRasterBindingOffsets = 12;    // uint per pixel + 1: its first fragment slot, the total last
GPU_CONST uint kRasterBindingFragments = 13;  // uvec2 per fragment: depth bits, packed colour and opacity
GPU_CONST uint kRasterBindingCounters = 14;   // RasterCounters
GPU_CONST uint kRasterBindingMeshDepth = 15;  // sampler2DMS (sampler2D with one sample): the meshes' depth
GPU_CONST uint kRasterBindingHairColor = 16;  // image2D rgba16f: the hair, premultiplied
GPU_CONST uint kRasterBindingLightDepth = 17; // uint per light texel: the hair's first depth (float bits)
GPU_CONST uint kRasterBindingLightOpacity = 18;    // uint x 4 per light texel: opacity layers, fixed point
GPU_CONST uint kRasterBindingOpacityImage = 19;    // image2D rgba16f: the deep opacity layers, as shaders read them
GPU_CONST uint kRasterBindingDepthRange = 20;      // vec2 per pixel: the nearest and farthest mesh depth sample
GPU_CONST uint kRasterBindingBlockSums = 21;       // uint per scan block: its counts' total, then its offset
GPU_CONST uint kRasterBindingMeshSamples = 22;     // uint per mesh depth sample (pixel * samples + s): float bits
GPU_CONST uint kRasterBindingLightDepthImage = 23; // image2D r32f: the hair's first depth from the light, as values
GPU_CONST uint kRasterBindingTileDepth = 24; // float per kRasterDepthTile^2 pixels: their farthest mesh depth sample
GPU_CONST uint kRasterBindingCurves = 25;    // vec4 x 2 per guide point (guide * (D + 1) + i): position, tangent
GPU_CONST uint kRasterBindingPieces = 26;    // RasterPiece per recorded piece (strands.pieces)
GPU_CONST uint kRasterBindingReserved = 27;  // uint per pixel + 1: its first reserved slot (rasterReservedSlot)
GPU_CONST uint kRasterBindingSpillList = 28; // uvec4 per spilled fragment: pixel, its number there, depth bits, colour

// The coarse depth's tiles: kRasterDepthTile x kRasterDepthTile pixels (strands_depth.comp's workgroup).
GPU_CONST uint kRasterDepthTile = 8u;
// A segment reaching more tiles than this is walked without looking at them.
GPU_CONST uint kRasterMaxCullTiles = 16u;

// Fixed point of the light's opacity sums (integer units per unit of opacity).
GPU_CONST float kOpacityFixedScale = 1024.0f;
// Fixed point of a pixel's blended tail: -log(1 - alpha) summed in units of 1 / kTailFixedScale;
// alpha x colour and alpha in units of 255^3 / 2^12 (about 1 / 4048), whole numbers from the
// fragment's bytes (addToTail).
GPU_CONST float kTailFixedScale = 4096.0f;
GPU_CONST uint kTailSaturate = 0x7fffffffu;
GPU_CONST float kRasterFarDepth = 2.0f; // an empty slot of the nearest list: behind everything

// Push constants of every compute-raster kernel.
struct StrandRasterPush {
    uint guideCount;
    uint verticesPerStrand; // V of the guides
    uint strandsPerGuide;   // S as set (the strand's identity: guide * S + s, as hair.tese has it)
    uint drawnPerGuide;     // strands generated per guide this frame: ceil(LOD strands) <= S
    uint divisions;         // D segments per strand (D + 1 vertices)
    uint interpolation;     // kInterpolation* (strands.h)
    float clumpRadius;      // asset units
    float deviation;        // asset units
    float width;            // strand width at the root, asset units, LOD's scale included
    float lodStrands;       // strands per guide after LOD (continuous)
    uint fromLight;         // 1: generate for the light's maps (orthographic, no shading)
    uint segmentCount;      // guideCount * drawnPerGuide * D
    uint targetWidth;       // pixels of the picture (or texels of the light's map) per row
    uint targetHeight;
    uint samples;          // MSAA samples of the meshes' depth
    uint fragmentCapacity; // fragments the fragment buffer holds
    uint domLayers;        // deep opacity layers (light opacity kernel)
    uint scanBlocks;       // ceil((pixels + 1) / kRasterScanBlock)
    uint oitK;             // nearest fragments kept sorted (the resolve's specialization constant)
    uint piece;            // the piece strands.write and strands.resolve draw; strands.pieces: how many are recorded
    float coilRadius;      // render-time coil (strands.h coilAt): helix radius, asset units (0: none)
    float coilFrequency;   // its turns per asset unit of length along the strand
    uint reserving;        // 1: strands.count writes into the reserved layout (the buffer has room for it)
    uint spillCapacity;    // spilled fragments the spill list holds (at most kRasterSpillList)
};

// What the kernels count, copied back to the host each frame.
struct RasterCounters {
    uint fragments;   // fragments the pixels held this frame (what the buffer needed)
    uint capacity;    // fragments the buffer holds
    uint overflow;    // fragments not drawn: pieces past those recorded (the renderer records more next frame)
    uint segments;    // segments on screen, in front of the camera
    uint maxPixel;    // the most fragments one pixel held
    uint hidden;      // of the segments on screen, those behind the meshes' coarse depth (not walked)
    uint pieces;      // the pieces the frame's fragments needed (rasterPieces)
    uint stride;      // the pieces' stride in the scan's offsets (rasterPieceStride)
    uint spilled;     // fragments strands.count found no reserved room for (strands.write writes them)
    uint reservedEnd; // the reserved layout's end when the frame is drawn in it, else kRasterNotReserved
    uint spillListed; // spilled fragments given a place in the spill list (past spillCapacity: none)
};

// ---- Pieces: any frame in a bounded fragment buffer --------------------------------------------
// The scan lays every pixel's fragments side by side in pixel order (row by row), so a piece of
// the frame is a run of pixels: those whose first fragment's offset o lies in [p * stride,
// (p + 1) * stride). The walk is done once per piece (its segments culled to the piece's rows),
// each fragment of the piece's pixels written at o + cursor - p * stride, and the piece resolved;
// a pixel is whole in one piece, so each picture is the same however many pieces it took. With
// stride = capacity - (the most fragments one pixel holds), every piece's fragments fit the
// buffer. A frame that fits is one piece (stride past every offset), drawn as before.
GPU_CONST uint kRasterMaxPieces = 64u; // pieces the renderer records at most in one frame
GPU_CONST uint kRasterOnePiece = 0xffffffffu;

// The stride for `total` fragments in a buffer of `capacity`, the largest pixel holding `maxPixel`.
// A pixel of more than half the buffer keeps capacity - stride of them (rasterPixelCap).
GPU_FN uint rasterPieceStride(uint total, uint capacity, uint maxPixel)
{
    if (total <= capacity)
        return kRasterOnePiece;
    return capacity - min(maxPixel, capacity / 2u);
}

// The pieces a frame of `total` fragments takes at `stride` (every pixel's offset is at most the
// total, so the last piece holds the pixels at the end, with fragments or none).
GPU_FN uint rasterPieces(uint total, uint stride)
{
    return stride == kRasterOnePiece ? 1u : total / stride + 1u;
}

// The most fragments a pixel keeps: all of them unless it alone holds more than half the buffer.
GPU_FN uint rasterPixelCap(uint capacity, uint stride)
{
    return stride == kRasterOnePiece ? capacity : capacity - stride;
}

// ---- One walk: the last frame's layout, with room to spare ------------------------------------
// A pixel's fragments change little from one frame to the next, so strands.count writes each
// fragment as it counts it, into room reserved from the last frame's offsets: pixel p's n-th
// fragment goes to reserved[p] + n while that is below reserved[p + 1] (rasterReservedSlot leaves
// each pixel an eighth more than its last count and kRasterReservedPerPixel more). The scan then
// finds the exact offsets as before; the frame is drawn in the reserved layout when the reserved
// region and the exact one after it fit the buffer (rasterDrawsReserved): a pixel whose count fit
// its room is resolved from there, and only a frame with a pixel that did not (its fragments are
// `spilled`) is finished by strands.write, which writes those pixels' fragments after the reserved region,
// at reservedEnd + their exact offsets. Otherwise (the buffer too small for both: a tight budget)
// the frame is drawn as before, exactly laid out, in pieces. strands.reserve lays out the next
// frame's room after the resolve. The lists' semantics do not depend on the order fragments
// arrive in, so the picture is the same byte for byte however it was written. strands.count lists
// each fragment it spills (with its pixel and its number there, n >= the room), so strands.write
// needs no second walk: one thread a listed fragment puts it at reservedEnd + offset + n, and
// strands.resolve reads such a pixel's first `room` fragments from its room and the rest from
// there. Past the list's capacity, strands.write walks every segment again and writes every
// fragment of the pixels that spilled there, which the resolve then reads all from there. The renderer asks
// strands.count to write (push.reserving) only where the buffer holds both layouts of a frame like its last; a first
// frame is laid out exactly.
GPU_CONST uint kRasterNotReserved = 0xffffffffu;
GPU_CONST uint kRasterReservedPerPixel = 4u;
GPU_CONST uint kRasterSpillList = 1u << 20;

// strands.write's threads in the reserved layout when `spilled` fragments spilled: one a listed
// fragment where the list (of `spillCapacity`) held them all, else one a segment (`segmentCount`)
// to walk again; none where nothing spilled.
GPU_FN uint rasterSpillWriteThreads(uint spilled, uint spillCapacity, uint segmentCount)
{
    return spilled <= spillCapacity ? spilled : segmentCount;
}

// Pixel `pixel`'s first reserved slot when the last frame's offset there was `offset`: monotone in
// the pixel (the offsets are), so pixel p's room, reserved[p + 1] - reserved[p], is at least its
// last count c plus c / 8 plus kRasterReservedPerPixel. Past three quarters of a uint's range (where
// it would wrap) there is no room.
GPU_FN uint rasterReservedSlot(uint offset, uint pixel)
{
    if (offset >= 0xc0000000u || pixel >= 0x04000000u)
        return 0xffffffffu;
    return offset + offset / 8u + kRasterReservedPerPixel * pixel;
}

// Whether a frame of `total` fragments is drawn in the reserved layout, which ends at `reservedEnd`:
// the reserved region and, after it, the exact layout of the pixels that had no room fit `capacity`.
GPU_FN bool rasterDrawsReserved(uint reservedEnd, uint total, uint capacity)
{
    return reservedEnd <= capacity && total <= capacity - reservedEnd;
}

// A recorded piece as strands.pieces finds it (binary searches over the offsets), with the
// indirect dispatches of its walk and its resolve (no groups where the piece is empty or was not
// needed).
struct RasterPiece {
    uint firstPixel; // its pixels: [firstPixel, endPixel) in row-major order
    uint endPixel;
    uint firstRow; // the rows they span: [firstRow, endRow)
    uint endRow;
    uint walkGroups[3];    // strands.write's dispatch (the segments' rows of workgroups, or none)
    uint resolveRow;       // the first row of its resolve's workgroups (8 rows a workgroup)
    uint resolveGroups[3]; // strands.resolve's dispatch: the piece's rows of 8 x 8 tiles
    uint pad0;
};

// Workgroups of `groupSize` for `items` items, in rows of at most 65535 (the per-vertex,
// per-segment and per-block kernels' dispatch): x per row, y rows.
GPU_FN uvec2 rasterLinearGroups(uint items, uint groupSize)
{
    uint groups = items / groupSize + (items % groupSize != 0u ? 1u : 0u);
    uint x = min(groups, 65535u);
    return uvec2(x, x == 0u ? 0u : (groups + x - 1u) / x);
}

// One strand vertex as the rasterizer reads it: where it is on the screen and how wide.
// position.xy pixels, .z depth (0 near .. 1 far), .w half the ribbon's width in pixels;
// w < 0 marks a vertex that is not drawn (behind the camera, or a strand LOD left out).
// Its colour is a second word: packUnorm4x8(vec4(sqrt(rgb), opacity)), as OIT nodes store it.

// The per-vertex, per-segment and per-block kernels are dispatched in rows of at most 65535
// workgroups (the dispatch limit every device has); a thread's number counts whole rows first.
GPU_FN uint linearInvocation(uvec3 global, uint threadsPerRow)
{
    return global.x + global.y * threadsPerRow;
}

// The segment thread t walks (segments are numbered strand by strand: (guide * S + s) * D + i):
// threads go clump by clump, neighbouring threads taking the same segment i of neighbouring
// strands s of one guide. Those strands cross the same pixels at about the same time, so one
// subgroup's atomics and stores land on the same pixels' counts and neighbouring slots together.
GPU_FN uint clumpOrderedSegment(uint t, uint divisions, uint strandsPerGuide)
{
    uint perGuide = divisions * strandsPerGuide;
    uint guide = t / perGuide;
    uint r = t % perGuide;
    return (guide * strandsPerGuide + r % strandsPerGuide) * divisions + r / strandsPerGuide;
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
    vec2 a;    // start
    vec2 dir;  // unit direction (x axis when degenerate)
    float len; // length, pixels
    float ha;  // half width at the start and the end, pixels
    float hb;
    float footA; // max(|dir.x|, |dir.y|) and min: the pixel's footprint across and along
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

// ---- Where a segment reaches --------------------------------------------------------------------

// The x range on the row at height cy of the points within `s` of the segment's ribbon, a
// rectangle (each side a slab, each slab an interval of x on the row); empty (x > y) when the row
// misses it.
GPU_FN vec2 ribbonRowWithin(RasterSegment seg, float cy, float s)
{
    float across = max(seg.ha, seg.hb) + s;
    float y = cy - seg.a.y;
    float lo = -1e30f;
    float hi = 1e30f;
    // across: v = dir.x * y - dir.y * (x - a.x), |v| <= across
    if (abs(seg.dir.y) > 1e-6f) {
        float x0 = (seg.dir.x * y - across) / seg.dir.y;
        float x1 = (seg.dir.x * y + across) / seg.dir.y;
        lo = max(lo, min(x0, x1));
        hi = min(hi, max(x0, x1));
    } else if (abs(y) > across) {
        return vec2(1.0f, 0.0f);
    }
    // along: u = dir.x * (x - a.x) + dir.y * y, -s <= u <= len + s
    if (abs(seg.dir.x) > 1e-6f) {
        float x0 = (-s - seg.dir.y * y) / seg.dir.x;
        float x1 = (seg.len + s - seg.dir.y * y) / seg.dir.x;
        lo = max(lo, min(x0, x1));
        hi = min(hi, max(x0, x1));
    } else if (seg.dir.y * y < -s || seg.dir.y * y > seg.len + s) {
        return vec2(1.0f, 0.0f);
    }
    return vec2(lo + seg.a.x, hi + seg.a.x);
}

// The x range of the pixel centres on the row of centres at height cy that the segment's ribbon
// can cover: within its widest half width plus the pixel's footprint (s = (footA + footB) / 2)
// across the segment, and within s of its ends along it (a rectangle: each side a slab, each slab
// an interval of x on the row). Exactly where segmentCoverage can be above zero; empty (x > y)
// when the row misses the rectangle.
GPU_FN vec2 ribbonRowSpan(RasterSegment seg, float cy)
{
    return ribbonRowWithin(seg, cy, 0.5f * (seg.footA + seg.footB) + 1e-4f);
}

// A texel of the light's maps and a light segment, as the tessellation path's light pass
// rasterizes its ribbons (at least a texel wide, their opacity scaled by the share of that width
// the strand covers): x 1 when the texel's centre lies within the ribbon, y where along it (t),
// z the share. The depth and the opacity passes take the same texels.
GPU_FN vec3 lightTexelHit(RasterSegment s, vec2 centre)
{
    vec2 d = centre - s.a;
    float u = dot(d, s.dir);
    float t = s.len > 0.0f ? clamp(u / s.len, 0.0f, 1.0f) : 0.0f;
    float h = mix(s.ha, s.hb, t);
    bool inside = u >= 0.0f && u <= s.len && abs(s.dir.x * d.y - s.dir.y * d.x) <= max(h, 0.5f);
    return vec3(inside ? 1.0f : 0.0f, t, min(2.0f * h, 1.0f));
}

// How far beyond its ends, in x or y, a segment's ribbon can reach a pixel centre.
GPU_FN float ribbonReach(RasterSegment seg)
{
    return max(seg.ha, seg.hb) + seg.footA + seg.footB;
}

// The pixels whose centres lie within `reach` of the segment from a to b in x and y: x0, y0, x1,
// y1, inclusive, clamped to a width x height target (empty, x0 > x1 or y0 > y1, off it).
GPU_FN ivec4 pixelBoundsWithin(vec2 a, vec2 b, float reach, uint width, uint height)
{
    vec2 lo = min(a, b) - reach - 0.5f;
    vec2 hi = max(a, b) + reach - 0.5f;
    return ivec4(max(int(ceil(lo.x)), 0), max(int(ceil(lo.y)), 0), min(int(floor(hi.x)), int(width) - 1),
                 min(int(floor(hi.y)), int(height) - 1));
}

// The pixels whose centres the ribbon of the segment from a to b can reach (ribbonReach).
GPU_FN ivec4 ribbonPixelBounds(RasterSegment seg, vec2 a, vec2 b, uint width, uint height)
{
    return pixelBoundsWithin(a, b, ribbonReach(seg), width, height);
}

// The light's texels are taken by their centres (lightTexelHit), not by the pixel's area: a
// light segment's texels are those whose centres lie within the ribbon (`reach`, at least a texel
// wide), found row by row within a sixteenth of a texel of it (the margin covers the rounding of
// solving for a row's ends; the pixel footprint's, about 0.7 a side, would walk twice the texels).
GPU_CONST float kLightCentreMargin = 0.0625f;

GPU_FN ivec4 lightTexelBounds(RasterSegment reach, vec2 a, vec2 b, uint width, uint height)
{
    return pixelBoundsWithin(a, b, max(reach.ha, reach.hb) + kLightCentreMargin, width, height);
}

GPU_FN vec2 lightRowCentres(RasterSegment reach, float cy)
{
    return ribbonRowWithin(reach, cy, kLightCentreMargin);
}

// Whether a fragment at `depth` (in front of the camera) could pass the meshes' depth test where
// the farthest of their samples is `farthest`: a fragment farther than every sample is behind
// them all (strands_fragments.comp's per-pixel test). A segment's fragments are never nearer than
// its nearer end; mix() may round a last bit below it, hence the margin.
GPU_FN bool depthCanPass(float nearestDepth, float farthest)
{
    return nearestDepth - 1e-6f <= farthest;
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
    return vec4(vec3(v) * vec3(v), v.w); // stored as sqrt(rgb)
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
    uint tailR; // sum of alpha * r
    uint tailG;
    uint tailB;
    uint tailAlpha; // sum of alpha
    uint tailClear; // sum of -log(1 - alpha): the tail lets exp(-sum) through
};

GPU_FN PixelFragments emptyPixelFragments()
{
    PixelFragments f;
    GPU_UNROLL for (uint i = 0u; i < kMaxOitK; ++i)
    {
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

GPU_FN uint saturatingAdd(uint sum, uint v)
{
    return min(sum, kTailSaturate - v) + v;
}

// A product of three bytes (at most 255^3) in the tail's units of 255^3 / 2^12, rounded.
GPU_FN uint tailUnits(uint product)
{
    return (product + 2048u) >> 12u;
}

// What a fragment of alpha byte `a` adds to the tail's clear sum: -log(1 - alpha) in units of
// 1 / kTailFixedScale (alpha held below 0.999, so one fragment adds at most 28295).
GPU_FN uint tailClearUnits(uint a)
{
    float clear = -log(1.0f - min(float(a) * (1.0f / 255.0f), 0.999f));
    return uint(clear * kTailFixedScale + 0.5f);
}

// A pixel of at most this many fragments cannot saturate its tail: each fragment adds at most
// tailClearUnits(255) = 28295 to the clear sum (and 4048, tailUnits(255^3), to the others), and
// 75000 x 28295 stays below kTailSaturate. Its sums may then be plain additions (insertFragment's
// `saturate` false), with the same result.
GPU_CONST uint kTailExactFragments = 75000u;

// The clear units of alpha byte `a`: computed, or read from a table the includer fills with
// tailClearUnits (strands_resolve.comp: `shared uint tailClearTable[256]`, TAIL_CLEAR_TABLE).
#ifdef TAIL_CLEAR_TABLE
#define TAIL_CLEAR_UNITS(a) tailClearTable[a]
#else
#define TAIL_CLEAR_UNITS(a) tailClearUnits(a)
#endif

// The fragment joins the tail. Its colour bytes hold sqrt(rgb) and its alpha byte alpha
// (packFragmentColor), so alpha x r is (A x R x R) / 255^3 exactly: whole-number arithmetic,
// with no conversion where unpacking to floats would take nine (the logarithm is
// tailClearUnits'); the tail is where most of a busy pixel's fragments go. `saturate` false
// adds without the guard, for pixels of at most kTailExactFragments fragments.
GPU_FN void addToTail(GPU_INOUT(PixelFragments) f, uint color, bool saturate)
{
    uint r = color & 0xffu;
    uint g = (color >> 8u) & 0xffu;
    uint b = (color >> 16u) & 0xffu;
    uint a = color >> 24u;
    uint addR = tailUnits(a * r * r);
    uint addG = tailUnits(a * g * g);
    uint addB = tailUnits(a * b * b);
    uint addAlpha = tailUnits(a * 65025u);
    uint addClear = TAIL_CLEAR_UNITS(a);
    if (saturate) {
        f.tailR = saturatingAdd(f.tailR, addR);
        f.tailG = saturatingAdd(f.tailG, addG);
        f.tailB = saturatingAdd(f.tailB, addB);
        f.tailAlpha = saturatingAdd(f.tailAlpha, addAlpha);
        f.tailClear = saturatingAdd(f.tailClear, addClear);
    } else {
        f.tailR += addR;
        f.tailG += addG;
        f.tailB += addB;
        f.tailAlpha += addAlpha;
        f.tailClear += addClear;
    }
}

// Adds a fragment: it takes its place among the nearest k (after every kept fragment not farther
// than it), the kept ones behind it move back one, and whatever falls out of the last kept slot
// (or the fragment itself, when it is behind all k) joins the tail. Written as independent
// comparisons and moves with constant indices, not a chain of swaps: the lists stay in registers
// and the steps do not wait on one another. `saturate`: as addToTail's.
GPU_FN void insertFragmentSummed(GPU_INOUT(PixelFragments) f, uint k, float depth, uint color, bool saturate)
{
    float lastDepth = kRasterFarDepth;
    uint lastColor = 0u;
    GPU_UNROLL for (uint i = 0u; i < kMaxOitK; ++i)
    {
        if (i + 1u == k) {
            lastDepth = f.depth[i];
            lastColor = f.color[i];
        }
    }
    if (depth > lastDepth) {
        addToTail(f, color, saturate); // behind all k kept (most fragments, once k are kept): one comparison
        return;
    }
    uint position = 0u;
    GPU_UNROLL for (uint i = 0u; i < kMaxOitK; ++i) position +=
        i < k && !fragmentFarther(f.depth[i], f.color[i], depth, color) ? 1u : 0u;
    if (position >= k) {
        addToTail(f, color, saturate); // behind all k kept, at the last one's depth
        return;
    }
    GPU_UNROLL for (uint i = kMaxOitK - 1u; i > 0u; --i)
    {
        if (i < k && i > position) {
            f.depth[i] = f.depth[i - 1u];
            f.color[i] = f.color[i - 1u];
        }
    }
    GPU_UNROLL for (uint i = 0u; i < kMaxOitK; ++i)
    {
        if (i == position) {
            f.depth[i] = depth;
            f.color[i] = color;
        }
    }
    if (lastDepth < kRasterFarDepth)
        addToTail(f, lastColor, saturate);
}

// insertFragmentSummed with the tail's guard, for a pixel of any number of fragments.
GPU_FN void insertFragment(GPU_INOUT(PixelFragments) f, uint k, float depth, uint color)
{
    insertFragmentSummed(f, k, depth, color, true);
}

GPU_FN vec4 resolveFragments(PixelFragments f, uint k)
{
    vec3 color = vec3(0.0f);
    float transmittance = 1.0f;
    GPU_UNROLL for (uint i = 0u; i < kMaxOitK; ++i)
    {
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

#ifdef __cplusplus
// The layouts GLSL gives these blocks, checked where they are defined (C++ only).
static_assert(sizeof(gpu::StrandRasterPush) == 96, "StrandRasterPush must fit the 128 bytes of push constants");
static_assert(sizeof(gpu::RasterCounters) == 44);
static_assert(sizeof(gpu::RasterPiece) == 48 && offsetof(gpu::RasterPiece, walkGroups) == 16 &&
                  offsetof(gpu::RasterPiece, resolveGroups) == 32,
              "RasterPiece must match its std430 layout (its dispatches are read at these offsets)");
#endif

#endif
