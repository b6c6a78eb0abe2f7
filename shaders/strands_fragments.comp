#version 460
// strands_fragments.comp: one thread per strand segment (clump by clump: clumpOrderedSegment);
// every pixel its ribbon can reach, row by row (ribbonRowSpan), is covered analytically
// (segmentCoverage) and tested against the meshes' depth (the share of MSAA samples in front
// scales the coverage, so the head's silhouette stays antialiased); the colour and opacity
// interpolate the two vertices' (shaded along the strand by strands_generate.comp).
// Two variants (the walk is the same code, the pieces' bookkeeping only in the second, so that
// the count's loop is not made heavier by what it never runs):
//   strands_fragments.comp (strands.count): each fragment that stays is counted at its pixel
//                          (atomicAdd) and written into the pixel's reserved room
//                          (shared/strand_raster.h "One walk") when the count is within it; the
//                          fragments that are not are counted as spilled
//   strands_fragments_write.comp (RASTER_WRITE, strands.write): written to its pixel's next slot, from a cursor (the counts, which the
//                          scan set to each pixel's offset). In the reserved layout only the
//                          pixels that had no room, after the reserved region: one thread a
//                          fragment of the spill list, no walk (no threads where nothing spilled),
//                          or past the list's capacity the walk again. Otherwise one piece
//                          of the frame a dispatch
//                          (push.piece, shared/strand_raster.h "Pieces"): only the piece's pixels,
//                          at their slot less the piece's start, segments off the piece's rows
//                          not walked; a pixel's fragments past rasterPixelCap are skipped (the
//                          scan counted them as not drawn)
// Both variants make exactly the same decisions (the same arithmetic on the same input).
// Segments with an end behind the camera or outside the depth range are not drawn; nor are those
// behind the farthest mesh sample of every 8 x 8 tile they reach (the coarse depth of
// strands_depth.comp): none of their fragments could pass the per-pixel test, so skipping their
// walk changes nothing but the time (they are counted as hidden).
// The meshes' depth samples come from a buffer (float bits, pixel * samples + s): strands_depth.comp
// copies the depth image there, or the compute meshes drew into it.
#extension GL_GOOGLE_include_directive : require
#include "shared/strand_raster.h"

layout(local_size_x = 64) in;  // kRasterGroupSize
#ifdef RASTER_WRITE
const bool kWrite = true;
#else
const bool kWrite = false;
#endif
layout(push_constant) uniform PushBlock { StrandRasterPush push; };
layout(set = 0, binding = kRasterBindingVertices, std430) readonly buffer Vertices { vec4 vertices[]; };
layout(set = 0, binding = kRasterBindingColors, std430) readonly buffer Colors { uint colors[]; };
layout(set = 0, binding = kRasterBindingCounts, std430) buffer Counts { uint counts[]; };
layout(set = 0, binding = kRasterBindingFragments, std430) writeonly buffer Fragments { uvec2 fragments[]; };
layout(set = 0, binding = kRasterBindingCounters, std430) buffer Counters { RasterCounters counters; };
layout(set = 0, binding = kRasterBindingDepthRange, std430) readonly buffer DepthRange { vec2 depthRange[]; };
layout(set = 0, binding = kRasterBindingMeshSamples, std430) readonly buffer MeshSamples { uint meshSamples[]; };

layout(set = 0, binding = kRasterBindingTileDepth, std430) readonly buffer TileDepth { float tileDepth[]; };
layout(set = 0, binding = kRasterBindingReserved, std430) readonly buffer Reserved { uint reserved[]; };
#ifdef RASTER_WRITE
layout(set = 0, binding = kRasterBindingSpillList, std430) readonly buffer SpillList { uvec4 spillList[]; };
#else
layout(set = 0, binding = kRasterBindingSpillList, std430) writeonly buffer SpillList { uvec4 spillList[]; };
#endif
#ifdef RASTER_WRITE
layout(set = 0, binding = kRasterBindingOffsets, std430) readonly buffer Offsets { uint offsets[]; };
layout(set = 0, binding = kRasterBindingPieces, std430) readonly buffer Pieces { RasterPiece pieces[]; };
#endif

shared uint groupSegments;
shared uint groupHidden;
shared uint groupSpilled;

// Whether any pixel in `bounds` could hold a fragment as near as `nearest`: whether it lies in
// front of the farthest mesh sample of some tile the bounds reach (true, unlooked, past
// kRasterMaxCullTiles tiles).
bool reachesUnhiddenTile(ivec4 bounds, float nearest)
{
    ivec4 tiles = bounds / int(kRasterDepthTile);
    if (uint((tiles.z - tiles.x + 1) * (tiles.w - tiles.y + 1)) > kRasterMaxCullTiles)
        return true;
    uint tilesPerRow = (push.targetWidth + kRasterDepthTile - 1u) / kRasterDepthTile;
    for (int ty = tiles.y; ty <= tiles.w; ++ty)
        for (int tx = tiles.x; tx <= tiles.z; ++tx)
            if (depthCanPass(nearest, tileDepth[uint(ty) * tilesPerRow + uint(tx)]))
                return true;
    return false;
}

// The walk's next pixel: along the row, else the first of the next row the ribbon reaches (its
// span, ribbonRowSpan); false past `lastRow`. A walk starts at y = its first row - 1, x1 = x - 1.
bool nextPixel(RasterSegment s, int lastRow, inout int y, inout int x, inout int x1)
{
    ++x;
    while (x > x1) {
        ++y;
        if (y > lastRow)
            return false;
        vec2 span = ribbonRowSpan(s, float(y) + 0.5);
        x = max(int(ceil(span.x - 0.5)), 0);
        x1 = min(int(floor(span.y - 0.5)), int(push.targetWidth) - 1);
    }
    return true;
}

#ifndef RASTER_WRITE
// strands.count's fragment n of pixel p, once n has come back from the pixel's atomic: into the
// pixel's reserved room [first, end) where it fits, else spilled, and listed while the list has
// room (a plain read first: no atomics once full).
void placeFragment(uint p, uint n, uint first, uint end, uvec2 fragment, inout uint spilled)
{
    if (n < end - first && first + n < push.fragmentCapacity) {
        fragments[first + n] = fragment;
        return;
    }
    spilled++;
    if (counters.spillListed < push.spillCapacity) {
        uint listed = atomicAdd(counters.spillListed, 1u);
        if (listed < push.spillCapacity)
            spillList[listed] = uvec4(p, n, fragment);
    }
}
#endif

void main()
{
    if (gl_LocalInvocationIndex == 0u) {
        groupSegments = 0u;
        groupHidden = 0u;
        groupSpilled = 0u;
    }
    barrier();

    // The piece this dispatch writes (the whole frame where it is one piece): its pixels, rows and
    // first slot; whether some pixel holds more than it may keep.
#ifdef RASTER_WRITE
    uint firstPixel = 0u, endPixel = 0xffffffffu, firstRow = 0u, endRow = 0xffffffffu, base = 0u;
    bool capped = false;
    uint cap = push.fragmentCapacity;
    uint reservedEnd = counters.reservedEnd; // the reserved layout: the spilled pixels after its region
    bool inReserved = reservedEnd != kRasterNotReserved;
    {
        uint stride = counters.stride;
        if (!inReserved && stride != kRasterOnePiece) {
            RasterPiece piece = pieces[push.piece];
            firstPixel = piece.firstPixel;
            endPixel = piece.endPixel;
            firstRow = piece.firstRow;
            endRow = piece.endRow;
            base = push.piece * stride;
            cap = rasterPixelCap(push.fragmentCapacity, stride);
            capped = counters.maxPixel > cap;
        }
    }
#endif

    uint thread = linearInvocation(gl_GlobalInvocationID, gl_NumWorkGroups.x * gl_WorkGroupSize.x);
#ifdef RASTER_WRITE
    if (inReserved && counters.spilled <= push.spillCapacity) {  // (the same for every thread)
        // The spilled fragments, listed: fragment n of pixel p (n >= its room) to n past the
        // pixel's offset after the reserved region (strands.resolve reads the first `room` from
        // the room and the rest from there).
        if (thread < counters.spilled) {
            uvec4 f = spillList[thread];
            fragments[reservedEnd + offsets[f.x] + f.y] = f.zw;
        }
        return;
    }
#endif
    uint segment = clumpOrderedSegment(thread, push.divisions, push.drawnPerGuide);
    bool drawn = false;
    bool hidden = false;
    uint spilled = 0u;  // (strands.count) fragments with no reserved room
    if (thread < push.segmentCount) {
        uint v = segment / push.divisions * (push.divisions + 1u) + segment % push.divisions;
        vec4 a = vertices[v];
        vec4 b = vertices[v + 1u];
        drawn = a.w >= 0.0 && b.w >= 0.0 && min(a.z, b.z) >= 0.0 && max(a.z, b.z) <= 1.0;
        RasterSegment s = makeRasterSegment(a.xy, b.xy, a.w, b.w);
        ivec4 bounds = ribbonPixelBounds(s, a.xy, b.xy, push.targetWidth, push.targetHeight);
        hidden = drawn && bounds.x <= bounds.z && bounds.y <= bounds.w && !reachesUnhiddenTile(bounds, min(a.z, b.z));
#ifdef RASTER_WRITE
        bounds.y = max(bounds.y, int(firstRow));  // only the piece's rows
        bounds.w = min(bounds.w, int(min(endRow, 0x7fffffffu)) - 1);
#endif
        if (drawn && !hidden) {
            vec4 colorA = unpackFragmentColor(colors[v]);
            vec4 colorB = unpackFragmentColor(colors[v + 1u]);
            uint samples = push.samples;
            // The walk runs a pixel ahead: the next pixel's depth range (and for strands.count its
            // room) is loaded while this one is worked out, and strands.count stores a fragment
            // only once the next fragment's atomic is on its way, so that a lane waits on memory
            // about once a fragment rather than three times (count 0.127 -> 0.100 ms on the seed's
            // workload on the H100, 1.160 -> 1.121 on the bob: docs/experiments.md).
            int y = bounds.y - 1, x = 0, x1 = -1;
            bool more = nextPixel(s, bounds.w, y, x, x1);
            uint nextP = more ? uint(y) * push.targetWidth + uint(x) : 0u;
            vec2 nextRange = depthRange[nextP];
#ifndef RASTER_WRITE
            uint nextFirst = reserved[nextP], nextEnd = reserved[nextP + 1u];
            bool pending = false;  // a fragment whose number at its pixel is on its way
            uint pendingP = 0u, pendingN = 0u, pendingFirst = 0u, pendingEnd = 0u;
            uvec2 pendingFragment = uvec2(0u);
#endif
            while (more) {
                vec2 centre = vec2(float(x), float(y)) + 0.5;
                uint p = nextP;
                vec2 range = nextRange;
#ifndef RASTER_WRITE
                uint first = nextFirst, end = nextEnd;
#endif
                more = nextPixel(s, bounds.w, y, x, x1);
                if (more) {
                    nextP = uint(y) * push.targetWidth + uint(x);
                    nextRange = depthRange[nextP];
#ifndef RASTER_WRITE
                    nextFirst = reserved[nextP];
                    nextEnd = reserved[nextP + 1u];
#endif
                }
                vec2 hit = segmentCoverage(s, centre);
                if (hit.x <= 0.0)
                    continue;
                float depth = mix(a.z, b.z, hit.y);
                uint front = depth <= range.x ? samples : 0u;
                if (depth > range.x && depth <= range.y) {  // at a mesh's edge: each sample
                    for (uint m = 0u; m < samples; ++m) {
                        float d = uintBitsToFloat(meshSamples[p * samples + m]);
                        front += depth <= d ? 1u : 0u;
                    }
                }
                if (front == 0u)
                    continue;
                vec4 c = mix(colorA, colorB, hit.y);
                float alpha = c.w * hit.x * float(front) / float(samples);
                if (alpha < 0.5 / 255.0)
                    continue;  // below what the fragment's 8 bits of alpha hold
#ifdef RASTER_WRITE
                if (p < firstPixel || p >= endPixel)
                    continue;  // another piece's pixel
                if (inReserved && offsets[p + 1u] - offsets[p] <= reserved[p + 1u] - reserved[p])
                    continue;  // strands.count wrote it into the pixel's room
                uint cursor = atomicAdd(counts[p], 1u);  // it starts at the pixel's offset
                if (capped && cursor - offsets[p] >= cap)
                    continue;
                uint slot = inReserved ? reservedEnd + cursor : cursor - base;
                if (slot < push.fragmentCapacity)
                    fragments[slot] = uvec2(floatBitsToUint(depth), packFragmentColor(c.rgb, alpha));
#else
                uint n = atomicAdd(counts[p], 1u);
                if (pending)
                    placeFragment(pendingP, pendingN, pendingFirst, pendingEnd, pendingFragment, spilled);
                pending = push.reserving != 0u;
                pendingP = p;
                pendingN = n;
                pendingFirst = first;
                pendingEnd = end;
                pendingFragment = uvec2(floatBitsToUint(depth), packFragmentColor(c.rgb, alpha));
#endif
            }
#ifndef RASTER_WRITE
            if (pending)
                placeFragment(pendingP, pendingN, pendingFirst, pendingEnd, pendingFragment, spilled);
#endif
        }
    }
    if (!kWrite && drawn)
        atomicAdd(groupSegments, 1u);
    if (!kWrite && hidden)
        atomicAdd(groupHidden, 1u);
    if (!kWrite && spilled > 0u)
        atomicAdd(groupSpilled, spilled);
    barrier();
    if (!kWrite && gl_LocalInvocationIndex == 0u && groupSegments > 0u)
        atomicAdd(counters.segments, groupSegments);
    if (!kWrite && gl_LocalInvocationIndex == 0u && groupHidden > 0u)
        atomicAdd(counters.hidden, groupHidden);
    if (!kWrite && gl_LocalInvocationIndex == 0u && groupSpilled > 0u)
        atomicAdd(counters.spilled, groupSpilled);
}
