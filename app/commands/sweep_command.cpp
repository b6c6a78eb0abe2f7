// app/commands/sweep_command.cpp: `wisp sweep`: the grid of settings (--vary, checked as --set checks them)
// over the shared options, every point of grown hair checked against the device before the first
// one runs.
#include "app/commands/commands.h"

#include "app/session/sweep.h"
#include "app/settings/workload.h"

#include <CLI/CLI.hpp>

#include <memory>

namespace wisp {

namespace {

struct SweepCommand {
    CLI::App* command = nullptr;
    std::unique_ptr<SessionCommandLine> shared;
    std::string out;
    std::vector<std::string> varies;
    SweepOptions options;
};

// Every point of a sweep's grid of grown hair, checked before the first one runs.
void checkSweepGrid(const vk::DeviceReport& device, const std::vector<SweepAxis>& axes, const SessionOptions& base)
{
    if (!base.source.hairFiles.empty())
        return; // loaded per point; the solver checks its own memory
    std::vector<size_t> at(axes.size(), 0);
    for (size_t axis = 0; axis < axes.size();) {
        Settings s = base.settings;
        for (size_t a = 0; a < axes.size(); ++a)
            applySetting(s, axes[a].name + "=" + axes[a].values[at[a]]);
        checkWorkload({.guides = s.growth.guides,
                       .verticesPerStrand = s.growth.verticesPerStrand,
                       .sim = s.sim,
                       .render = &s.render},
                      device);
        for (axis = 0; axis < axes.size() && ++at[axis] == axes[axis].values.size(); ++axis)
            at[axis] = 0; // the next point, odometer-wise
    }
    if (axes.empty())
        checkWorkload({.guides = base.settings.growth.guides,
                       .verticesPerStrand = base.settings.growth.verticesPerStrand,
                       .sim = base.settings.sim,
                       .render = &base.settings.render},
                      device);
}

int run(const GlobalOptions& g, SweepCommand& c)
{
    SessionOptions base = c.shared->resolve();
    c.options.axes = parseSweepGrid(c.varies, base.settings);
    c.options.outDir = c.out;
    vk::Context ctx(contextOptions(g));
    checkSweepGrid(ctx.report(), c.options.axes, base);
    return runSweep(ctx, c.options, base);
}

} // namespace

CommandRun addSweepCommand(CLI::App& app, const GlobalOptions& global)
{
    auto c = std::make_shared<SweepCommand>();
    CLI::App* cmd = app.add_subcommand("sweep", "per-pass GPU timings over a grid of settings: results.csv, fps.png, "
                                                "frame.png and passes.png (python3-matplotlib)");
    c->command = cmd;
    cmd->add_option("--out", c->out, "output folder (created)")->required();
    cmd->add_option("--vary", c->varies, "NAME=V1,V2,... for a setting from 'wisp settings'; several make a grid")
        ->required();
    cmd->add_option("--warmup", c->options.warmup, "frames before timing each point")
        ->check(CLI::Range(0u, 100000u))
        ->capture_default_str();
    cmd->add_option("--frames", c->options.frames, "frames timed at each point (median and p95)")
        ->check(CLI::Range(1u, 100000u))
        ->capture_default_str();
    c->shared = std::make_unique<SessionCommandLine>(
        cmd, SessionCommandLine::Uses{.scene = false, .noHair = false, .draws = true});
    return [c, &global] { return c->command->parsed() ? run(global, *c) : -1; };
}

} // namespace wisp
