// app/simulate.h: `wisp simulate`: physics only, headless, with quality metrics (stretch,
// penetration, root drift, resets, kinetic energy over time, GPU time per step) as text or JSON.
#pragma once

#include "physics/growth.h"
#include "physics/simulation.h"
#include "renderer/vk/context.h"

#include <optional>
#include <string>

namespace wisp {

struct SimulateOptions {
    vk::ContextOptions context;
    std::string headFile;
    GrowthSettings growth;
    SimSettings sim;
    uint32_t steps = 1000;
    std::optional<glm::vec4> sphere;  // centre xyz and radius, asset units
    bool json = false;
};

int runSimulate(const SimulateOptions& options);

}  // namespace wisp
