// renderer/mesh_pass.h: draws opaque triangle meshes (the head, later the collision sphere) into
// the render target with the plain surface shading of shaders/shared/lighting.h, shadowed by
// the light's maps; and the same meshes' depth from the light for the shadow pass.
#pragma once

#include "physics/mesh.h"
#include "renderer/pass.h"
#include "renderer/vk/handle.h"
#include "renderer/vk/resources.h"

#include <glm/glm.hpp>

namespace wisp {

namespace vk {
class Context;
}
class RenderTarget;
class FrameUniforms;
class LightMaps;

class MeshPass : public Pass {
public:
    MeshPass(const vk::Context& ctx, RenderTarget& target, FrameUniforms& uniforms);
    const char* name() const override { return "meshes"; }
    void declare(PassIo& io) override;
    void record(VkCommandBuffer cmd, FrameContext& frame) override;

    // The light's maps the shading reads (shadows); must be set before the first frame.
    void setLightMaps(LightMaps* maps) { lightMaps_ = maps; }
    // Draws the meshes' depth from the light into the rendering the caller has begun.
    void recordFromLight(VkCommandBuffer cmd, FrameContext& frame);

    void setMesh(const Mesh& mesh);  // uploads; call while the device is idle (load time)
    void setSurface(const glm::mat4& model, const glm::vec3& albedo, float roughness);
    void setClearColor(const glm::vec3& color) { clearColor_ = color; }

private:
    const vk::Context& ctx_;
    RenderTarget& target_;
    FrameUniforms& uniforms_;
    vk::DescriptorSetLayout setLayout_;
    vk::PipelineLayout layout_;
    vk::Pipeline pipeline_;
    vk::Pipeline lightPipeline_;  // depth only, from the light
    LightMaps* lightMaps_ = nullptr;
    vk::Buffer vertices_;
    vk::Buffer indices_;
    uint32_t indexCount_ = 0;
    glm::mat4 model_{1.0f};
    glm::vec3 albedo_{0.6f};
    float roughness_ = 0.5f;
    glm::vec3 clearColor_{0.0f};
    void drawMesh(VkCommandBuffer cmd);
};

}  // namespace wisp
