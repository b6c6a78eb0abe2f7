// renderer/mesh_pass.h: draws opaque triangle meshes (the head, later the collision sphere) into
// the render target with the plain surface shading of shaders/shared/lighting.h.
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

class MeshPass : public Pass {
public:
    MeshPass(const vk::Context& ctx, RenderTarget& target, FrameUniforms& uniforms);
    const char* name() const override { return "meshes"; }
    void declare(PassIo& io) override;
    void record(VkCommandBuffer cmd, FrameContext& frame) override;

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
    vk::Buffer vertices_;
    vk::Buffer indices_;
    uint32_t indexCount_ = 0;
    glm::mat4 model_{1.0f};
    glm::vec3 albedo_{0.6f};
    float roughness_ = 0.5f;
    glm::vec3 clearColor_{0.0f};
};

}  // namespace wisp
