// renderer/strand_draw.h: the strands a frame draws, as both hair paths take them: how many (the
// guides, strands per guide, segments per strand: what the commands and the panel report), how
// they are placed (interpolation, clumps, deviations), and LOD's continuous strand count with the
// width that keeps their coverage. The Renderer fills one draw for the camera and one for the
// light's maps; each path turns it into its own push constants (the tessellation's patches and
// instances are the graphics path's own arithmetic, renderer/graphics/).
#pragma once

#include "renderer/settings.h"

#include <cstdint>

namespace wisp {

// What a frame draws for given settings, whichever path draws it: every strand at full detail
// (before LOD), each cut into `divisions` segments.
struct StrandCounts {
    uint32_t guides = 0;
    uint32_t strandsPerGuide = 0; // as drawn (before LOD)
    uint32_t divisions = 0;       // segments per strand
    uint64_t strands() const { return uint64_t(guides) * strandsPerGuide; }
    uint64_t segments() const { return strands() * divisions; }
};
// The device memory of the guides' triangles (each guide with the two it interpolates between), of
// which the path that draws the strands uploads its own copy.
constexpr uint64_t guideTriangleBytes(uint64_t guides)
{
    return guides * 4 * sizeof(uint32_t);
}

inline StrandCounts strandCounts(uint32_t guides, const StrandSettings& settings)
{
    return {.guides = guides, .strandsPerGuide = settings.strandsPerGuide, .divisions = settings.divisions};
}

struct StrandDraw {
    uint32_t guides = 0;
    uint32_t verticesPerStrand = 0; // V of the guides
    uint32_t strandsPerGuide = 0;   // S as set (a strand's identity is guide * S + s on both paths)
    uint32_t divisions = 0;         // D segments per strand
    uint32_t interpolation = 0;     // gpu::kInterpolation* (shaders/shared/strands.h)
    float clumpRadius = 0.0f;       // asset units
    float deviation = 0.0f;         // asset units
    float coilRadius = 0.0f;        // render-time coil's helix radius, asset units (0: none)
    float coilFrequency = 0.0f;     // its turns per asset unit of length
    float width = 0.0f;             // strand width at the root, asset units, before LOD's scale
    float lodStrands = 0.0f;        // strands per guide after LOD (continuous, <= S)
    float lodWidthScale = 1.0f;     // LOD's width multiplier
    float minPixelWidth = 0.0f;     // ribbons narrower than this are widened, their alpha scaled
    bool reverseOrder = false;      // guides and strand chunks last to first (order-independence tests)
};

} // namespace wisp
