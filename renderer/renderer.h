// renderer/renderer.h: the scene renderer shared by the window and the headless front ends. It
// owns the render target, the per-frame uniforms and the passes, in the order they run:
//   physics (when hair is attached) | shadow (head and hair depth from the light) | opacity (deep
//   opacity layers) | [oit.clear] | meshes (head) | hair (tessellated strands) | [oit.resolve
//   (compute) | oit.composite | oit.stats] | guides (lines, optional)
// The bracketed passes run in OIT mode (transparency=oit); in MSAA mode the hair writes coverage.
// With hair_raster=compute the strands' and meshes' compute passes replace the shadow's hair,
// the opacity, the meshes and the hair (renderer.cpp's passes()). Each path's objects are made the
// first time a frame draws with it; this header names the graphics path's classes only.
// A front end begins a Frame, calls prepare(), runs passes() plus its own tail (readback or
// present), and submits.
#pragma once

#include "assets/head.h"
#include "renderer/camera.h"
#include "renderer/composite_pass.h"
#include "renderer/compute/mesh_raster.h"
#include "renderer/compute/strand_raster.h"
#include "renderer/frame_uniforms.h"
#include "renderer/guide_pass.h"
#include "renderer/hair_lut_image.h"
#include "renderer/light_maps.h"
#include "renderer/mesh_pass.h"
#include "renderer/oit_stats.h"
#include "renderer/physics_pass.h"
#include "renderer/render_target.h"
#include "renderer/settings.h"
#include "renderer/strand_draw.h"
#include "shading/hair_bsdf.h"

#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace wisp {

namespace vk {
class Context;
}
struct FrameContext;
// The graphics path (renderer/graphics/): only renderer.cpp, which makes the pass list, knows it.
class HairPass;
class Oit;
class OitClearPass;
class OitResolvePass;
class OitStatsPass;

// What the light's view is fitted to: the scene's bounds (head and hair at rest, with room for
// the hair to move) and the scene's units.
struct LightFit {
    Bounds scene;
    float unitsPerMetre = 1.0f;
};

// Turns the human-facing settings and the camera into the GPU's per-frame block, all but the hair
// material (`hair`: the Renderer packs it when the look changes, not every frame).
gpu::FrameParams pack(const RenderSettings& settings, const OrbitCamera& camera, VkExtent2D extent, float timeSeconds,
                      const LightFit& light);

class Renderer {
public:
    Renderer(const vk::Context& ctx, const RenderSettings& settings, uint32_t framesInFlight);
    ~Renderer();
    Renderer(const Renderer&) = delete;
    Renderer& operator=(const Renderer&) = delete;

    // Uploads the head mesh; call while the device is idle.
    void setHead(const Head& head);
    // Simulates `strands` with `solver` (which must outlive the renderer) and draws them as hair;
    // unitsPerMetre converts the strand settings' metres into the head's units.
    void attachHair(GpuSolver& solver, const StrandSet& strands, float unitsPerMetre);
    // The strands the current settings draw (for the CLI and UI to report), and how the path that
    // draws them splits them ("drawn in compute ..." or the tessellation's patches and draws).
    StrandCounts hairCounts() const;
    std::string describeHairDraw() const;
    // Where the head is (rigid; the hair's colliders follow it), the user's sphere (xyz, radius; 0:
    // none) to draw, and whether to draw a marker where the light comes from (the window does).
    void setHeadTransform(const glm::mat4& transform);
    void setSphere(const glm::vec4& sphere) { meshPass_->setSphere(sphere); }
    void showLightMarker(bool show) { showLightMarker_ = show; }
    // The simulation steps to record in the next frame (none: the hair holds still).
    void setSteps(std::vector<gpu::SimStep> steps);
    // The steps of the frame after the next one, known now (a fixed clock), or the next frame's own
    // where its picture may show the hair a frame late (the window): recorded after the next
    // frame's guide curves, which are the last to read the solver's buffers, each kernel in front
    // of one of the compute path's passes, so that the physics runs beside the drawing instead of
    // before it; the frame after then takes no steps of its own (setSteps({})). With the graphics
    // path, or the guides drawn, they run at the frame's end. Recorded once (a frame drawn again
    // does not run them again).
    void setStepsAhead(std::vector<gpu::SimStep> steps) { stepsAhead_ = std::move(steps); }
    PhysicsPass* physics() { return physicsPass_.get(); }
    // The tessellation's pass: made the first time a frame draws with the graphics path (null
    // until then: no tessellation pipeline is built while compute draws).
    HairPass* hair() { return hairPass_.get(); }
    // Recreates the size-dependent images; call while the device is idle.
    void resize(VkExtent2D extent);

    // Writes this frame's uniforms and resets per-frame target state.
    void prepare(FrameContext& frame, const OrbitCamera& camera, float timeSeconds);
    std::vector<Pass*> passes();
    std::vector<TrackedImage*> transientImages();
    // Fragments the OIT lists held and dropped in the last completed frame of `slot` (zeros in MSAA
    // mode or when the hair is drawn in compute).
    OitStats oitStats(uint32_t slot) const;
    // After a frame that overflowed the automatic OIT pool: grows it (the device must be idle), so
    // the next frame drops nothing; false when it cannot (the user's pool, or the device's limit).
    bool growOit(const OitStats& overflowed);
    // The compute path's counts of the last completed frame of `slot` (zeros when it is not used).
    RasterStats rasterStats(uint32_t slot) const;
    // How the hair is drawn now (hair_raster, auto resolved for the device).
    HairRaster hairRaster() const;
    // Whether the meshes are drawn in compute too (MeshRaster): with the compute hair, unless the
    // guides are shown (their lines are drawn into the graphics meshes' target).
    bool computeMeshes() const;

    RenderTarget& target() { return *target_; }
    MeshPass& meshes() { return *meshPass_; }
    OitResolvePass* oitResolve() { return oitResolve_.get(); } // (made with the graphics path's OIT)
    StrandRaster* strandRaster() { return strandRaster_.get(); }
    MeshRaster* meshRaster() { return meshRaster_.get(); }
    // The per-frame block prepare() last wrote (the tests' CPU twins take it as their input).
    const gpu::FrameParams& frameParams() const { return frameParams_; }
    LightMaps& lightMaps() { return *lightMaps_; }
    RenderSettings& settings() { return settings_; }
    const Bounds& sceneBounds() const { return bounds_; }

private:
    const vk::Context& ctx_;
    RenderSettings settings_;
    FrameUniforms uniforms_;
    std::unique_ptr<RenderTarget> target_;
    std::unique_ptr<MeshPass> meshPass_;
    std::unique_ptr<PhysicsPass> physicsPass_;
    std::vector<gpu::SimStep> stepsAhead_;
    std::vector<std::unique_ptr<PhysicsKernelPass>> aheadPasses_; // the last frame's steps ahead
    std::unique_ptr<GuidePass> guidePass_;
    std::unique_ptr<HairPass> hairPass_;
    std::unique_ptr<HairLutImage> hairLut_; // the lookup mode's tables, sampled by both paths
    uint32_t framesInFlight_ = 1;
    std::unique_ptr<LightMaps> lightMaps_;
    std::unique_ptr<ShadowPass> shadowPass_;
    std::unique_ptr<OpacityPass> opacityPass_;
    std::unique_ptr<Oit> oit_;
    std::unique_ptr<OitClearPass> oitClear_;
    std::unique_ptr<OitResolvePass> oitResolve_;
    std::unique_ptr<CompositePass> oitComposite_;
    std::unique_ptr<OitStatsPass> oitStats_;
    // The compute path (made the first time a frame draws with it) and what it adds to the frame.
    std::unique_ptr<StrandRaster> strandRaster_;
    std::unique_ptr<ShadowPass> headShadowPass_; // the head's depth alone: the hair's maps come from compute
    std::unique_ptr<CompositePass> strandComposite_;
    std::unique_ptr<MeshRaster> meshRaster_; // made the first time a frame draws its meshes in compute
    GpuSolver* solver_ = nullptr;
    std::vector<glm::uvec4> guideTriangles_;
    void makeStrandRaster();
    void placeStepsAhead(std::vector<Pass*>& list);
    void makeOit();
    void makeHairPass();
    uint32_t guideCount_ = 0;
    uint32_t verticesPerStrand_ = 0;
    float unitsPerMetre_ = 1.0f;
    float lodReferenceDistance_ = 1.0f; // the default framing's distance: full detail at or nearer
    Bounds bounds_;
    Mesh headMesh_; // kept to paint its scalp once the hair is known
    LightFit lightFit_;
    glm::vec4 hairVolume_{0.0f}; // the hair's rest bounds as a sphere in head space (radius 0: no hair)
    glm::mat4 headTransform_{1.0f};
    bool showLightMarker_ = false;
    shading::HairParams lutParams_;                     // what the lookup tables were built for
    std::optional<shading::HairParams> materialParams_; // what `material_` was packed from
    gpu::HairMaterial material_{};
    gpu::FrameParams frameParams_{};
};

} // namespace wisp
