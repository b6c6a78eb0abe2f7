// app/commands/view_command.cpp: `wisp view`: the window's own options (--frames, --screenshot, --script)
// over the shared ones; the window starts from a scene's state at time 0. Without a display it
// says so before loading anything.
#include "app/commands/commands.h"

#include "app/window/viewer.h"
#include "app/window/window.h"

#include <CLI/CLI.hpp>

#include <memory>

namespace wisp {

namespace {

struct ViewCommand {
    CLI::App* command = nullptr;
    std::unique_ptr<SessionCommandLine> shared;
    WindowOptions options;
};

int run(const GlobalOptions& g, ViewCommand& c)
{
    requireDisplay(); // before any loading
    SessionOptions session = c.shared->resolve();
    WindowOptions& o = c.options;
    o.context = contextOptions(g);
    o.scene = buildCheckedHead(g, session, &session.settings.render, /*window=*/true);
    o.timeline = session.timeline;
    o.sceneLength = session.sceneLength();
    o.source = session.source;
    o.settings = session.settings;
    // The window starts from the scene's state at time 0 (its sphere, wind and light).
    SceneState initial = session.timeline.at(0.0);
    o.settings.sim.wind = initial.wind;
    o.sphere = initial.sphere;
    o.settings.render.light = initial.light;
    return runWindow(std::move(o));
}

} // namespace

CommandRun addViewCommand(CLI::App& app, const GlobalOptions& global)
{
    auto c = std::make_shared<ViewCommand>();
    CLI::App* cmd = app.add_subcommand(
        "view", "the interactive window: the hair simulated live, a panel of settings, counts and GPU times, keys for "
                "the sphere, the light, the head and the wind (listed by 'wisp view --help')");
    c->command = cmd;
    cmd->footer("Keys and mouse: " + viewerHelp());
    c->shared = std::make_unique<SessionCommandLine>(cmd, SessionCommandLine::Uses{});
    WindowOptions& o = c->options;
    cmd->add_option("--frames", o.maxFrames, "close after this many frames (0 = run until closed)")
        ->check(wholeWithin(0, 4294967295.0));
    cmd->add_option("--screenshot", o.screenshot, "write the last frame to this PNG when closing");
    cmd->add_flag("--screenshot-panel", o.screenshotPanel, "the --screenshot includes the ImGui panel");
    cmd->add_option(
           "--script", o.script,
           "replay timed input events from this file: lines 'FRAME press|release|tap KEY' or "
           "'FRAME drag-sphere|drag-light|orbit DX DY' or 'FRAME set NAME=VALUE' (a setting, as set in the "
           "panel) (KEY: left right up down pageup pagedown j l i k a d w plus minus space n r p f5 o h t f2 f3 "
           "escape)")
        ->check(CLI::ExistingFile);
    return [c, &global] { return c->command->parsed() ? run(global, *c) : -1; };
}

} // namespace wisp
