// app/commands/simulate_command.cpp: `wisp simulate`: physics only, headless; the options of the run (steps,
// sampling, --profile) over the shared head, hair, scene and settings options.
#include "app/commands/commands.h"

#include "app/session/hair_session.h"
#include "app/session/simulate.h"

#include <CLI/CLI.hpp>

#include <memory>

namespace wisp {

namespace {

struct SimulateCommand {
    CLI::App* command = nullptr;
    std::unique_ptr<SessionCommandLine> shared;
    SimulateOptions options;
};

int run(const GlobalOptions& g, SimulateCommand& c)
{
    SessionOptions session = c.shared->resolve();
    c.options.settings = session.settings;
    GroomedHead scene = buildCheckedHead(g, session, nullptr);
    vk::Context ctx(contextOptions(g));
    HairSession hair(ctx, std::move(scene), session.settings.sim, session.timeline, session.source);
    return runSimulate(ctx, hair, c.options);
}

} // namespace

CommandRun addSimulateCommand(CLI::App& app, const GlobalOptions& global)
{
    auto c = std::make_shared<SimulateCommand>();
    CLI::App* cmd = app.add_subcommand("simulate", "physics only, headless: quality metrics as text or JSON");
    c->command = cmd;
    SimulateOptions& o = c->options;
    cmd->add_option("--steps", o.steps, "fixed simulation steps to run")
        ->check(wholeWithin(1, 10000000))
        ->capture_default_str();
    cmd->add_flag("--json", o.json, "print one JSON object");
    cmd->add_option("--sample-every", o.sampleEvery,
                    "steps between samples of the kinetic energy (each reads the state back)")
        ->check(wholeWithin(1, 10000000))
        ->capture_default_str();
    cmd->add_flag("--profile", o.profile,
                  "time each kernel: --warmup steps, then --steps steps each timed on its own (median and p95)");
    cmd->add_option("--warmup", o.warmup, "steps before timing with --profile")
        ->check(wholeWithin(0, 100000))
        ->capture_default_str();
    c->shared = std::make_unique<SessionCommandLine>(
        cmd, SessionCommandLine::Uses{.scene = true, .noHair = false, .draws = false});
    return [c, &global] { return c->command->parsed() ? run(global, *c) : -1; };
}

} // namespace wisp
