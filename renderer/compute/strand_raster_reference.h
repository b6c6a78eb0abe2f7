// renderer/compute/strand_raster_reference.h: the compute strand renderer's kernels in plain C++, over the
// same shared math (shaders/shared/strands.h, strand_shading.h, strand_raster.h): each function is
// the twin of one kernel, one loop where the kernel has one thread per item. The tests run both on
// the same input and compare (tests/test_strand_raster.cpp). No Vulkan.
#pragma once

#include "shaders/shared/frame_params.h"
#include "shaders/shared/sim.h"
#include "shaders/shared/strand_raster.h"
#include "shaders/shared/strands.h"

#include <glm/glm.hpp>

#include <cstdint>
#include <vector>

namespace wisp::reference {

struct StrandVertices {
    std::vector<glm::vec4> positions; // StrandVertex: x, y pixels, depth, half width (< 0: not drawn)
    std::vector<uint32_t> colors;     // packFragmentColor(rgb, opacity)
};

// strands_curves.comp: each guide's curve at the strands' points t = i / D (guide * (D + 1) + i).
// `guides` holds the guide vertices in strand-major order (guide * V + i).
std::vector<gpu::CurvePoint> guideCurves(const gpu::StrandRasterPush& push, const std::vector<glm::vec3>& guides);

// The drawn strands in world space, as strands_generate.comp places them before it projects them:
// vertex (guide * drawnPerGuide + s) * (D + 1) + i, its unit tangent and its world width
// (strandWidthAt of the guide's share of the width setting, guideWidthScale). The path tracer
// (renderer/reference/) traces these.
struct DrawnStrands {
    std::vector<glm::vec3> positions;
    std::vector<glm::vec3> tangents;
    std::vector<float> widths;
};
DrawnStrands placeStrands(const gpu::StrandRasterPush& push, const gpu::FrameParams& frame, const gpu::SimParams& sim,
                          const std::vector<glm::vec3>& guides, const std::vector<glm::uvec4>& triangles);

// strands_generate.comp (and _light with push.fromLight): `guides` holds the guide vertices in
// strand-major order (guide * V + i). Shading with the light's visibility at 1 (the twin does not
// sample the light's maps: compare with shadows off) and the karis or kajiya model.
StrandVertices generateStrands(const gpu::StrandRasterPush& push, const gpu::FrameParams& frame,
                               const gpu::SimParams& sim, const std::vector<glm::vec3>& guides,
                               const std::vector<glm::uvec4>& triangles);

// One fragment as strands_fragments.comp writes it: its depth and its packed colour and opacity.
struct Fragment {
    float depth = 0.0f;
    uint32_t color = 0;
    bool operator<(const Fragment& o) const { return depth != o.depth ? depth < o.depth : color < o.color; }
    bool operator==(const Fragment& o) const { return depth == o.depth && color == o.color; }
};

// What pixelFragments() found of the segments: those drawn (on screen, in front of the camera),
// those of them the kernels skip as hidden (behind the farthest mesh depth of every 8 x 8 tile
// they reach), and of those the ones that gave a fragment all the same (the twin walks every
// segment: 0 unless the skip loses hair).
struct SegmentCounts {
    uint32_t drawn = 0;
    uint32_t hidden = 0;
    uint32_t hiddenWithFragments = 0;
};

// strands_depth.comp, strands_fragments.comp (count and write) and the scan: every pixel's
// fragments (row-major), given the meshes' depth (one sample per pixel, row-major), each pixel's
// in the order the segments come (the kernels' order is the atomics').
std::vector<std::vector<Fragment>> pixelFragments(const gpu::StrandRasterPush& push, const StrandVertices& strands,
                                                  const std::vector<float>& meshDepth, SegmentCounts* counts = nullptr);

// strands_pieces.comp: the `recorded` pieces of a frame whose scan gave `offsets` (pixels + 1,
// the total last), cut at `stride` into `needed` pieces; `notDrawn` gets the fragments of the
// pixels past the recorded pieces. `counters` say whether the frame is drawn in the reserved
// layout and whether any fragment spilled (no second walk when it is and none did).
std::vector<gpu::RasterPiece> framePieces(const gpu::StrandRasterPush& push, const std::vector<uint32_t>& offsets,
                                          const gpu::RasterCounters& counters, uint32_t recorded, uint32_t* notDrawn);

// strands_reserve.comp: the next frame's reserved first slot of every pixel (and one past the
// last) from this frame's `offsets`.
std::vector<uint32_t> reservedLayout(const std::vector<uint32_t>& offsets);

// strands_resolve.comp: the premultiplied hair of every pixel.
std::vector<glm::vec4> resolvePixels(const gpu::StrandRasterPush& push,
                                     const std::vector<std::vector<Fragment>>& pixels);

struct LightMaps {
    std::vector<uint32_t> depth;     // float bits per texel: the hair's first depth (1 where none)
    std::vector<glm::uvec4> opacity; // fixed-point opacity per texel and layer
};

// strands_light.comp, both variants (the light's strands from generateStrands with fromLight).
LightMaps rasterLight(const gpu::StrandRasterPush& push, const gpu::FrameParams& frame, const StrandVertices& strands);

} // namespace wisp::reference
