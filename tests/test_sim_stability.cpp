// tests/test_sim_stability.cpp: every physics setting of the settings table at its minimum,
// midpoint and maximum (every choice), the others at their defaults, on two small grooms on the
// CPU reference solver for two simulated seconds: the hair stays finite and
// unstretched, goes no deeper into the head's colliders than its rest pose does plus the default
// margin, keeps its kinetic energy within a bound set by the defaults' run, settles once the head
// stops, and each value really reaches the solver. (The GPU against the CPU on a handful of them:
// test_gpu_solver.cpp, GpuSolver.StabilityTrialsMatchTheCpu.)
#include "assets/head.h"
#include "physics/colliders.h"
#include "physics/cpu_solver.h"
#include "physics_trials.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

using namespace wisp;
using test::TrialRun;

namespace {

TrialRun runTrial(const GroomedHead& scene, const SimSettings& sim)
{
    StrandSet strands = test::strandsUnder(scene, sim);
    SimSetup setup = makeSimSetup(sim, strands, scene.gpuColliders, scene.unitsPerMetre, scene.head.mesh);
    CpuSolver cpu(strands, setup, glm::mat4(1.0f));
    const uint32_t steps = test::trialSteps(sim);
    for (int k = -int(test::trialSettleSteps(sim)); k < 0; ++k)
        cpu.step(test::trialStep(setup, sim, k));
    TrialRun run;
    for (uint32_t k = 0; k < steps; ++k) {
        std::vector<glm::vec4> previous = cpu.state().positions;
        gpu::SimStep step = test::trialStep(setup, sim, int(k));
        cpu.step(step);
        run.add(measure(cpu.state(), previous, 1.0f / sim.stepHz, strands, setup, step), k, steps);
    }
    run.finish(cpu.state());
    return run;
}

struct Groom {
    std::string name;
    GroomedHead scene;
    float restPenetration = 0.0f; // the deepest free vertex of the rest pose inside a collider
    TrialRun defaults;
};

// The grooms and their runs at the defaults, made once for every setting's test.
const std::vector<Groom>& grooms()
{
    static const std::vector<Groom> all = [] {
        std::vector<Groom> out;
        for (const auto& [name, growth] : test::trialGrooms()) {
            Groom g{name, buildGrownHead(defaultHeadPath(), growth), 0.0f, {}};
            g.restPenetration = test::restPenetration(g.scene);
            g.defaults = runTrial(g.scene, SimSettings{});
            out.push_back(std::move(g));
        }
        return out;
    }();
    return all;
}

} // namespace

class EveryPhysicsSetting : public testing::TestWithParam<std::string> {};

// The bounds, each against the defaults' run of the same groom (a quarter of a second to settle
// from the rest pose, then the head turning to and fro for a second and still for one), whose
// worst kinetic energy is the hair carried round by the head:
//  - energy: at most 4 times it (the hair no more than twice as fast on the whole), times the
//    square of how much harder gravity and the gusts' strongest wind pull than the default gravity
//    where they do (the speed drag allows grows with the pull): the default bob's 64 at damping 0
//    was 1,450, growing 2.4 times every 5 steps;
//  - settling: a second after the head stopped (and the wind dropped), at most 3% of it;
//  - penetration: no deeper than the rest pose's own free vertices (colliders are ellipsoids under a
//    scalp that dips into them) plus the default collision margin;
//  - stretch: follow-the-leader keeps every segment's length to float rounding.
TEST_P(EveryPhysicsSetting, IsStableAtItsExtremesAndMidpoint)
{
    const SettingSpec& spec = settingSpec(GetParam());
    std::vector<SettingValue> values = test::trialValues(spec);
    ASSERT_FALSE(values.empty()) << spec.name << ": a physics setting of a type the stability trials give no values "
                                 << "(tests/physics_trials.h trialValues)";
    const Settings defaults;
    for (const Groom& groom : grooms()) {
        float diagonal = groom.scene.head.mesh.bounds().diagonal();
        float margin = SimSettings{}.collisionMarginMetres * groom.scene.unitsPerMetre;
        for (const SettingValue& value : values) {
            Settings settings;
            setSetting(settings, spec, value, spec.name);
            TrialRun run = runTrial(groom.scene, settings.sim);
            std::string what = groom.name + ", " + spec.name + "=" + settingText(spec, value);
            float pull = test::pullAgainstDefault(settings.sim);
            float energyBound = 4.0f * groom.defaults.worstEnergy * pull * pull;
            float moved = test::largestMove(run.positions, groom.defaults.positions);
            std::fprintf(stderr,
                         "%s: worst energy %.4g (bound %.4g), a second after %.3g (defaults %.3g), penetration %.3g "
                         "of the diagonal (rest %.3g), stretch %.2g, moved %.3g from the defaults' end\n",
                         what.c_str(), double(run.worstEnergy), double(energyBound), double(run.lastEnergy),
                         double(groom.defaults.lastEnergy), double(run.worstPenetration / diagonal),
                         double(groom.restPenetration / diagonal), double(run.worstStretch), double(moved));
            EXPECT_TRUE(run.finite) << what;
            EXPECT_EQ(run.resets, 0u) << what;
            EXPECT_LT(run.worstStretch, 1e-4f) << what;
            EXPECT_LT(run.worstPenetration, groom.restPenetration + margin) << what;
            EXPECT_LT(run.worstEnergy, energyBound) << what;
            EXPECT_LT(run.lastEnergy, 0.03f * groom.defaults.worstEnergy) << what << ": it settles";
            // Each value reaches the solver: the hair ends elsewhere than with the defaults. The
            // wind's frequency acts only with wind, and the grid's sums differ only on the GPU
            // (GpuSolver.StabilityTrialsMatchTheCpu): those change what the solver is given.
            if (spec.get(settings) == spec.get(defaults)) {
                continue;
            }
            if (spec.name == "wind_frequency" || spec.name == "grid_atomics") {
                SimSetup a = makeSimSetup(settings.sim, groom.scene.strands, groom.scene.gpuColliders, 1.0f);
                SimSetup b = makeSimSetup(defaults.sim, groom.scene.strands, groom.scene.gpuColliders, 1.0f);
                EXPECT_TRUE(a.windFrequency != b.windFrequency || a.params.gridFixedScale != b.params.gridFixedScale)
                    << what << ": the value does not reach the solver";
            } else {
                EXPECT_GT(moved, 1e-5f * diagonal) << what << ": the value does not reach the solver";
            }
        }
    }
}

INSTANTIATE_TEST_SUITE_P(Table, EveryPhysicsSetting, testing::ValuesIn(test::physicsSettingNames()),
                         [](const testing::TestParamInfo<std::string>& param) { return param.param; });
