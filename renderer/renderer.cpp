// renderer/renderer.cpp: settings packing and the pass list: the one file outside renderer/graphics/
// that knows the graphics path's classes (tests/test_layers.cpp checks the includes).
#include "renderer/renderer.h"

#include "gpu/context.h"
#include "gpu/frame.h"
#include "renderer/graphics/hair_pass.h"
#include "renderer/graphics/oit.h"
#include "shading/hair_look.h"
#include "shading/hair_models.h"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>

namespace wisp {

glm::vec3 LightSettings::direction() const
{
    float az = glm::radians(azimuthDeg);
    float el = glm::radians(elevationDeg);
    return glm::normalize(glm::vec3(std::sin(az) * std::cos(el), std::sin(el), std::cos(az) * std::cos(el)));
}

gpu::FrameParams pack(const RenderSettings& s, const OrbitCamera& camera, VkExtent2D extent, float timeSeconds,
                      const LightFit& light)
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
    p.backgroundTop = s.backgroundTop;
    p.backgroundBottom = s.backgroundBottom;
    p.viewportHeight = static_cast<float>(extent.height);
    p.headTransform = glm::mat4(1.0f); // the Renderer sets the head's pose (setHeadTransform) after packing
    const LightSettings* unshadowed[] = {&s.fill, &s.rim}; // frameLight 1 and 2
    static_assert(std::size(unshadowed) == gpu::kFrameLights - 1);
    for (size_t i = 0; i < std::size(unshadowed); ++i)
        p.unshadowed[i] = {.direction = unshadowed[i]->direction(),
                           .intensity = unshadowed[i]->intensity,
                           .color = unshadowed[i]->color,
                           .pad = 0.0f};

    // The light's view: orthographic along its direction, around the sphere holding the scene.
    glm::vec3 centre = light.scene.center();
    float radius = std::max(0.5f * light.scene.diagonal(), 1e-6f);
    glm::vec3 toLight = p.lightDirection;
    glm::vec3 up = std::abs(toLight.y) > 0.99f ? glm::vec3(0.0f, 0.0f, 1.0f) : glm::vec3(0.0f, 1.0f, 0.0f);
    glm::mat4 lightView = glm::lookAt(centre + 2.0f * radius * toLight, centre, up);
    glm::mat4 lightProjection = glm::orthoRH_ZO(-radius, radius, -radius, radius, radius, 3.0f * radius);
    const ShadowSettings& sh = s.shadows;
    p.lightViewProjection = lightProjection * lightView;
    p.shadowMapSize = float(sh.mapSize);
    p.lightTexelsPerUnit = float(sh.mapSize) / (2.0f * radius);
    p.lightDepthRange = 2.0f * radius;
    p.pcfSamples = sh.pcfSamples;
    p.pcfRadius = sh.pcfRadiusTexels;
    // About a texel and a half of depth: enough for surfaces at a slant to the light not to
    // shadow themselves, little enough that contact shadows stay attached.
    p.shadowBias = 1.5f / p.lightTexelsPerUnit / p.lightDepthRange;
    p.domLayers = sh.domLayers;
    p.domSpacing = sh.domSpacingMetres * light.unitsPerMetre / p.lightDepthRange;
    p.domKappa = sh.domKappa;
    p.hairOpacity = s.transparency.hairOpacity;
    p.strandLengthJitter = s.strands.lengthJitter;
    p.shadowsEnabled = sh.enabled ? 1u : 0u;

    const HairLook& look = s.hair;
    p.shadingModel = look.model == ShadingModel::Karis    ? gpu::kShadingKaris
                     : look.model == ShadingModel::Kajiya ? gpu::kShadingKajiya
                                                          : gpu::kShadingLut;
    p.hairVariation = look.variation;
    p.hairStreaks = look.streaks;
    p.hairAlong = glm::vec4(look.along, 0.0f, 0.0f, 0.0f);
    p.hairAmbientOcclusion = 0.6f;
    p.multipleScattering = look.multipleScattering ? 1u : 0u;
    return p;
}

Renderer::Renderer(const vk::Context& ctx, const RenderSettings& settings, uint32_t framesInFlight)
    : ctx_(ctx), settings_(settings), uniforms_(ctx, framesInFlight), framesInFlight_(framesInFlight)
{
    target_ = std::make_unique<RenderTarget>(ctx, VkExtent2D{settings.width, settings.height}, settings.samples);
    lightMaps_ = std::make_unique<LightMaps>(ctx, settings.shadows.mapSize);
    meshPass_ = std::make_unique<MeshPass>(ctx_, *target_, uniforms_, *lightMaps_);
    shadowPass_ = std::make_unique<ShadowPass>(*lightMaps_, *meshPass_);
    opacityPass_ = std::make_unique<OpacityPass>(*lightMaps_);
    meshPass_->setSurface(settings_.headAlbedo, settings_.headRoughness);
}

Renderer::~Renderer() = default;

void Renderer::setHead(const Head& head)
{
    headMesh_ = head.mesh;
    bounds_ = head.mesh.bounds();
    lightFit_.scene = bounds_;
    lodReferenceDistance_ = OrbitCamera::framing(bounds_, float(settings_.width) / float(settings_.height)).distance;
    meshPass_->setMesh(head.mesh);
}

void Renderer::resize(VkExtent2D extent)
{
    settings_.width = extent.width;
    settings_.height = extent.height;
    target_->resize(extent);
    meshPass_->resize();
    if (oit_)
        oit_->resize(extent, settings_.transparency.oitNodesPerPixel);
    if (strandRaster_)
        strandRaster_->resize();
    if (meshRaster_)
        meshRaster_->resize();
}

std::vector<TrackedImage*> Renderer::transientImages()
{
    std::vector<TrackedImage*> list = target_->transientImages();
    if (oit_)
        list.push_back(&oit_->color());
    for (TrackedImage* image : lightMaps_->transientImages())
        list.push_back(image);
    if (strandRaster_)
        list.push_back(&strandRaster_->color());
    list.push_back(&meshPass_->shadowMask());
    if (meshRaster_)
        for (TrackedImage* image : meshRaster_->transientImages())
            list.push_back(image);
    return list;
}

OitStats Renderer::oitStats(uint32_t slot) const
{
    return oit_ && hairRaster() == HairRaster::Graphics ? oit_->stats(slot) : OitStats{};
}

bool Renderer::growOit(const OitStats& overflowed)
{
    return oit_ && oit_->grow(overflowed);
}

void Renderer::prepare(FrameContext& frame, const OrbitCamera& camera, float timeSeconds)
{
    target_->beginFrame();
    // The hair material (64 samples across the fibre) and the lookup tables follow the look:
    // packed again, or rebuilt (about 9 ms), only when its parameters change.
    shading::HairParams look = hairParams(settings_.hair);
    if (!materialParams_ || std::memcmp(&look, &*materialParams_, sizeof(look)) != 0) {
        material_ = shading::packHairMaterial(look);
        materialParams_ = look;
    }
    // The scalp under the hair: the hair's own colour (the reference's, from its absorption), darkened.
    if (solver_)
        meshPass_->setScalp(kScalpDarkening * shading::colorFromSigmaA(look.sigmaA, look.betaN), settings_.scalpPaint);
    gpu::FrameParams frameParams = pack(settings_, camera, target_->extent(), timeSeconds, lightFit_);
    frameParams.headTransform = headTransform_;
    frameParams.hairVolume =
        glm::vec4(glm::vec3(headTransform_ * glm::vec4(glm::vec3(hairVolume_), 1.0f)), hairVolume_.w);
    frameParams.hair = material_;
    uniforms_.write(frame.slot, frameParams);
    frameParams_ = frameParams;
    meshPass_->setInverseViewProjection(glm::inverse(frameParams.viewProjection));
    lightMaps_->setHeadKey({.lightViewProjection = frameParams.lightViewProjection,
                            .headTransform = headTransform_,
                            .sphere = meshPass_->sphere(),
                            .enabled = settings_.shadows.enabled ? 1u : 0u,
                            .size = lightMaps_->size()});
    float sceneRadius = 0.5f * lightFit_.scene.diagonal();
    meshPass_->setLightMarker(lightFit_.scene.center() + 0.75f * sceneRadius * settings_.light.direction(),
                              showLightMarker_ ? 0.025f * sceneRadius : 0.0f);
    shadowPass_->setEnabled(settings_.shadows.enabled);
    if (hairLut_ && settings_.hair.model == ShadingModel::Lut && std::memcmp(&look, &lutParams_, sizeof(look)) != 0) {
        hairLut_->upload(shading::buildHairLut(look), &frame);
        lutParams_ = look;
    }
    opacityPass_->setEnabled(settings_.shadows.enabled && settings_.shadows.domLayers > 0);
    if (computeMeshes()) {
        if (!meshRaster_)
            meshRaster_ = std::make_unique<MeshRaster>(ctx_, *target_, uniforms_, *lightMaps_, *meshPass_);
        meshRaster_->setHair(nullptr, nullptr);
        meshRaster_->setVisibility(frameParams.viewProjection, headTransform_);
    }
    if (!solver_)
        return;
    const StrandSettings& s = settings_.strands;
    StrandCounts counts = hairCounts();
    // LOD (TressFX): beyond the default framing distance the strand count falls with the square of
    // the distance (the screen area the head covers), continuously, and the width grows to keep
    // the coverage; never below lodMinFraction of the strands.
    float fraction = 1.0f;
    if (s.lod) {
        float ratio = lodReferenceDistance_ / std::max(camera.distance, 1e-6f);
        fraction = std::clamp(ratio * ratio, s.lodMinFraction, 1.0f);
    }
    StrandDraw draw;
    draw.guides = counts.guides;
    draw.verticesPerStrand = verticesPerStrand_;
    draw.strandsPerGuide = counts.strandsPerGuide;
    draw.divisions = counts.divisions;
    draw.interpolation = s.interpolation == Interpolation::Single  ? gpu::kInterpolationSingle
                         : s.interpolation == Interpolation::Multi ? gpu::kInterpolationMulti
                                                                   : gpu::kInterpolationMixed;
    draw.clumpRadius = s.clumpRadiusMetres * unitsPerMetre_;
    draw.deviation = s.deviationMetres * unitsPerMetre_;
    draw.coilRadius = s.coilRadiusMetres * unitsPerMetre_;
    draw.coilFrequency = s.coilTurnsPerMetre / unitsPerMetre_;
    draw.width = s.widthMetres * unitsPerMetre_;
    draw.lodStrands = std::max(1.0f, float(counts.strandsPerGuide) * fraction);
    draw.lodWidthScale = std::sqrt(float(counts.strandsPerGuide) / draw.lodStrands);
    draw.minPixelWidth = s.minPixelWidth;
    draw.reverseOrder = s.reverseOrder;
    // The light's maps need the hair's depth and opacity, not every strand: LOD's fewer, wider
    // strands (the same coverage) cost a fraction of the work.
    StrandDraw light = draw;
    light.lodStrands = lightLodStrands(draw.lodStrands, settings_.shadows.strandFraction);
    light.lodWidthScale = draw.lodWidthScale * std::sqrt(draw.lodStrands / light.lodStrands);
    if (hairRaster() != HairRaster::Compute) {
        makeHairPass();
        makeOit();
        if (oitResolve_)
            oitResolve_->setK(settings_.transparency.oitK, frame);
        hairPass_->setDraw(draw, light, hairDrawCounts(guideCount_, s));
        lightMaps_->useHairDepthValues(false);
        return;
    }

    // The compute path draws the same strands from the same parameters. Its hair depth from the
    // light is sampled as values where the opacity layers need it; copied into the depth image
    // only for the PCF of the hair's shadow (no opacity layers).
    makeStrandRaster();
    lightMaps_->useHairDepthValues(settings_.shadows.domLayers > 0);
    headShadowPass_->setEnabled(settings_.shadows.enabled);
    strandComposite_->setSource(&strandRaster_->color(), &strandRaster_->colorImage());
    strandRaster_->prepare(frame, draw, light,
                           {.shadows = settings_.shadows.enabled,
                            .oitK = settings_.transparency.oitK,
                            .domLayers = settings_.shadows.domLayers,
                            .lut = &hairLut_->info(),
                            .fragmentBudgetBytes = uint64_t(settings_.fragmentBudgetMiB) << 20});
    if (computeMeshes()) {
        meshRaster_->setHair(&strandRaster_->color(), &strandRaster_->colorImage());
        strandRaster_->setMeshSamples(&meshRaster_->depthSamples());
    } else {
        strandRaster_->setMeshSamples(nullptr);
    }
}

void Renderer::makeOit()
{
    // The linked lists only where the graphics path draws the hair with them: the compute path has
    // buffers of its own, sized for it.
    if (oit_ || settings_.transparency.mode != Transparency::Oit)
        return;
    oit_ = std::make_unique<Oit>(ctx_, target_->extent(), settings_.transparency.oitNodesPerPixel, framesInFlight_,
                                 settings_.transparency.oitAutoNodes);
    oitClear_ = std::make_unique<OitClearPass>(*oit_);
    oitResolve_ = std::make_unique<OitResolvePass>(ctx_, *oit_);
    oitComposite_ = std::make_unique<CompositePass>(ctx_, *target_, "oit.composite");
    oitComposite_->setSource(&oit_->color(), &oit_->colorImage());
    oitStats_ = std::make_unique<OitStatsPass>(*oit_);
    if (hairPass_)
        hairPass_->setOit(oit_.get());
}

void Renderer::makeHairPass()
{
    // The tessellation's pipelines only where the graphics path draws: the compute path's default
    // frame builds none of them.
    if (hairPass_ || !solver_)
        return;
    hairPass_ = std::make_unique<HairPass>(ctx_, *target_, uniforms_, *solver_, guideTriangles_);
    hairPass_->setLightMaps(lightMaps_.get());
    hairPass_->setLut(hairLut_.get());
    if (oit_)
        hairPass_->setOit(oit_.get());
    shadowPass_->setHair(hairPass_.get());
    opacityPass_->setHair(hairPass_.get());
}

void Renderer::makeStrandRaster()
{
    if (strandRaster_)
        return;
    strandRaster_ = std::make_unique<StrandRaster>(ctx_, *target_, uniforms_, *lightMaps_, *solver_, guideTriangles_,
                                                   framesInFlight_);
    headShadowPass_ = std::make_unique<ShadowPass>(*lightMaps_, *meshPass_);
    headShadowPass_->setHairDepth(false);
    strandComposite_ = std::make_unique<CompositePass>(ctx_, *target_, "hair.composite");
}

HairRaster Renderer::hairRaster() const
{
    return resolveHairRaster(settings_.hairRaster);
}

bool Renderer::computeMeshes() const
{
    return hairRaster() == HairRaster::Compute && !settings_.strands.showGuides;
}

RasterStats Renderer::rasterStats(uint32_t slot) const
{
    return strandRaster_ && solver_ && hairRaster() == HairRaster::Compute ? strandRaster_->stats(slot) : RasterStats{};
}

void Renderer::attachHair(GpuSolver& solver, const StrandSet& strands, float unitsPerMetre)
{
    meshPass_->setMesh(headMesh_, scalpCoverage(headMesh_, strands));
    physicsPass_ = std::make_unique<PhysicsPass>(solver);
    guidePass_ = std::make_unique<GuidePass>(ctx_, *target_, uniforms_, solver, uint32_t(strands.strandCount()),
                                             strands.verticesPerStrand);
    lutParams_ = hairParams(settings_.hair);
    hairLut_ = std::make_unique<HairLutImage>(ctx_);
    hairLut_->upload(shading::buildHairLut(lutParams_), nullptr);
    // The light's view holds the head and the hair at rest, with room for the hair to swing.
    glm::vec3 lo = lightFit_.scene.min, hi = lightFit_.scene.max;
    for (const glm::vec3& p : strands.rest) {
        lo = glm::min(lo, p);
        hi = glm::max(hi, p);
    }
    glm::vec3 margin = 0.1f * (hi - lo);
    lightFit_.scene = {lo - margin, hi + margin};
    if (!strands.rest.empty()) {
        Bounds rest{strands.rest.front(), strands.rest.front()};
        for (const glm::vec3& p : strands.rest) {
            rest.min = glm::min(rest.min, p);
            rest.max = glm::max(rest.max, p);
        }
        hairVolume_ = glm::vec4(rest.center(), std::max(0.5f * rest.diagonal(), 1e-6f));
    }
    lightFit_.unitsPerMetre = unitsPerMetre;
    guideCount_ = uint32_t(strands.strandCount());
    verticesPerStrand_ = strands.verticesPerStrand;
    solver_ = &solver;
    guideTriangles_ = guideTriangles(strands);
    // Each path's objects now where it draws, else the first time a frame draws with it.
    if (hairRaster() == HairRaster::Compute) {
        makeStrandRaster();
    } else {
        makeHairPass();
        makeOit();
    }
    unitsPerMetre_ = unitsPerMetre;
}

void Renderer::setHeadTransform(const glm::mat4& transform)
{
    headTransform_ = transform;
    meshPass_->setHeadTransform(transform);
}

StrandCounts Renderer::hairCounts() const
{
    return strandCounts(guideCount_, settings_.strands);
}

std::string Renderer::describeHairDraw() const
{
    if (hairRaster() == HairRaster::Compute)
        return "drawn in compute (hair_raster=compute)";
    return wisp::describeHairDraw(hairDrawCounts(guideCount_, settings_.strands));
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
    bool meshesInCompute = computeMeshes() && meshRaster_;
    auto meshes = [&] {
        if (meshesInCompute) {
            for (MeshRaster::Stage stage : MeshRaster::kMeshStages)
                if (stage == MeshRaster::Stage::Shade || meshRaster_->visibilityStale())
                    list.push_back(meshRaster_->pass(stage)); // (a still camera keeps the samples)
        } else {
            list.push_back(meshPass_->depthPass());
            list.push_back(meshPass_->shadowMaskPass());
            list.push_back(meshPass_.get());
        }
    };
    if (solver_ && hairRaster() == HairRaster::Compute) {
        using Stage = StrandRaster::Stage;
        list.push_back(strandRaster_->pass(Stage::Clear));
        list.push_back(headShadowPass_.get());
        for (Stage stage : StrandRaster::kLightStages)
            if (stage != Stage::Clear && (stage != Stage::LightCopy || !lightMaps_->hairDepthValuesUsed()))
                list.push_back(strandRaster_->pass(stage));
        meshes();
        for (Stage stage : StrandRaster::kCameraStages)
            list.push_back(strandRaster_->pass(stage));
        for (uint32_t piece = 0; piece < strandRaster_->recordedPieces(); ++piece) {
            list.push_back(strandRaster_->piecePass(Stage::Write, piece));
            list.push_back(strandRaster_->piecePass(Stage::Resolve, piece));
        }
        list.push_back(strandRaster_->pass(Stage::Reserve));
        if (meshesInCompute) {
            for (MeshRaster::Stage stage : MeshRaster::kFinalStages)
                list.push_back(meshRaster_->pass(stage));
        } else {
            list.push_back(strandComposite_.get());
        }
        list.push_back(strandRaster_->pass(Stage::Stats));
    } else if (!solver_ && meshesInCompute) {
        list.push_back(shadowPass_.get());
        list.push_back(opacityPass_.get());
        meshes();
        for (MeshRaster::Stage stage : MeshRaster::kFinalStages)
            list.push_back(meshRaster_->pass(stage));
    } else {
        list.push_back(shadowPass_.get());
        list.push_back(opacityPass_.get());
        if (oitClear_)
            list.push_back(oitClear_.get());
        meshes();
        if (hairPass_)
            list.push_back(hairPass_.get());
        if (oitResolve_) {
            list.push_back(oitResolve_.get());
            list.push_back(oitComposite_.get());
            list.push_back(oitStats_.get());
        }
    }
    if (guidePass_ && settings_.strands.showGuides)
        list.push_back(guidePass_.get());
    if (solver_ && !stepsAhead_.empty())
        placeStepsAhead(list);
    return list;
}

void Renderer::placeStepsAhead(std::vector<Pass*>& list)
{
    // Each step's integrate in front of one of the compute path's long passes after the curves,
    // its gather in front of the pass after that one; kernels without a host run at the end, one
    // after another. (Measured on the H100: the light's opacity and the count hide an integrate
    // whole, the generate half, the resolve none of it, so a fourth step costs there what it cost
    // first: docs/experiments.md, "The physics beside the frame's passes".)
    struct Kernel {
        GpuSolver::Stage stage;
        gpu::SimStep step;
        uint32_t turn;
        Pass* host = nullptr;
    };
    // Each step's turn of the grid's sums, as the solver will take them: after this frame's own
    // steps, recorded first, one after another.
    std::vector<Kernel> kernels;
    uint32_t turn = solver_->turn() ^ (physicsPass_ ? uint32_t(physicsPass_->stepCount() & 1u) : 0u);
    for (const gpu::SimStep& step : stepsAhead_) {
        for (GpuSolver::Stage stage : GpuSolver::kStages)
            kernels.push_back({stage, step, turn});
        turn ^= 1u;
    }
    stepsAhead_.clear();
    aheadPasses_.clear();
    if (hairRaster() == HairRaster::Compute && strandRaster_ && !settings_.strands.showGuides) {
        using Stage = StrandRaster::Stage;
        std::vector<Pass*> heavy = {strandRaster_->pass(Stage::LightOpacity), strandRaster_->pass(Stage::Generate),
                                    strandRaster_->pass(Stage::CountFragments)};
        if (strandRaster_->recordedPieces() > 0)
            heavy.push_back(strandRaster_->piecePass(Stage::Resolve, 0));
        auto curves = std::find(list.begin(), list.end(), strandRaster_->pass(Stage::Curves));
        size_t k = 0;
        for (auto it = curves == list.end() ? curves : curves + 1; it != list.end() && k < kernels.size(); ++it)
            if (kernels[k].stage != GpuSolver::Stage::Integrate || std::ranges::find(heavy, *it) != heavy.end())
                kernels[k++].host = *it;
    }
    std::vector<Pass*> placed;
    size_t k = 0;
    for (Pass* pass : list) {
        if (k < kernels.size() && kernels[k].host == pass) {
            aheadPasses_.push_back(std::make_unique<PhysicsKernelPass>(*solver_, kernels[k].stage, kernels[k].step,
                                                                       kernels[k].turn, pass));
            pass = aheadPasses_.back().get();
            ++k;
        }
        placed.push_back(pass);
    }
    for (; k < kernels.size(); ++k) {
        aheadPasses_.push_back(
            std::make_unique<PhysicsKernelPass>(*solver_, kernels[k].stage, kernels[k].step, kernels[k].turn, nullptr));
        placed.push_back(aheadPasses_.back().get());
    }
    list = std::move(placed);
}

} // namespace wisp
