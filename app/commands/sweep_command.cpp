// app/commands/sweep_command.cpp: `wisp sweep`: the grid of settings (--vary, checked as --set checks them)
// over the shared options, every point of grown hair checked against the device before the first
// one runs.
#include "app/commands/commands.h"

#include "app/session/sweep.h"
#include "app/settings/workload.h"
#include "core/error.h"
#include "physics/growth.h"

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

// Every point of a sweep's grid, checked before the first one runs: the growth's contradictions
// (curl_turns against vertices_per_strand, ...) and, of grown hair, the device's memory. A failure
// names the point.
void checkSweepGrid(const vk::DeviceReport& device, const std::vector<SweepAxis>& axes, const SessionOptions& base)
{
    size_t points = 1;
    for (const SweepAxis& a : axes)
        points *= a.values.size();
    for (size_t index = 0; index < points; ++index) {
        std::vector<std::string> values;
        std::string named;
        size_t rest = index;
        for (const SweepAxis& a : axes) {
            values.push_back(a.values[rest % a.values.size()]);
            rest /= a.values.size();
            named += (named.empty() ? "" : ", ") + a.name + "=" + values.back();
        }
        Settings s = base.settings;
        try {
            applyPointSettings(s, base, axes, values);
            if (!base.source.hairFiles.empty())
                continue; // loaded per point; the solver checks its own memory
            checkGrowth(s.growth);
            checkWorkload({.guides = s.growth.guides,
                           .verticesPerStrand = s.growth.verticesPerStrand,
                           .sim = s.sim,
                           .render = &s.render},
                          device);
        } catch (const UserError& e) {
            throw UserError("sweep: point " + std::to_string(index + 1) + "/" + std::to_string(points) + " (" + named +
                            "), before any point ran: " + e.what());
        }
    }
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
        ->check(wholeWithin(0, 100000))
        ->capture_default_str();
    cmd->add_option("--frames", c->options.frames, "frames timed at each point (median and p95)")
        ->check(wholeWithin(1, 100000))
        ->capture_default_str();
    c->shared = std::make_unique<SessionCommandLine>(
        cmd, SessionCommandLine::Uses{.scene = false, .noHair = false, .draws = true});
    return [c, &global] { return c->command->parsed() ? run(global, *c) : -1; };
}

} // namespace wisp
