// renderer/strand_draw.h: the strands a frame draws, as both hair paths take them: the guides,
// how many strands each one grows and how they are placed (interpolation, clumps, deviations),
// and LOD's continuous strand count with the width that keeps their coverage. The Renderer fills
// one for the camera and one for the light's maps; the graphics path turns it into the
// tessellation's push constants (renderer/graphics/hair_pass.h), the compute path into its
// kernels' (renderer/compute/strand_raster.h).
#pragma once

#include <cstdint>

namespace wisp {

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
