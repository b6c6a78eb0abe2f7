// app/session/hair_session.cpp: the solver made and remade from the settings, and the fixed steps posed.
#include "app/session/hair_session.h"

#include "renderer/renderer.h"

#include <cstring>

namespace wisp {

SceneTimeline stillTimeline(const glm::vec4& sphere, const glm::vec3& wind, const LightSettings& light)
{
    SceneState still;
    still.sphere = sphere;
    still.wind = wind;
    still.light = light;
    return SceneTimeline({}, SceneInterpolation::Linear, still);
}

HairSession::HairSession(const vk::Context& ctx, GroomedHead scene, const SimSettings& sim, SceneTimeline timeline,
                         HairSource source)
    : ctx_(ctx), scene_(std::move(scene)), source_(std::move(source)), partsAsBuilt_(scene_.strands.parts),
      headBounds_(scene_.head.mesh.bounds()), sim_(sim), clock_(sim.stepHz), timeline_(std::move(timeline))
{
    if (scene_.strands.strandCount() == 0)
        return;
    scene_.strands.parts = source_.partsFor(partsAsBuilt_, sim_);
    setup_ = makeSetup();
    solver_ = std::make_unique<GpuSolver>(ctx_, scene_.strands, setup_, headTransformAt(0.0));
}

SimSetup HairSession::makeSetup() const
{
    // The wind the timeline starts with (steps carry their own; this is the setup's default).
    SimSettings sim = sim_;
    sim.wind = timeline_.at(0.0).wind;
    return makeSimSetup(sim, scene_.strands, scene_.gpuColliders, scene_.unitsPerMetre, scene_.head.mesh);
}

glm::mat4 HairSession::headTransformAt(double seconds) const
{
    return poses_ ? poses_(seconds).head : headYawTransform(headBounds_, timeline_.at(seconds).headYawDeg);
}

StepPose HairSession::timelinePose(double seconds) const
{
    SceneState s = timeline_.at(seconds);
    return {.head = headYawTransform(headBounds_, s.headYawDeg), .sphere = s.sphere, .wind = s.wind};
}

void HairSession::attachTo(Renderer& renderer)
{
    if (solver_)
        renderer.attachHair(*solver_, scene_.strands, scene_.unitsPerMetre);
}

std::vector<gpu::SimStep> HairSession::nextSteps(uint32_t count)
{
    std::vector<gpu::SimStep> steps;
    if (solver_) {
        for (uint64_t k = clock_.stepsDone(); k < clock_.stepsDone() + count; ++k) {
            StepPose p = poses_ ? poses_(clock_.stepEnd(k)) : timelinePose(clock_.stepEnd(k));
            steps.push_back(makeStep(setup_, p.head, p.sphere, clock_.stepStart(k), p.wind));
        }
    }
    clock_.advance(count);
    return steps;
}

std::vector<gpu::SimStep> HairSession::nextSteps(uint32_t count, const StepPose& pose)
{
    std::vector<gpu::SimStep> steps;
    if (solver_)
        for (uint64_t k = clock_.stepsDone(); k < clock_.stepsDone() + count; ++k)
            steps.push_back(makeStep(setup_, pose.head, pose.sphere, clock_.stepStart(k), pose.wind));
    clock_.advance(count);
    return steps;
}

bool HairSession::setSim(const SimSettings& sim, const glm::mat4& head)
{
    if (sim.stepHz != sim_.stepHz)
        clock_.setStepHz(sim.stepHz);
    sim_ = sim;
    if (!solver_)
        return false;
    scene_.strands.parts = source_.partsFor(partsAsBuilt_, sim_);
    SimSetup setup = makeSetup();
    bool same =
        setup.substeps == setup_.substeps && std::memcmp(&setup.params, &setup_.params, sizeof(gpu::SimParams)) == 0;
    setup_ = setup; // the wind's frequency, whichever way
    if (same)
        return false;
    solver_.reset(); // before the new one allocates
    solver_ = std::make_unique<GpuSolver>(ctx_, scene_.strands, setup_, head);
    return true;
}

void HairSession::reset(const glm::mat4& head)
{
    if (solver_)
        solver_->reset(head);
}

void HairSession::reloadShaders()
{
    if (solver_)
        solver_->reloadPipelines();
}

} // namespace wisp
