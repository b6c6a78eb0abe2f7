// renderer/compute/mesh_raster.h: the meshes (head, collision sphere, light marker) drawn in compute, for
// frames whose hair is drawn in compute (hair_raster=compute): on a GPU that runs its graphics
// stages on a few units (the H100), the meshes' 4x MSAA depth, shading and the hair's composite
// cost more than all the hair's kernels together. Same sample positions, same shading
// (shared/mesh_raster.h's meshSurfaceColor, which mesh.frag calls too), same shadows as the
// graphics meshes (MeshPass). Its passes, each a stage written once as the list of what it touches
// (gpu/compute_stage.h, stage() below):
//   meshes.clear    transfer: every sample's depth to 1, its triangle to none
//   meshes.raster   each sample's nearest depth (mesh_raster.comp, kPhase 0)
//   meshes.ids      the triangle holding it (kPhase 1)
//     (these three only when the samples would change: the camera, a mesh or the target moved,
//     MeshVisibilityKey; a still camera keeps the samples an earlier frame drew)
//   meshes.shade    the resolved colour of the meshes per pixel (mesh_shade.comp)
//     (then the strands, which read the samples' depth buffer)
//   hair.composite  the hair over the meshes, sRGB-encoded (hair_compose.comp)
//   frame.copy      into the target's result, which readback and the window read
// Its C++ twin is renderer/compute/mesh_raster_reference.h (tests/test_strand_raster.cpp compares them).
#pragma once

#include "gpu/compute_stage.h"
#include "gpu/handle.h"
#include "gpu/pass.h"
#include "gpu/resources.h"
#include "shaders/shared/mesh_raster.h"

#include <glm/glm.hpp>

#include <cstring>
#include <memory>
#include <vector>

namespace wisp {

namespace vk {
class Context;
}
class RenderTarget;
class FrameUniforms;
class LightMaps;
class MeshPass;

// What the meshes' samples (each one's depth and triangle) depend on. While it stays the same, the
// samples an earlier frame drew still hold: the meshes are rigid, so a frame whose camera, head,
// sphere and light marker have not moved has nothing new to rasterize (its shading, which the
// hair's shadows change, is done every frame).
struct MeshVisibilityKey {
    glm::mat4 viewProjection{1.0f};
    glm::mat4 headTransform{1.0f};
    glm::vec4 sphere{0.0f};
    glm::vec4 marker{0.0f};
    uint64_t meshVersion = 0; // MeshPass::meshVersion
    uint32_t width = 0;
    uint32_t height = 0;
    uint32_t samples = 0;
    uint32_t pad = 0;
};

class MeshRaster {
public:
    enum class Stage { Clear, Raster, Ids, Shade, Compose, Copy };
    static constexpr Stage kMeshStages[] = {Stage::Clear, Stage::Raster, Stage::Ids, Stage::Shade};
    static constexpr Stage kFinalStages[] = {Stage::Compose, Stage::Copy};

    // The device memory it allocates for a target of `extent` and `samples`: the samples' depth
    // and triangle, the meshes' colour (RGBA16F) and the frame (RGBA8).
    static constexpr uint64_t deviceBytes(VkExtent2D extent, uint32_t samples)
    {
        uint64_t pixels = uint64_t(extent.width) * extent.height;
        return pixels * (uint64_t(samples > 1 ? samples : 1) * 8 + 8 + 4);
    }

    // Draws what `meshes` holds (its buffers, surfaces, sphere and marker) as the target's
    // samples; the light's maps are read for the shadows.
    MeshRaster(const vk::Context& ctx, RenderTarget& target, FrameUniforms& uniforms, LightMaps& maps,
               MeshPass& meshes);
    ~MeshRaster();
    // Recreates what depends on the target's size; the device must be idle.
    void resize();
    // The hair to lay over the meshes this frame (premultiplied RGBA16F), or none.
    void setHair(TrackedImage* track, const vk::Image* image)
    {
        hairTrack_ = track;
        hairImage_ = image;
    }

    Pass* pass(Stage stage) { return passes_[size_t(stage)].get(); }
    // This frame's camera and head (before its passes are listed): whether the samples must be
    // drawn again (meshes.clear, meshes.raster and meshes.ids), or those of an earlier frame hold.
    void setVisibility(const glm::mat4& viewProjection, const glm::mat4& headTransform);
    bool visibilityStale() const { return drawnKey_.width == 0 || std::memcmp(&key_, &drawnKey_, sizeof(key_)) != 0; }
    // The samples' depth (float bits, pixel * samples + s), which the compute strands test against.
    TrackedBuffer& depthSamples() { return depthTrack_; }
    const vk::Buffer& depthBuffer() const { return depth_; }
    TrackedBuffer& idSamples() { return idTrack_; } // (pixel * samples + s): packMeshId, kNoMesh where none
    const vk::Buffer& idBuffer() const { return ids_; }
    TrackedImage& color() { return colorTrack_; } // the meshes, resolved (RGBA16F, tone-mapped linear)
    const vk::Image& colorImage() const { return color_; }
    std::vector<TrackedImage*> transientImages() { return {&colorTrack_, &frameTrack_}; }
    // The bytes of the buffers and images it holds (what deviceBytes estimates).
    uint64_t allocatedBytes() const;
    // The push constants this frame's kernels get (object and triangles per draw).
    gpu::MeshRasterPush push() const;

    // Each stage as the one list of what it touches (binding, resource, access) and its commands:
    // its pass declares and records from it, and the layout holds every binding the stages list.
    ComputeStage stage(Stage stage);
    const StageLayout& layout() const { return layout_; }

private:
    // meshes.raster or meshes.ids: a dispatch per mesh shown, its buffers bound in turn.
    void rasterize(StageCommands& commands, const vk::ComputeKernel& kernel);

    const vk::Context& ctx_;
    RenderTarget& target_;
    FrameUniforms& uniforms_;
    LightMaps& maps_;
    MeshPass& meshes_;
    StageLayout layout_;
    vk::ComputeKernel depthKernel_, idKernel_, shadeKernel_, composeKernel_;
    vk::Buffer depth_, ids_;
    TrackedBuffer depthTrack_, idTrack_;
    vk::Image color_, frame_;
    TrackedImage colorTrack_, frameTrack_;
    TrackedImage* hairTrack_ = nullptr;
    const vk::Image* hairImage_ = nullptr;
    std::vector<std::unique_ptr<ComputeStagePass>> passes_;
    MeshVisibilityKey key_{}, drawnKey_{}; // this frame's; the samples' (none drawn: width 0)
};

} // namespace wisp
