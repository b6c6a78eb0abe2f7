// renderer/settings.h: the render settings as plain structs with units and defaults; their names,
// ranges and help for people are the settings table's (app/settings/settings_table.cpp), and pack() in
// renderer.cpp turns them into the GPU's FrameParams.
#pragma once

#include "core/range.h"
#include "shaders/shared/strands.h"
#include "shading/hair_look.h"

#include <glm/glm.hpp>

#include <cstdint>
#include <string>

namespace wisp {

inline constexpr Range kImageSizeRange{16, 8192}; // pixels per side of the image (--width, --height)

// A directional light. The key (RenderSettings::light) is shadowed (the light's maps); the fill
// and the rim are not (shaders/shared/frame_params.h frameLight, evaluated in one loop by the meshes
// and the hair).
struct LightSettings {
    float azimuthDeg = 40.0f;            // around the up axis, 0 = in front of the face, + toward the head's left (+x)
    float elevationDeg = 35.0f;          // above the horizontal plane
    float intensity = 3.2f;              // radiance scale; 0 turns the light off
    glm::vec3 color{1.0f, 0.93f, 0.84f}; // warm key light, linear RGB

    glm::vec3 direction() const; // unit vector toward the light (world space, y up, face +z)
};

// The studio's defaults, a portrait's three lights around the default camera (yaw 25): the key
// (LightSettings' own defaults) warm, high and to the camera's right; the fill soft and cool on its
// left, a little above the eyes, about a quarter of the key; the rim behind and above the head,
// stronger than the key, lighting the crown and the hair's edge through its reflection and its
// transmission (Karis TT).
inline constexpr LightSettings kDefaultFill{
    .azimuthDeg = -45.0f, .elevationDeg = 10.0f, .intensity = 0.9f, .color = {0.78f, 0.87f, 1.0f}};
inline constexpr LightSettings kDefaultRim{
    .azimuthDeg = -160.0f, .elevationDeg = 40.0f, .intensity = 4.0f, .color = {1.0f, 0.97f, 0.93f}};

enum class Interpolation { Single, Multi, Mixed };

// How the simulated guides become drawn strands, on both paths (shaders/shared/strands.h: the compute
// path's strands.generate, the tessellation path's hair.tese).
struct StrandSettings {
    // Strands drawn per guide (the guide is one of them): the default's 2,200 guides x 46 draw 101,200,
    // a full head (more drawn strands cost the raster alone; more guides would cost the physics too).
    uint32_t strandsPerGuide = 46;
    uint32_t divisions = 24; // segments per drawn strand
    Interpolation interpolation = Interpolation::Mixed;
    float clumpRadiusMetres = 0.01f; // single-strand disc radius
    float deviationMetres = 0.012f;  // strength of random deviations
    float coilRadiusMetres = 0.0f;   // render-time coil (shaders/shared/strands.h coilAt): helix radius
    float coilTurnsPerMetre = 0.0f;  // its turns per metre along the strand
    float widthMetres = 0.0005f;     // ribbon width at the root
    bool lod = true;                 // fewer, wider strands with distance
    float lodMinFraction = 0.2f;     // LOD never draws fewer than this share of strands
    float minPixelWidth = 1.0f;      // narrower ribbons are widened, alpha = coverage
    bool showGuides = false;         // also draw the guides as lines
    // Each drawn strand cut from the tip by up to this share of its guide's length (uniform, its own
    // hash: shaders/shared/strands.h strandLengthFraction), so a clump's tips thin out; 0: every
    // strand as long as its guide. The default is the bob's (physics/hair_style.cpp); a loaded
    // groom is drawn at 0 unless it is given (app/commands/command.cpp).
    float lengthJitter = 0.15f;
    // The tessellation path's test knobs, not settings: draw the strands last to first (OIT order
    // tests), and how many vertices one patch may emit (shaders/shared/strands.h; lavapipe needs
    // <= ~128).
    bool reverseOrder = false;
    uint32_t maxPatchVertices = gpu::kMaxPatchVertices;
};

// strands_per_guide for a loaded groom when none is given: about kLoadedGroomStrands drawn in all
// (a head of hair has 100,000 to 150,000), so a file that holds every strand of a groom draws each
// once or a few times and a file of sparse guides draws more, at most `most` (the default).
inline constexpr uint64_t kLoadedGroomStrands = 100000;
constexpr uint32_t loadedStrandsPerGuide(uint64_t strandsInFiles, uint32_t most)
{
    if (strandsInFiles == 0)
        return most;
    uint64_t perStrand = (kLoadedGroomStrands + strandsInFiles / 2) / strandsInFiles;
    return uint32_t(perStrand < 1 ? 1 : perStrand > most ? most : perStrand);
}

// The key light's shadows, on both paths (renderer/light_maps.cpp, shaders/light_visibility.glsl).
struct ShadowSettings {
    bool enabled = true;
    uint32_t mapSize = 2048;         // shadow and deep opacity maps, texels per side
    uint32_t pcfSamples = 16;        // PCF taps
    float pcfRadiusTexels = 2.0f;    // PCF disk radius
    uint32_t domLayers = 4;          // deep opacity layers; 0: hair self-shadows by PCF instead
    float domSpacingMetres = 0.006f; // depth of one deep opacity layer
    float domKappa = 0.9f;           // transmittance = exp(-kappa * opacity)
    float strandFraction = 0.25f;    // share of the strands drawn into the light's maps (wider, same coverage)
};

enum class Transparency { Oit, Msaa };

// How hair fragments become pixels. oitK and hairOpacity serve both paths (the compute path's
// strands.resolve, the tessellation path's oit_resolve.comp: shaders/shared/strand_raster.h); the mode and
// the node pool are the tessellation path's (renderer/graphics/oit.cpp): the compute path always
// keeps per-pixel lists, in a buffer sized by RenderSettings::fragmentBudgetMiB.
struct TransparencySettings {
    Transparency mode = Transparency::Oit; // the tessellation path: lists, or opaque coverage with MSAA
    uint32_t oitK = 8;                     // nearest fragments sorted per pixel; the rest blended unsorted
    uint32_t oitNodesPerPixel = 0; // the tessellation path's fragment pool per pixel of the target; 0: automatic (24
                                   // per pixel, at least 8M nodes, grown when a frame overflows, within the limits)
    uint64_t oitAutoNodes = 0; // where the automatic pool starts, in nodes (0: the rule above; tests start it small)
    float hairOpacity = 0.85f; // opacity of a strand that covers its pixel (oit, deep opacity)
};

// How the hair is drawn: the tessellation and geometry stages (renderer/graphics/hair_pass.cpp), or
// entirely in compute (renderer/compute/strand_raster.cpp); auto picks the faster (resolveHairRaster).
enum class HairRaster { Graphics, Compute, Auto };

// What hair_raster=auto draws with: compute, the faster on every device measured, whatever the
// workload (docs/drawing.md, "Two ways to draw strands": lavapipe and an NVIDIA H100). Here, not in
// renderer.cpp, so that the workload's memory (app/settings/workload.cpp, without a device) counts
// the path that will draw.
constexpr HairRaster resolveHairRaster(HairRaster setting)
{
    return setting == HairRaster::Auto ? HairRaster::Compute : setting;
}

struct RenderSettings {
    uint32_t width = 1280;
    uint32_t height = 720;
    uint32_t samples = 4;                      // MSAA for meshes: 1, 2, 4 or 8 (clamped to what the device has)
    LightSettings light;                       // the key, shadowed
    LightSettings fill = kDefaultFill;         // unshadowed
    LightSettings rim = kDefaultRim;           // unshadowed
    float ambient = 0.35f;                     // hemisphere ambient scale
    glm::vec3 skyColor{0.55f, 0.62f, 0.75f};   // cool fill from above
    glm::vec3 groundColor{0.22f, 0.2f, 0.18f}; // warm bounce from below
    // The backdrop, a soft vertical gradient (linear RGB): a studio's paper lit brighter at the top.
    glm::vec3 backgroundTop{0.07f, 0.075f, 0.085f};
    glm::vec3 backgroundBottom{0.012f, 0.013f, 0.016f};
    float exposure = 1.0f;
    glm::vec3 headAlbedo{0.62f, 0.6f, 0.57f}; // mannequin grey-beige
    float headRoughness = 0.55f;
    // The scalp under the hair painted a darkened hair colour, this strongly (0: bare skin, 1: fully):
    // production grooms do, so that skin does not show between strands and along partings.
    float scalpPaint = 0.9f;
    HairRaster hairRaster = HairRaster::Auto;
    uint32_t fragmentBudgetMiB = 0; // fragment_budget: the compute path's fragment buffer at most; past it a
                                    // frame is drawn in pieces (0: automatic, 1/8 of the device's memory
                                    // within one buffer's range)
    StrandSettings strands;
    ShadowSettings shadows;
    TransparencySettings transparency;
    HairLook hair;
};

} // namespace wisp
