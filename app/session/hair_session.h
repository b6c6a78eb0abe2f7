// app/session/hair_session.h: one simulated head of hair as every front end runs it: the head and its
// groom, the solver and the fixed-step clock. render, record, simulate, sweep and the window each
// make one from their resolved options; the steps due (a frame's worth, or real time spent) and
// where the head, the sphere and the wind are at each step (a scene's timeline, the window's
// viewer, a test's motion) come from here, and so do the solver's rebuilds and shader reloads.
#pragma once

#include "app/scene/scene_timeline.h"
#include "app/settings/hair_source.h"
#include "physics/gpu_solver.h"
#include "physics/groomed_head.h"
#include "physics/simulation.h"
#include "physics/step_clock.h"

#include <functional>
#include <memory>
#include <vector>

namespace wisp {

namespace vk {
class Context;
}
class Renderer;

// Where the head, the user's sphere and the wind are at a moment.
struct StepPose {
    glm::mat4 head{1.0f};   // the head's rigid transform
    glm::vec4 sphere{0.0f}; // xyz, radius (0: none), head units
    glm::vec3 wind{0.0f};   // m/s²
};
using PoseAt = std::function<StepPose(double seconds)>;

// A timeline that holds still: the sphere, the wind and the light given, no keys.
SceneTimeline stillTimeline(const glm::vec4& sphere, const glm::vec3& wind, const LightSettings& light = {});

class HairSession {
public:
    // `scene`: the head and its hair (no strands: the head alone, nothing simulated); `timeline`
    // poses the steps (its head turn, sphere and wind); `source` gives each part's own parameters
    // over the settings (HairSource::partsFor).
    HairSession(const vk::Context& ctx, GroomedHead scene, const SimSettings& sim, SceneTimeline timeline,
                HairSource source = {});
    HairSession(const HairSession&) = delete;
    HairSession& operator=(const HairSession&) = delete;

    const GroomedHead& scene() const { return scene_; }
    const Bounds& headBounds() const { return headBounds_; }
    bool hasHair() const { return solver_ != nullptr; }
    GpuSolver* solver() { return solver_.get(); }
    const SimSetup& setup() const { return setup_; }
    const SimSettings& sim() const { return sim_; }
    StepClock& clock() { return clock_; }
    const StepClock& clock() const { return clock_; }
    const SceneTimeline& timeline() const { return timeline_; }
    // Poses the steps by `poses` instead of the timeline (a test's scripted motion).
    void setPoses(PoseAt poses) { poses_ = std::move(poses); }
    // The head's transform the timeline gives at `seconds` (a turn about the head's centre).
    glm::mat4 headTransformAt(double seconds) const;

    // Draws the hair with `renderer` (after making it, or after the solver was rebuilt).
    void attachTo(Renderer& renderer);

    // The next `count` fixed steps, each posed at its end (by the timeline, or setPoses); advances
    // the clock. Without hair the clock advances alone (time passes for the camera and the light).
    std::vector<gpu::SimStep> nextSteps(uint32_t count);
    // The same, all held at one pose (the window's: what its viewer shows now).
    std::vector<gpu::SimStep> nextSteps(uint32_t count, const StepPose& pose);

    // New simulation settings. When what the solver packs changed (anything but the wind and its
    // frequency, which the next steps take), the solver is made again, the hair back at rest
    // around `head`; true then, and the renderer must be attached again.
    bool setSim(const SimSettings& sim, const glm::mat4& head);
    // Every strand back at rest around `head` (the device must be idle).
    void reset(const glm::mat4& head);
    // The solver's kernels made again from the SPIR-V on disk (the device must be idle).
    void reloadShaders();

private:
    SimSetup makeSetup() const;
    StepPose timelinePose(double seconds) const;

    const vk::Context& ctx_;
    GroomedHead scene_;
    HairSource source_;
    std::vector<PartSettings> partsAsBuilt_; // before the settings' and the per-part overrides
    Bounds headBounds_;
    SimSettings sim_;
    SimSetup setup_;
    StepClock clock_;
    SceneTimeline timeline_;
    PoseAt poses_;
    std::unique_ptr<GpuSolver> solver_;
};

} // namespace wisp
