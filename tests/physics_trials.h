// tests/physics_trials.h: what the stability tests share: the physics settings as the
// settings table lists them, the values a trial gives each (its minimum, midpoint and maximum, or
// every choice), the small grooms they run on, a trial's settings applied as a session applies
// them (the per-part values written onto the scene's parts, as HairSession does through partsFor),
// its two seconds of steps and the worst of its metrics.
#pragma once

#include "app/settings/hair_source.h"
#include "app/settings/settings_table.h"
#include "physics/colliders.h"
#include "physics/groomed_head.h"
#include "physics/hair_style.h"
#include "physics/simulation.h"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

namespace wisp::test {

// Every setting of the table's simulation group: the physics a person can change.
inline std::vector<const SettingSpec*> physicsSettings()
{
    std::vector<const SettingSpec*> out;
    for (const SettingSpec& spec : settingSpecs())
        if (spec.group == SettingGroup::Simulation)
            out.push_back(&spec);
    return out;
}

inline std::vector<std::string> physicsSettingNames()
{
    std::vector<std::string> names;
    for (const SettingSpec* spec : physicsSettings())
        names.push_back(spec->name);
    return names;
}

// The values a trial gives `spec`: a number's minimum, midpoint and maximum (an integer's midpoint
// rounded down), every choice, off and on, a vector with all three components at the minimum, the
// midpoint and the maximum (its corners: the largest magnitudes). Empty for a type no trial knows
// (a new kind of physics setting then fails the test, by name, until it is given values here).
inline std::vector<SettingValue> trialValues(const SettingSpec& spec)
{
    const Range& r = spec.range;
    double mid = 0.5 * (r.min + r.max);
    switch (spec.type) {
    case SettingType::Number:
        return {{.number = r.min}, {.number = mid}, {.number = r.max}};
    case SettingType::Integer:
        return {{.number = r.min}, {.number = std::floor(mid)}, {.number = r.max}};
    case SettingType::OnOff:
        return {{.number = 0.0}, {.number = 1.0}};
    case SettingType::Choice: {
        std::vector<SettingValue> all;
        for (size_t i = 0; i < spec.choices.size(); ++i)
            all.push_back({.number = double(i)});
        return all;
    }
    case SettingType::Vector:
        return {{.vector = glm::dvec3(r.min)}, {.vector = glm::dvec3(mid)}, {.vector = glm::dvec3(r.max)}};
    case SettingType::Color:
        return {};
    }
    return {};
}

// The small grooms of the trials: 160 guides of the default bob, and fur (the crop cut to 4 cm).
inline std::vector<std::pair<std::string, GrowthSettings>> trialGrooms()
{
    GrowthSettings bob;
    bob.guides = 160;
    GrowthSettings fur;
    applyHairStyle(fur, *findHairStyle("crop"));
    fur.guides = 160;
    fur.lengthMetres = 0.04f;
    fur.trimLevelMetres = 0.0f;
    fur.hairlineLength = 1.0f;
    return {{"bob", bob}, {"fur", fur}};
}

// The scene's strands with each part's parameters as a session gives them under `sim` (the
// every-part values global_stiffness, local_stiffness, damping and drag when set).
inline StrandSet strandsUnder(const GroomedHead& scene, const SimSettings& sim)
{
    StrandSet strands = scene.strands;
    strands.parts = HairSource{}.partsFor(strands.parts, sim);
    return strands;
}

// Steps of a trial: a quarter of a second for the hair to settle from its rest pose with the head
// still (not measured: a rest pose inside the colliders pops out there, a start artefact of its
// own, docs/physics.md), then two simulated seconds.
inline uint32_t trialSettleSteps(const SimSettings& sim)
{
    return uint32_t(std::lround(0.25f * sim.stepHz));
}
inline uint32_t trialSteps(const SimSettings& sim)
{
    return uint32_t(std::lround(2.0f * sim.stepHz));
}

// Step k of a trial's measured two seconds (negative: settling): the head turns to and fro (0.4 rad
// at 4 rad/s) for the first second, then holds still; the wind blows in the first second only, so
// that the hair can settle in the second.
inline gpu::SimStep trialStep(const SimSetup& setup, const SimSettings& sim, int k)
{
    int half = int(trialSteps(sim) / 2);
    float t = float(std::clamp(k, 0, half)) / sim.stepHz;
    glm::mat4 head = glm::rotate(glm::mat4(1.0f), 0.4f * std::sin(4.0f * t), glm::vec3(0, 1, 0));
    bool windy = k >= 0 && k < half;
    return makeStep(setup, head, glm::vec4(0.0f), float(k) / sim.stepHz, windy ? sim.wind : glm::vec3(0.0f));
}

// The worst of a trial's metrics over its steps.
struct TrialRun {
    float worstEnergy = 0.0f;
    float lastEnergy = 0.0f; // the worst of the last tenth of the run, 0.9 s after the head stopped
    float worstPenetration = 0.0f;
    float worstStretch = 0.0f;
    uint32_t resets = 0;
    bool finite = true;
    std::vector<glm::vec4> positions; // at the end

    void add(const SimMetrics& m, uint32_t k, uint32_t steps)
    {
        worstEnergy = std::max(worstEnergy, m.kineticEnergy);
        worstPenetration = std::max(worstPenetration, m.maxPenetration);
        worstStretch = std::max(worstStretch, m.maxStretch);
        if (k >= steps - steps / 20)
            lastEnergy = std::max(lastEnergy, m.kineticEnergy);
    }
    void finish(const SimState& state)
    {
        for (const glm::vec4& p : state.positions)
            finite = finite && std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z);
        resets = state.nonfiniteResets;
        positions = state.positions;
    }
};

// How much harder than the default gravity the hair is pulled: gravity and the wind at its
// strongest gust (sim.h strandWind: at most 1.25 times the setting), against the default gravity;
// at least 1.
inline float pullAgainstDefault(const SimSettings& sim)
{
    return std::max(1.0f, (sim.gravity + 1.25f * glm::length(sim.wind)) / SimSettings{}.gravity);
}

// The deepest free vertex of the rest pose inside the head's colliders (the colliders are
// ellipsoids under the scalp, which dips into them here and there).
inline float restPenetration(const GroomedHead& scene)
{
    float deepest = 0.0f;
    const StrandSet& s = scene.strands;
    for (size_t k = 0; k < s.strandCount(); ++k)
        for (uint32_t i = s.strands[k].pinnedRoot; i < s.verticesPerStrand; ++i)
            deepest = std::max(deepest, penetrationDepth(scene.gpuColliders, s.rest[k * s.verticesPerStrand + i]));
    return deepest;
}

inline float largestMove(const std::vector<glm::vec4>& a, const std::vector<glm::vec4>& b)
{
    float worst = 0.0f;
    for (size_t i = 0; i < a.size() && i < b.size(); ++i)
        worst = std::max(worst, glm::length(glm::vec3(a[i]) - glm::vec3(b[i])));
    return worst;
}

} // namespace wisp::test
