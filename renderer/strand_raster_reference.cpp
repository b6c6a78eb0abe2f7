// renderer/strand_raster_reference.cpp: the compute strand renderer's CPU twin (see the header).
// Each loop body is its kernel's main() over the same shared functions; only the addressing and
// the atomics (here plain adds, mins and appends) differ.
#include "renderer/strand_raster_reference.h"

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

}  // namespace

StrandVertices generateStrands(const gpu::StrandRasterPush& push, const gpu::FrameParams& frame,
                               const gpu::SimParams& sim, const std::vector<glm::vec3>& guides,
                               const std::vector<glm::uvec4>& triangles)
{
    uint32_t perStrand = push.divisions + 1;
    size_t count = size_t(push.guideCount) * push.drawnPerGuide * perStrand;
    StrandVertices out;
    out.positions.resize(count);
    out.colors.resize(count);
    for (uint32_t id = 0; id < count; ++id) {
        uint32_t drawn = id / perStrand;
        uint32_t i = id % perStrand;
        uint32_t guide = drawn / push.drawnPerGuide;
        uint32_t s = drawn % push.drawnPerGuide;
        float t = float(i) / float(push.divisions);
        gpu::CurvePoint g = evaluateGuide(guides, push.verticesPerStrand, guide, t);
        gpu::CurvePoint g1 = g, g2 = g;
        if (gpu::strandIsMulti(push.interpolation, s)) {
            g1 = evaluateGuide(guides, push.verticesPerStrand, triangles[guide].y, t);
            g2 = evaluateGuide(guides, push.verticesPerStrand, triangles[guide].z, t);
        }
        gpu::CurvePoint point =
            gpu::placeStrandPoint(g, g1, g2, guide, s, t, push.interpolation, push.clumpRadius, push.deviation);
        glm::vec3 p = point.position;
        if (s != 0)
            for (uint32_t c = 0; c < sim.colliderCount; ++c)
                p = gpu::pushOutOfCollider(sim.colliders[c], frame.headTransform, p);

        uint32_t strand = guide * push.strandsPerGuide + s;
        float alpha = frame.hairOpacity * gpu::lodAlpha(s, push.lodStrands);
        float worldWidth = gpu::strandWidthAt(push.width, t);
        if (push.fromLight != 0) {
            out.positions[id] = gpu::projectStrandVertex(frame.lightViewProjection, glm::vec2(frame.shadowMapSize), p,
                                                         worldWidth, frame.lightTexelsPerUnit);
            out.colors[id] = gpu::packFragmentColor(glm::vec3(0.0f), alpha);
            continue;
        }
        glm::vec2 size(frame.viewportWidth, frame.viewportHeight);
        float pixelsPerUnit = std::abs(frame.projection[1][1]) * 0.5f * size.y;
        out.positions[id] = gpu::projectStrandVertex(frame.viewProjection, size, p, worldWidth, pixelsPerUnit);
        glm::vec3 color = gpu::shadeStrandPoint(frame, p, point.tangent, t, strand, glm::vec2(1.0f), glm::vec3(0.0f));
        out.colors[id] = gpu::packFragmentColor(color, alpha);
    }
    return out;
}

TileBins binSegments(const gpu::StrandRasterPush& push, const std::vector<glm::vec4>& vertices)
{
    size_t tiles = size_t(push.tilesX) * push.tilesY;
    TileBins out;
    out.counts.assign(tiles, 0);
    out.bins.assign(tiles, {});
    for (uint32_t segment = 0; segment < push.segmentCount; ++segment) {
        uint32_t v = firstVertex(push, segment);
        glm::vec4 a = vertices[v], b = vertices[v + 1];
        if (!(a.w >= 0.0f && b.w >= 0.0f && std::min(a.z, b.z) >= 0.0f && std::max(a.z, b.z) <= 1.0f))
            continue;
        float r = gpu::segmentReach(a.w, b.w);
        float size = float(gpu::kRasterTileSize);
        int ty0 = std::max(int(std::floor((std::min(a.y, b.y) - r) / size)), 0);
        int ty1 = std::min(int(std::floor((std::max(a.y, b.y) + r) / size)), int(push.tilesY) - 1);
        bool drawn = false;
        for (int ty = ty0; ty <= ty1; ++ty) {
            glm::vec2 span = gpu::segmentRowSpan(glm::vec2(a), glm::vec2(b), r, float(ty) * size, float(ty + 1) * size);
            if (span.x > span.y)
                continue;
            int tx0 = std::max(int(std::floor(span.x / size)), 0);
            int tx1 = std::min(int(std::floor(span.y / size)), int(push.tilesX) - 1);
            for (int tx = tx0; tx <= tx1; ++tx) {
                size_t tile = size_t(ty) * push.tilesX + size_t(tx);
                ++out.counts[tile];
                out.bins[tile].push_back(segment);
                drawn = true;
            }
        }
        out.segments += drawn ? 1 : 0;
    }
    out.offsets.resize(tiles + 1);
    uint32_t total = 0;
    for (size_t t = 0; t < tiles; ++t) {
        out.offsets[t] = total;
        total += out.counts[t];
    }
    out.offsets[tiles] = total;
    return out;
}

std::vector<glm::vec4> rasterTiles(const gpu::StrandRasterPush& push, const StrandVertices& strands,
                                   const std::vector<std::vector<uint32_t>>& bins, const std::vector<float>& meshDepth,
                                   uint64_t* fragments)
{
    std::vector<glm::vec4> out(size_t(push.targetWidth) * push.targetHeight, glm::vec4(0.0f));
    uint32_t k = std::min(push.oitK, gpu::kMaxOitK);
    uint64_t added = 0;
    for (uint32_t y = 0; y < push.targetHeight; ++y) {
        for (uint32_t x = 0; x < push.targetWidth; ++x) {
            size_t tile = size_t(y / gpu::kRasterTileSize) * push.tilesX + x / gpu::kRasterTileSize;
            glm::vec2 centre = glm::vec2(float(x), float(y)) + 0.5f;
            glm::vec2 origin = glm::vec2(float(x / gpu::kRasterTileSize), float(y / gpu::kRasterTileSize)) *
                               float(gpu::kRasterTileSize);
            uint32_t lane = (y % gpu::kRasterTileSize) * gpu::kRasterTileSize + x % gpu::kRasterTileSize;
            float depthHere = meshDepth[size_t(y) * push.targetWidth + x];
            gpu::PixelFragments f = gpu::emptyPixelFragments();
            for (uint32_t segment : bins[tile]) {
                uint32_t v = firstVertex(push, segment);
                glm::vec4 a = strands.positions[v], b = strands.positions[v + 1];
                glm::uvec2 mask = gpu::tilePixelMask(glm::vec2(a), glm::vec2(b), gpu::segmentReach(a.w, b.w), origin);
                if (((lane < 32 ? mask.x : mask.y) & (1u << (lane % 32))) == 0)
                    continue;
                gpu::RasterSegment s = gpu::makeRasterSegment(glm::vec2(a), glm::vec2(b), a.w, b.w);
                glm::vec2 hit = gpu::segmentCoverage(s, centre);
                if (hit.x <= 0.0f)
                    continue;
                float depth = glm::mix(a.z, b.z, hit.y);
                if (!(depth <= depthHere))
                    continue;
                glm::vec4 c = glm::mix(gpu::unpackFragmentColor(strands.colors[v]),
                                       gpu::unpackFragmentColor(strands.colors[v + 1]), hit.y);
                float alpha = c.w * hit.x;
                if (alpha < 0.5f / 255.0f)
                    continue;
                gpu::insertFragment(f, k, depth, gpu::packFragmentColor(glm::vec3(c), alpha));
                ++added;
            }
            out[size_t(y) * push.targetWidth + x] = gpu::resolveFragments(f, k);
        }
    }
    if (fragments)
        *fragments = added;
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
            float alpha = 0.5f * (glm::unpackUnorm4x8(strands.colors[v]).w + glm::unpackUnorm4x8(strands.colors[v + 1]).w);
            gpu::RasterSegment s = gpu::makeRasterSegment(glm::vec2(a), glm::vec2(b), a.w, b.w);
            float r = std::max(gpu::segmentReach(a.w, b.w), 1.2072f);
            bool alongX = std::abs(b.x - a.x) >= std::abs(b.y - a.y);
            glm::vec2 pa = alongX ? glm::vec2(a.y, a.x) : glm::vec2(a);
            glm::vec2 pb = alongX ? glm::vec2(b.y, b.x) : glm::vec2(b);
            int lo = int(std::floor(std::min(pa.y, pb.y) - r));
            int hi = int(std::floor(std::max(pa.y, pb.y) + r));
            int limit = int(alongX ? push.targetWidth : push.targetHeight);
            for (int line = std::max(lo, 0); line <= std::min(hi, limit - 1); ++line) {
                glm::vec2 span = gpu::segmentRowSpan(pa, pb, r, float(line), float(line + 1));
                if (span.x > span.y)
                    continue;
                for (int m = int(std::floor(span.x)); m <= int(std::floor(span.y)); ++m) {
                    glm::ivec2 texel = alongX ? glm::ivec2(line, m) : glm::ivec2(m, line);
                    if (texel.x < 0 || texel.y < 0 || texel.x >= int(push.targetWidth) ||
                        texel.y >= int(push.targetHeight))
                        continue;
                    size_t index = size_t(texel.y) * push.targetWidth + size_t(texel.x);
                    glm::vec2 centre = glm::vec2(texel) + 0.5f;
                    if (!opacity) {
                        glm::vec2 d = centre - s.a;
                        float u = glm::dot(d, s.dir);
                        float t = s.len > 0.0f ? std::clamp(u / s.len, 0.0f, 1.0f) : 0.0f;
                        float across = std::abs(s.dir.x * d.y - s.dir.y * d.x);
                        if (u < 0.0f || u > s.len || across > std::max(glm::mix(s.ha, s.hb, t), 0.5f))
                            continue;
                        uint32_t bits = std::bit_cast<uint32_t>(std::max(glm::mix(a.z, b.z, t), 0.0f));
                        out.depth[index] = std::min(out.depth[index], bits);
                        continue;
                    }
                    glm::vec2 hit = gpu::segmentCoverage(s, centre);
                    if (hit.x <= 0.0f)
                        continue;
                    float z0 = std::bit_cast<float>(out.depth[index]);
                    float depth = glm::mix(a.z, b.z, hit.y);
                    uint32_t layers = std::clamp(push.domLayers, 1u, gpu::kMaxDomLayers);
                    uint32_t layer = std::min(uint32_t(std::max(depth - z0, 0.0f) / std::max(frame.domSpacing, 1e-12f)),
                                              layers - 1);
                    out.opacity[index][int(layer)] += uint32_t(alpha * hit.x * gpu::kOpacityFixedScale + 0.5f);
                }
            }
        }
    }
    return out;
}

}  // namespace wisp::reference
