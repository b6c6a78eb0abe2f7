// renderer/renderer.cpp: settings packing and the pass list.
#include "renderer/renderer.h"

#include "renderer/frame.h"
#include "renderer/vk/context.h"

#include <algorithm>
#include <cmath>

namespace wisp {

static_assert(sizeof(gpu::FrameParams) == 3 * 64 + 6 * 16 + 64, "FrameParams must match its std140 layout");
static_assert(offsetof(gpu::FrameParams, headTransform) == 288);
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
    p.headTransform = glm::mat4(1.0f);  // the head does not move in the renderer yet
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
    lodReferenceDistance_ = OrbitCamera::framing(bounds_, float(settings_.width) / float(settings_.height)).distance;
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
    if (!hairPass_)
        return;
    const StrandSettings& s = settings_.strands;
    HairDrawCounts counts = hairCounts();
    hairPass_->setCounts(counts);
    // LOD (TressFX): beyond the default framing distance the strand count falls with the square of
    // the distance (the screen area the head covers), continuously, and the width grows to keep
    // the coverage; never below lodMinFraction of the strands.
    float fraction = 1.0f;
    if (s.lod) {
        float ratio = lodReferenceDistance_ / std::max(camera.distance, 1e-6f);
        fraction = std::clamp(ratio * ratio, s.lodMinFraction, 1.0f);
    }
    gpu::HairPush push{};
    push.guideCount = counts.guides;
    push.verticesPerStrand = verticesPerStrand_;
    push.strandsPerGuide = counts.strandsPerGuide;
    push.divisions = counts.divisions;
    push.lengthChunks = counts.lengthChunks;
    push.strandsPerPatch = counts.strandsPerPatch;
    push.interpolation = s.interpolation == Interpolation::Single  ? gpu::kInterpolationSingle
                         : s.interpolation == Interpolation::Multi ? gpu::kInterpolationMulti
                                                                   : gpu::kInterpolationMixed;
    push.clumpRadius = s.clumpRadiusMetres * unitsPerMetre_;
    push.deviation = s.deviationMetres * unitsPerMetre_;
    push.width = s.widthMetres * unitsPerMetre_;
    push.lodStrands = std::max(1.0f, float(counts.strandsPerGuide) * fraction);
    push.lodWidthScale = std::sqrt(float(counts.strandsPerGuide) / push.lodStrands);
    push.minPixelWidth = s.minPixelWidth;
    push.rootColor = s.rootColor;
    push.specularShift = s.specularShift;
    push.tipColor = s.tipColor;
    hairPass_->setPush(push);
}

void Renderer::attachHair(GpuSolver& solver, const StrandSet& strands, float unitsPerMetre)
{
    physicsPass_ = std::make_unique<PhysicsPass>(solver);
    guidePass_ = std::make_unique<GuidePass>(ctx_, *target_, uniforms_, solver, uint32_t(strands.strandCount()),
                                             strands.verticesPerStrand);
    hairPass_ = std::make_unique<HairPass>(ctx_, *target_, uniforms_, solver, strands);
    guideCount_ = uint32_t(strands.strandCount());
    verticesPerStrand_ = strands.verticesPerStrand;
    unitsPerMetre_ = unitsPerMetre;
}

HairDrawCounts Renderer::hairCounts() const
{
    return hairDrawCounts(guideCount_, settings_.strands);
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
    if (hairPass_)
        list.push_back(hairPass_.get());
    if (guidePass_ && settings_.strands.showGuides)
        list.push_back(guidePass_.get());
    return list;
}

}  // namespace wisp
