// renderer/renderer.cpp: settings packing and the pass list.
#include "renderer/renderer.h"

#include "renderer/frame.h"
#include "renderer/vk/context.h"

#include <cmath>

namespace wisp {

static_assert(sizeof(gpu::FrameParams) == 3 * 64 + 6 * 16, "FrameParams must match its std140 layout");
static_assert(offsetof(gpu::FrameParams, cameraPosition) == 192);
static_assert(offsetof(gpu::FrameParams, lightDirection) == 208);
static_assert(offsetof(gpu::FrameParams, viewportHeight) == 284);

glm::vec3 LightSettings::direction() const
{
    float az = glm::radians(azimuthDeg);
    float el = glm::radians(elevationDeg);
    return glm::normalize(glm::vec3(std::sin(az) * std::cos(el), std::sin(el), std::cos(az) * std::cos(el)));
}

gpu::FrameParams pack(const RenderSettings& s, const OrbitCamera& camera, VkExtent2D extent, float timeSeconds)
{
    float aspect = static_cast<float>(extent.width) / static_cast<float>(extent.height);
    gpu::FrameParams p{};
    p.view = camera.view();
    p.projection = camera.projection(aspect);
    p.viewProjection = p.projection * p.view;
    p.cameraPosition = camera.position();
    p.time = timeSeconds;
    p.lightDirection = s.light.direction();
    p.lightIntensity = s.light.intensity;
    p.lightColor = s.light.color;
    p.ambientIntensity = s.ambient;
    p.skyColor = s.skyColor;
    p.exposure = s.exposure;
    p.groundColor = s.groundColor;
    p.viewportWidth = static_cast<float>(extent.width);
    p.backgroundColor = s.background;
    p.viewportHeight = static_cast<float>(extent.height);
    return p;
}

Renderer::Renderer(const vk::Context& ctx, const RenderSettings& settings, uint32_t framesInFlight)
    : ctx_(ctx), settings_(settings), uniforms_(ctx, framesInFlight)
{
    target_ = std::make_unique<RenderTarget>(ctx, VkExtent2D{settings.width, settings.height}, settings.samples);
    meshPass_ = std::make_unique<MeshPass>(ctx_, *target_, uniforms_);
    meshPass_->setClearColor(settings_.background);
    meshPass_->setSurface(glm::mat4(1.0f), settings_.headAlbedo, settings_.headRoughness);
}

void Renderer::setHead(const Head& head)
{
    bounds_ = head.mesh.bounds();
    meshPass_->setMesh(head.mesh);
}

void Renderer::resize(VkExtent2D extent)
{
    settings_.width = extent.width;
    settings_.height = extent.height;
    target_->resize(extent);
}

void Renderer::prepare(FrameContext& frame, const OrbitCamera& camera, float timeSeconds)
{
    target_->beginFrame();
    uniforms_.write(frame.slot, pack(settings_, camera, target_->extent(), timeSeconds));
}

void Renderer::attachHair(GpuSolver& solver, const StrandSet& strands)
{
    physicsPass_ = std::make_unique<PhysicsPass>(solver);
    guidePass_ = std::make_unique<GuidePass>(ctx_, *target_, uniforms_, solver, uint32_t(strands.strandCount()),
                                             strands.verticesPerStrand);
}

void Renderer::setSteps(std::vector<gpu::SimStep> steps)
{
    if (physicsPass_)
        physicsPass_->setSteps(std::move(steps));
}

std::vector<Pass*> Renderer::passes()
{
    std::vector<Pass*> list;
    if (physicsPass_)
        list.push_back(physicsPass_.get());
    list.push_back(meshPass_.get());
    if (guidePass_)
        list.push_back(guidePass_.get());
    return list;
}

}  // namespace wisp
