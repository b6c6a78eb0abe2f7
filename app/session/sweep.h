// app/session/sweep.h: `wisp sweep`: per-pass GPU timings over a grid of settings (any name from
// `wisp settings`), written as results.csv and drawn as charts by scripts/plot_sweep.py.
#pragma once

#include "app/scene/session_options.h"
#include "app/settings/settings_table.h"
#include "gpu/context.h"

#include <filesystem>
#include <string>
#include <vector>

namespace wisp {

struct SweepAxis {
    std::string name;
    std::vector<std::string> values;
};

// Parses "NAME=V1,V2,..."; every value is checked as --set checks it, on a copy of `base`; an
// empty value (a trailing comma too) or one given twice is refused.
SweepAxis parseSweepAxis(const std::string& spec, const Settings& base);
// The most points a sweep's grid may have: each point is a run of --warmup + --frames frames.
inline constexpr size_t kSweepMostPoints = 1024;
// Every --vary, each a setting varied once, in a grid of at most kSweepMostPoints points; throws
// UserError naming the --vary (or the grid's size) otherwise.
std::vector<SweepAxis> parseSweepGrid(const std::vector<std::string>& specs, const Settings& base);

struct SweepOptions {
    std::filesystem::path outDir;
    std::vector<SweepAxis> axes;
    uint32_t warmup = 60;
    uint32_t frames = 300;
};

// The settings of one point of the grid (`values` one per axis) over `base`'s: a style axis first,
// under the command line's own values (an explicit --guides wins over it, as over --style), then
// the other axes.
void applyPointSettings(Settings& settings, const SessionOptions& base, const std::vector<SweepAxis>& axes,
                        const std::vector<std::string>& values);

// Runs every point of the grid; `base` holds the head, the hair and the settings every point
// starts from.
int runSweep(const vk::Context& ctx, const SweepOptions& options, const SessionOptions& base);

} // namespace wisp
