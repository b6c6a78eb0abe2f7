// renderer/mesh_pass.h: draws opaque triangle meshes (the head, the collision sphere, the light's
// marker) into the render target with the plain surface shading of shaders/shared/lighting.h,
// shadowed by the light's maps, the head's scalp painted under the hair; and the same meshes'
// depth from the light for the shadow pass. Three passes of the frame:
//   meshes.depth   the meshes' depth alone (no fragment shader)
//   meshes.shadow  compute: each pixel's light visibility at that depth, the shadow mask
//                  (mesh_shadow.comp: the PCF and deep opacity taps run on every unit of the GPU)
//   meshes         the shading, one shadow-mask texel per fragment, depth tested against the first
#pragma once

#include "assets/mesh.h"
#include "gpu/compute_stage.h"
#include "gpu/handle.h"
#include "gpu/pass.h"
#include "gpu/resources.h"
#include "physics/strand_set.h"

#include <glm/glm.hpp>

#include <memory>
#include <vector>

namespace wisp {

namespace vk {
class Context;
}
class RenderTarget;
class FrameUniforms;
class LightMaps;

// The scalp under a groom, per vertex of the head (0..1): grown hair's own field
// (StrandSet::scalpPaint, physics/scalp.h); for loaded hair 1 within the roots' typical spacing of a
// root, fading to 0 at two and a half times it (the hairline), so the painted scalp covers where
// hair grows and a little past it. Head space, as the strands' rest pose.
std::vector<float> scalpCoverage(const Mesh& head, const StrandSet& strands);
// The scalp is painted the hair's colour times this (RenderSettings::scalpPaint says how strongly).
inline constexpr float kScalpDarkening = 0.45f;

class MeshPass : public Pass {
public:
    // `maps`: the light's maps the shading reads (shadows).
    MeshPass(const vk::Context& ctx, RenderTarget& target, FrameUniforms& uniforms, LightMaps& maps);
    ~MeshPass() override;
    const char* name() const override { return "meshes"; }
    void declare(PassIo& io) override;
    void record(VkCommandBuffer cmd, FrameContext& frame) override;

    // Draws the meshes' depth from the light into the rendering the caller has begun.
    void recordFromLight(VkCommandBuffer cmd, FrameContext& frame);

    // The head; uploads, call while the device is idle (load time). `scalp`: per vertex, 0..1, how
    // much hair grows there (painted with setScalp's colour); empty: none.
    void setMesh(const Mesh& mesh, const std::vector<float>& scalp = {});
    // The colour the scalp under the hair is painted and how strongly (0: not at all).
    void setScalp(const glm::vec3& albedo, float strength)
    {
        scalpAlbedo_ = albedo;
        scalpStrength_ = strength;
    }
    void setSurface(const glm::vec3& albedo, float roughness);
    // Where the head is this frame (rigid; its surface's model matrix applies first).
    void setHeadTransform(const glm::mat4& transform) { headTransform_ = transform; }
    // The user's collision sphere (xyz centre, w radius; 0 hides it): drawn, and casts shadows.
    void setSphere(const glm::vec4& sphere) { sphere_ = sphere; }
    const glm::vec4& sphere() const { return sphere_; }
    // A small bright ball where the light comes from (radius 0 hides it); casts no shadow.
    void setLightMarker(const glm::vec3& position, float radius) { marker_ = glm::vec4(position, radius); }
    // The camera's clip -> world this frame (the shadow mask places each pixel's depth with it).
    void setInverseViewProjection(const glm::mat4& m) { inverseViewProjection_ = m; }
    // The passes that run before this one: the depth, then the shadow mask.
    Pass* depthPass() { return depthPass_.get(); }
    Pass* shadowMaskPass() { return shadowMaskPass_.get(); }
    TrackedImage& shadowMask() { return shadowMaskTrack_; } // rewritten every frame
    // Recreates the shadow mask at the target's size; the device must be idle.
    void resize();

    // What the compute meshes (renderer/compute/mesh_raster.h) draw: each object's vertices (7 floats:
    // position, normal, scalp weight) and triangles (3 indices), and the surfaces.
    struct Buffers {
        VkBuffer vertices = VK_NULL_HANDLE;
        VkBuffer indices = VK_NULL_HANDLE;
        uint32_t triangles = 0;
    };
    Buffers headBuffers() const { return {head_.vertices, head_.indices, head_.indexCount / 3}; }
    Buffers sphereBuffers() const { return {sphereMesh_.vertices, sphereMesh_.indices, sphereMesh_.indexCount / 3}; }
    // How many times setMesh has uploaded a head: what was drawn of an earlier one no longer holds.
    uint64_t meshVersion() const { return meshVersion_; }
    const glm::vec4& marker() const { return marker_; }
    const glm::vec3& albedo() const { return albedo_; }
    float roughness() const { return roughness_; }
    const glm::vec3& scalpAlbedo() const { return scalpAlbedo_; }
    float scalpStrength() const { return scalpStrength_; }

    void declareDepth(PassIo& io);
    void recordDepth(VkCommandBuffer cmd, FrameContext& frame);
    // The shadow mask's compute stage (gpu/compute_stage.h): the frame's parameters, the light's
    // maps and the meshes' depth read, the mask written, and its dispatch; its pass declares and
    // records from it.
    ComputeStage shadowMaskStage();
    const StageLayout& shadowMaskLayout() const { return shadowLayout_; }

private:
    const vk::Context& ctx_;
    RenderTarget& target_;
    FrameUniforms& uniforms_;
    vk::DescriptorSetLayout setLayout_;
    vk::PipelineLayout layout_;
    vk::Pipeline pipeline_;
    vk::Pipeline backgroundPipeline_; // the backdrop's gradient behind the meshes (background.frag)
    vk::Pipeline lightPipeline_;      // depth only, from the light
    vk::Pipeline depthPipeline_;      // depth only, from the camera
    LightMaps& maps_;
    StageLayout shadowLayout_;
    vk::ComputeKernel shadowKernel_; // mesh_shadow.comp
    vk::Sampler nearest_;
    vk::Image shadowMask_;
    TrackedImage shadowMaskTrack_;
    std::unique_ptr<Pass> depthPass_, shadowMaskPass_;
    glm::mat4 inverseViewProjection_{1.0f};
    struct GpuMesh {
        vk::Buffer vertices;
        vk::Buffer indices;
        uint32_t indexCount = 0;
    };
    GpuMesh upload(const Mesh& mesh, const char* name, const std::vector<float>& scalp) const;
    GpuMesh head_;
    GpuMesh sphereMesh_; // a unit sphere, scaled and placed for the sphere and the marker
    glm::mat4 headTransform_{1.0f};
    glm::vec4 sphere_{0.0f};
    glm::vec4 marker_{0.0f};
    uint64_t meshVersion_ = 0;
    glm::vec3 albedo_{0.6f};
    float roughness_ = 0.5f;
    glm::vec3 scalpAlbedo_{0.0f};
    float scalpStrength_ = 0.0f;
    void draw(VkCommandBuffer cmd, const GpuMesh& mesh, const glm::mat4& model, const glm::vec3& albedo,
              float roughness);
};

} // namespace wisp
