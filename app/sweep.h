// app/sweep.h: `wisp sweep`: per-pass GPU timings over a grid of settings (any name from
// `wisp settings`), written as results.csv and drawn as charts by scripts/plot_sweep.py.
#pragma once

#include "app/session_options.h"
#include "app/settings_table.h"
#include "gpu/context.h"

#include <filesystem>
#include <string>
#include <vector>

namespace wisp {

struct SweepAxis {
    std::string name;
    std::vector<std::string> values;
};

// Parses "NAME=V1,V2,..."; every value is checked as --set checks it, on a copy of `base`.
SweepAxis parseSweepAxis(const std::string& spec, const Settings& base);

struct SweepOptions {
    std::filesystem::path outDir;
    std::vector<SweepAxis> axes;
    uint32_t warmup = 60;
    uint32_t frames = 300;
};

// Runs every point of the grid; `base` holds the head, the hair and the settings every point
// starts from.
int runSweep(const vk::Context& ctx, const SweepOptions& options, const SessionOptions& base);

} // namespace wisp
