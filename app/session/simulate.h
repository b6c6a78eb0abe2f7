// app/session/simulate.h: headless physics: `wisp simulate` (quality metrics as text or JSON) and the
// run loop behind it, which tests also drive with scripted head and sphere motion.
#pragma once

#include "app/scene/scene_timeline.h"
#include "app/session/hair_session.h"
#include "app/session/headless.h"
#include "app/settings/settings_table.h"
#include "gpu/context.h"
#include "physics/groom_metrics.h"
#include "physics/groomed_head.h"
#include "physics/simulation.h"

#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace wisp {

// Where the head and the sphere are, and the wind, at simulated time t (seconds): a test's
// scripted motion.
struct Motion {
    std::function<glm::mat4(float)> head = [](float) { return glm::mat4(1.0f); };
    std::function<glm::vec4(float)> sphere = [](float) { return glm::vec4(0.0f); }; // xyz, radius (0: none)
    std::function<glm::vec3(float)> wind; // m/s²; empty: the settings' wind throughout
};

struct SimulationReport {
    SimMetrics last;                                 // after the final step
    SimMetrics worst;                                // the largest of each metric over every sample
    std::vector<std::pair<uint32_t, float>> energy;  // (step, kinetic energy) every sample
    std::vector<std::pair<uint32_t, double>> stepMs; // (step, GPU ms per step since the last sample)
    double gpuMsPerStep = 0.0;
    uint32_t nonfiniteResets = 0;
    SimState state;                // the final state
    glm::mat4 headTransform{1.0f}; // where the head is after the final step
    // When the head turns during the run: the tips' lag behind it (physics/groom_metrics.h), the
    // tips sampled every 60 Hz frame's worth of steps (and at every energy sample).
    std::optional<TipLag> tipLag;
    MemorySample memoryStart, memoryEnd; // after the first sample, and at the end
};

// Runs `session`'s next `steps` fixed steps on the GPU, sampling every `sampleEvery` steps.
SimulationReport simulateHeadless(const vk::Context& ctx, HairSession& session, uint32_t steps,
                                  uint32_t sampleEvery = 25, const std::function<void(uint32_t)>& progress = {});
// The same for `scene` from rest, posed by `motion` (each step at its end).
SimulationReport simulateHeadless(const vk::Context& ctx, const GroomedHead& scene, const SimSettings& sim,
                                  uint32_t steps, const Motion& motion = {}, uint32_t sampleEvery = 25,
                                  const std::function<void(uint32_t)>& progress = {});

// Per-dispatch GPU time of a physics step: warm up, then time every step on its own.
struct DispatchTiming {
    std::string name;
    double medianMs = 0.0;
    double p95Ms = 0.0;
};
std::vector<DispatchTiming> profilePhysics(const vk::Context& ctx, HairSession& session, uint32_t warmupSteps,
                                           uint32_t timedSteps);

struct SimulateOptions {
    Settings settings; // every setting, for the JSON output
    uint32_t steps = 1000;
    bool json = false;
    // Steps between samples of the kinetic energy (each reads the state back). Frequent samples of a
    // large run leave the GPU mostly idle while the CPU copies, and the H100 then runs the same
    // kernels about twice as slowly (measured: 1.76 ms a step sampling every 100 steps, 3.9 ms every
    // 25, at 3.2 M vertices; consistent with the GPU lowering its clocks, not confirmed).
    uint32_t sampleEvery = 100;
    bool profile = false; // per-dispatch timings instead of the quality run
    uint32_t warmup = 60; // steps before timing (profile)
};

int runSimulate(const vk::Context& ctx, HairSession& session, const SimulateOptions& options);

} // namespace wisp
