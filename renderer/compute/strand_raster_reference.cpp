// renderer/compute/strand_raster_reference.cpp: the compute strand renderer's CPU twin (see the header).
// Each loop body is its kernel's main() over the same shared functions; only the addressing and
// the atomics (here plain adds, mins and appends) differ.
#include "renderer/compute/strand_raster_reference.h"

#include "shaders/shared/strand_shading.h"
#include "shaders/shared/strands.h"

#include <algorithm>
#include <bit>
#include <cmath>

namespace wisp::reference {

namespace {

gpu::CurvePoint evaluateGuide(const std::vector<glm::vec3>& guides, uint32_t V, uint32_t guide, float t)
{
    uint32_t seg = gpu::curveSegment(t, V);
    auto point = [&](uint32_t i) { return guides[size_t(guide) * V + i]; };
    return gpu::guideCurvePoint(point(seg == 0 ? 0 : seg - 1), point(seg), point(seg + 1),
                                point(std::min(seg + 2, V - 1)), gpu::curveLocal(t, V, seg));
}

uint32_t firstVertex(const gpu::StrandRasterPush& push, uint32_t segment)
{
    return segment / push.divisions * (push.divisions + 1) + segment % push.divisions;
}

} // namespace

std::vector<gpu::CurvePoint> guideCurves(const gpu::StrandRasterPush& push, const std::vector<glm::vec3>& guides)
{
    uint32_t perGuide = push.divisions + 1;
    std::vector<gpu::CurvePoint> out(size_t(push.guideCount) * perGuide);
    for (uint32_t id = 0; id < out.size(); ++id) {
        float t = float(id % perGuide) / float(push.divisions);
        out[id] = evaluateGuide(guides, push.verticesPerStrand, id / perGuide, t);
    }
    return out;
}

namespace {

// Vertex `id` of the drawn strands as strands_generate.comp places it: which guide, which of its
// strands and how far along (t = i / D of the strand, which lies along the first
// strandLengthFraction of its guide), the point (pushed out of the colliders), its tangent and
// its world width. `curves`: guideCurves().
struct PlacedVertex {
    uint32_t guide = 0;
    uint32_t s = 0; // of the guide's drawnPerGuide
    float t = 0.0f;
    glm::vec3 position{0.0f};
    glm::vec3 tangent{0.0f};
    float width = 0.0f;
};

PlacedVertex placeVertex(const gpu::StrandRasterPush& push, const gpu::FrameParams& frame, const gpu::SimParams& sim,
                         const std::vector<gpu::CurvePoint>& curves, const std::vector<glm::uvec4>& triangles,
                         uint32_t id)
{
    uint32_t perStrand = push.divisions + 1;
    uint32_t drawn = id / perStrand;
    uint32_t i = id % perStrand;
    PlacedVertex v;
    v.guide = drawn / push.drawnPerGuide;
    v.s = drawn % push.drawnPerGuide;
    v.t = float(i) / float(push.divisions);
    float fraction = gpu::strandLengthFraction(v.guide, v.s, frame.strandLengthJitter);
    float x = float(i) * fraction;
    auto curveAt = [&](uint32_t guide) { // the kernel's guideCurveAt
        uint32_t k = gpu::curveSampleBelow(x, push.divisions);
        const gpu::CurvePoint* c = &curves[size_t(guide) * perStrand];
        return gpu::curveBetweenSamples(c[k], c[k + 1], x - float(k),
                                        float(push.verticesPerStrand - 1) / float(push.divisions));
    };
    gpu::CurvePoint g = curveAt(v.guide);
    gpu::CurvePoint g1 = g, g2 = g;
    if (gpu::strandIsMulti(push.interpolation, v.s)) {
        g1 = curveAt(triangles[v.guide].y);
        g2 = curveAt(triangles[v.guide].z);
    }
    gpu::CurvePoint point = gpu::placeStrandPoint(
        g, g1, g2, v.guide, v.s, gpu::strandGuideParameter(v.t, fraction), push.interpolation, push.clumpRadius,
        push.deviation, gpu::guideLength(triangles[v.guide].w), push.coilRadius, push.coilFrequency, push.divisions);
    v.position = point.position;
    if (v.s != 0)
        for (uint32_t c = 0; c < sim.colliderCount; ++c)
            v.position = gpu::pushOutOfCollider(sim.colliders[c], frame.headTransform, v.position);
    v.tangent = point.tangent;
    v.width = gpu::strandWidthAt(push.width * gpu::guideWidthScale(triangles[v.guide].w), v.t);
    return v;
}

size_t drawnVertexCount(const gpu::StrandRasterPush& push)
{
    return size_t(push.guideCount) * push.drawnPerGuide * (push.divisions + 1);
}

} // namespace

DrawnStrands placeStrands(const gpu::StrandRasterPush& push, const gpu::FrameParams& frame, const gpu::SimParams& sim,
                          const std::vector<glm::vec3>& guides, const std::vector<glm::uvec4>& triangles)
{
    size_t count = drawnVertexCount(push);
    std::vector<gpu::CurvePoint> curves = guideCurves(push, guides); // strands.curves, as the kernel reads it
    DrawnStrands out;
    out.positions.resize(count);
    out.tangents.resize(count);
    out.widths.resize(count);
    for (uint32_t id = 0; id < count; ++id) {
        PlacedVertex v = placeVertex(push, frame, sim, curves, triangles, id);
        out.positions[id] = v.position;
        out.tangents[id] = v.tangent;
        out.widths[id] = v.width;
    }
    return out;
}

StrandVertices generateStrands(const gpu::StrandRasterPush& push, const gpu::FrameParams& frame,
                               const gpu::SimParams& sim, const std::vector<glm::vec3>& guides,
                               const std::vector<glm::uvec4>& triangles)
{
    size_t count = drawnVertexCount(push);
    std::vector<gpu::CurvePoint> curves = guideCurves(push, guides);
    StrandVertices out;
    out.positions.resize(count);
    out.colors.resize(count);
    for (uint32_t id = 0; id < count; ++id) {
        PlacedVertex v = placeVertex(push, frame, sim, curves, triangles, id); // as placeStrands places it
        uint32_t strand = v.guide * push.strandsPerGuide + v.s;
        float alpha = frame.hairOpacity * gpu::lodAlpha(v.s, push.lodStrands);
        if (push.fromLight != 0) {
            out.positions[id] = gpu::projectStrandVertex(frame.lightViewProjection, glm::vec2(frame.shadowMapSize),
                                                         v.position, v.width, frame.lightTexelsPerUnit);
            out.colors[id] = gpu::packFragmentColor(glm::vec3(0.0f), alpha);
            continue;
        }
        glm::vec2 size(frame.viewportWidth, frame.viewportHeight);
        float pixelsPerUnit = std::abs(frame.projection[1][1]) * 0.5f * size.y;
        out.positions[id] = gpu::projectStrandVertex(frame.viewProjection, size, v.position, v.width, pixelsPerUnit);
        glm::vec3 noLut[gpu::kFrameLights]{}; // (the twin is compared in the karis and kajiya modes)
        glm::vec3 color = gpu::shadeStrandPoint(frame, v.position, v.tangent, v.t, strand, glm::vec2(1.0f), noLut);
        out.colors[id] = gpu::packFragmentColor(color, alpha);
    }
    return out;
}

std::vector<std::vector<Fragment>> pixelFragments(const gpu::StrandRasterPush& push, const StrandVertices& strands,
                                                  const std::vector<float>& meshDepth, SegmentCounts* counts)
{
    std::vector<std::vector<Fragment>> out(size_t(push.targetWidth) * push.targetHeight);
    SegmentCounts found;
    // strands_depth.comp's coarse depth: each tile's farthest sample.
    constexpr int kTile = int(gpu::kRasterDepthTile);
    int tilesX = (int(push.targetWidth) + kTile - 1) / kTile, tilesY = (int(push.targetHeight) + kTile - 1) / kTile;
    std::vector<float> tileDepth(size_t(tilesX) * size_t(tilesY), 0.0f);
    for (uint32_t y = 0; y < push.targetHeight; ++y)
        for (uint32_t x = 0; x < push.targetWidth; ++x) {
            float& tile = tileDepth[size_t(int(y) / kTile) * size_t(tilesX) + size_t(int(x) / kTile)];
            tile = std::max(tile, meshDepth[size_t(y) * push.targetWidth + x]);
        }
    // strands_fragments.comp's reachesUnhiddenTile.
    auto hidden = [&](glm::ivec4 bounds, float nearest) {
        if (bounds.x > bounds.z || bounds.y > bounds.w)
            return false;
        glm::ivec4 tiles = bounds / kTile;
        if (uint32_t((tiles.z - tiles.x + 1) * (tiles.w - tiles.y + 1)) > gpu::kRasterMaxCullTiles)
            return false;
        for (int ty = tiles.y; ty <= tiles.w; ++ty)
            for (int tx = tiles.x; tx <= tiles.z; ++tx)
                if (gpu::depthCanPass(nearest, tileDepth[size_t(ty) * size_t(tilesX) + size_t(tx)]))
                    return false;
        return true;
    };
    for (uint32_t segment = 0; segment < push.segmentCount; ++segment) {
        uint32_t v = firstVertex(push, segment);
        glm::vec4 a = strands.positions[v], b = strands.positions[v + 1];
        if (!(a.w >= 0.0f && b.w >= 0.0f && std::min(a.z, b.z) >= 0.0f && std::max(a.z, b.z) <= 1.0f))
            continue;
        ++found.drawn;
        gpu::RasterSegment s = gpu::makeRasterSegment(glm::vec2(a), glm::vec2(b), a.w, b.w);
        glm::vec4 colorA = gpu::unpackFragmentColor(strands.colors[v]);
        glm::vec4 colorB = gpu::unpackFragmentColor(strands.colors[v + 1]);
        glm::ivec4 bounds = gpu::ribbonPixelBounds(s, glm::vec2(a), glm::vec2(b), push.targetWidth, push.targetHeight);
        bool skipped = hidden(bounds, std::min(a.z, b.z)); // walked all the same: any fragment is a loss
        found.hidden += skipped ? 1 : 0;
        bool gave = false;
        for (int y = bounds.y; y <= bounds.w; ++y) {
            glm::vec2 span = gpu::ribbonRowSpan(s, float(y) + 0.5f);
            int x0 = std::max(int(std::ceil(span.x - 0.5f)), 0);
            int x1 = std::min(int(std::floor(span.y - 0.5f)), int(push.targetWidth) - 1);
            for (int x = x0; x <= x1; ++x) {
                glm::vec2 hit = gpu::segmentCoverage(s, glm::vec2(float(x), float(y)) + 0.5f);
                if (hit.x <= 0.0f)
                    continue;
                float depth = glm::mix(a.z, b.z, hit.y);
                size_t p = size_t(y) * push.targetWidth + size_t(x);
                if (!(depth <= meshDepth[p]))
                    continue;
                glm::vec4 c = glm::mix(colorA, colorB, hit.y);
                float alpha = c.w * hit.x;
                if (alpha < 0.5f / 255.0f)
                    continue;
                out[p].push_back({depth, gpu::packFragmentColor(glm::vec3(c), alpha)});
                gave = true;
            }
        }
        found.hiddenWithFragments += skipped && gave ? 1 : 0;
    }
    if (counts)
        *counts = found;
    return out;
}

std::vector<gpu::RasterPiece> framePieces(const gpu::StrandRasterPush& push, const std::vector<uint32_t>& offsets,
                                          const gpu::RasterCounters& counters, uint32_t recorded, uint32_t* notDrawn)
{
    uint32_t stride = counters.stride, needed = counters.pieces;
    uint32_t walked = counters.reservedEnd == gpu::kRasterNotReserved
                          ? push.segmentCount
                          : gpu::rasterSpillWriteThreads(counters.spilled, push.spillCapacity, push.segmentCount);
    uint32_t width = push.targetWidth;
    uint32_t pixels = width * push.targetHeight;
    auto firstPixelFrom = [&](uint32_t target) {
        return uint32_t(std::lower_bound(offsets.begin(), offsets.begin() + pixels, target) - offsets.begin());
    };
    std::vector<gpu::RasterPiece> out(recorded);
    *notDrawn = 0;
    for (uint32_t p = 0; p < recorded; ++p) {
        gpu::RasterPiece& r = out[p];
        r = {};
        if (p < needed) {
            r.firstPixel = p == 0 ? 0u : firstPixelFrom(p * stride);
            r.endPixel = p + 1 < needed ? firstPixelFrom((p + 1) * stride) : pixels;
        }
        bool drawn = r.firstPixel < r.endPixel;
        r.firstRow = drawn ? r.firstPixel / width : 0u;
        r.endRow = drawn ? (r.endPixel - 1) / width + 1 : 0u;
        glm::uvec2 walk = drawn ? gpu::rasterLinearGroups(walked, gpu::kRasterGroupSize) : glm::uvec2(0);
        r.walkGroups[0] = walk.x;
        r.walkGroups[1] = walk.y;
        r.walkGroups[2] = 1;
        r.resolveRow = r.firstRow / 8;
        r.resolveGroups[0] = drawn ? (width + 7) / 8 : 0u;
        r.resolveGroups[1] = drawn ? (r.endRow + 7) / 8 - r.resolveRow : 0u;
        r.resolveGroups[2] = 1;
        if (p + 1 == recorded && needed > recorded)
            *notDrawn = offsets[pixels] - offsets[firstPixelFrom(recorded * stride)];
    }
    return out;
}

std::vector<uint32_t> reservedLayout(const std::vector<uint32_t>& offsets)
{
    std::vector<uint32_t> out(offsets.size());
    for (size_t p = 0; p < offsets.size(); ++p)
        out[p] = gpu::rasterReservedSlot(offsets[p], uint32_t(p));
    return out;
}

std::vector<glm::vec4> resolvePixels(const gpu::StrandRasterPush& push,
                                     const std::vector<std::vector<Fragment>>& pixels)
{
    uint32_t k = std::clamp(push.oitK, 1u, gpu::kMaxOitK);
    std::vector<glm::vec4> out(pixels.size());
    for (size_t p = 0; p < pixels.size(); ++p) {
        gpu::PixelFragments f = gpu::emptyPixelFragments();
        for (const Fragment& fragment : pixels[p])
            gpu::insertFragment(f, k, fragment.depth, fragment.color);
        out[p] = gpu::resolveFragments(f, k);
    }
    return out;
}

LightMaps rasterLight(const gpu::StrandRasterPush& push, const gpu::FrameParams& frame, const StrandVertices& strands)
{
    size_t texels = size_t(push.targetWidth) * push.targetHeight;
    LightMaps out;
    out.depth.assign(texels, std::bit_cast<uint32_t>(1.0f));
    out.opacity.assign(texels, glm::uvec4(0));
    for (int pass = 0; pass < 2; ++pass) {
        bool opacity = pass == 1;
        for (uint32_t segment = 0; segment < push.segmentCount; ++segment) {
            uint32_t v = firstVertex(push, segment);
            glm::vec4 a = strands.positions[v], b = strands.positions[v + 1];
            if (a.w < 0.0f || b.w < 0.0f)
                continue;
            float alpha =
                0.5f * (glm::unpackUnorm4x8(strands.colors[v]).w + glm::unpackUnorm4x8(strands.colors[v + 1]).w);
            gpu::RasterSegment s = gpu::makeRasterSegment(glm::vec2(a), glm::vec2(b), a.w, b.w);
            gpu::RasterSegment reach =
                gpu::makeRasterSegment(glm::vec2(a), glm::vec2(b), std::max(a.w, 0.5f), std::max(b.w, 0.5f));
            glm::ivec4 bounds =
                gpu::lightTexelBounds(reach, glm::vec2(a), glm::vec2(b), push.targetWidth, push.targetHeight);
            for (int y = bounds.y; y <= bounds.w; ++y) {
                glm::vec2 span = gpu::lightRowCentres(reach, float(y) + 0.5f);
                int x0 = std::max(int(std::ceil(span.x - 0.5f)), 0);
                int x1 = std::min(int(std::floor(span.y - 0.5f)), int(push.targetWidth) - 1);
                for (int x = x0; x <= x1; ++x) {
                    glm::ivec2 texel(x, y);
                    if (texel.x < 0 || texel.y < 0 || texel.x >= int(push.targetWidth) ||
                        texel.y >= int(push.targetHeight))
                        continue;
                    size_t index = size_t(texel.y) * push.targetWidth + size_t(texel.x);
                    glm::vec3 hit = gpu::lightTexelHit(s, glm::vec2(texel) + 0.5f);
                    if (hit.x <= 0.0f)
                        continue;
                    float depth = glm::mix(a.z, b.z, hit.y);
                    if (!opacity) {
                        uint32_t bits = std::bit_cast<uint32_t>(std::max(depth, 0.0f));
                        out.depth[index] = std::min(out.depth[index], bits);
                        continue;
                    }
                    float z0 = std::bit_cast<float>(out.depth[index]);
                    uint32_t layers = std::clamp(push.domLayers, 1u, gpu::kMaxDomLayers);
                    uint32_t layer =
                        std::min(uint32_t(std::max(depth - z0, 0.0f) / std::max(frame.domSpacing, 1e-12f)), layers - 1);
                    out.opacity[index][int(layer)] += uint32_t(alpha * hit.z * gpu::kOpacityFixedScale + 0.5f);
                }
            }
        }
    }
    return out;
}

} // namespace wisp::reference
