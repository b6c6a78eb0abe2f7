// app/commands/record_command.cpp: `wisp record`: the options of a recording (its folder, video, frames and
// rate) over the shared ones; with a scene and no --frames, as many frames as the scene lasts.
#include "app/commands/commands.h"

#include "app/session/hair_session.h"
#include "app/session/record.h"

#include <CLI/CLI.hpp>

#include <cmath>
#include <memory>

namespace wisp {

namespace {

struct RecordCommand {
    CLI::App* command = nullptr;
    CLI::Option* frames = nullptr;
    std::unique_ptr<SessionCommandLine> shared;
    std::string out, video;
    RecordOptions options;
};

int run(const GlobalOptions& g, RecordCommand& c)
{
    SessionOptions session = c.shared->resolve();
    RecordOptions& rec = c.options;
    rec.outDir = c.out;
    rec.video = c.video;
    rec.settings = session.settings.render;
    if (session.scene && c.frames->count() == 0 && session.sceneLength() > 0.0)
        rec.frames = std::max(1u, uint32_t(std::ceil(session.sceneLength() * double(rec.fps) - 1e-6)));
    checkRecordOutputs(rec); // before any loading
    GroomedHead scene = buildCheckedHead(g, session, &rec.settings);
    vk::Context ctx(contextOptions(g));
    HairSession hair(ctx, std::move(scene), session.settings.sim, session.timeline, session.source);
    return runRecord(ctx, hair, rec);
}

} // namespace

CommandRun addRecordCommand(CLI::App& app, const GlobalOptions& global)
{
    auto c = std::make_shared<RecordCommand>();
    CLI::App* cmd = app.add_subcommand(
        "record", "render a run frame by frame into a folder of PNGs (+ a video through ffmpeg, + a contact sheet); "
                  "reproducible");
    c->command = cmd;
    cmd->add_option("--out", c->out,
                    "output folder for frame_00000.png ... and contact_sheet.png (created; its parent must exist)")
        ->required();
    cmd->add_flag("--overwrite", c->options.overwrite,
                  "delete the frames and contact sheet of an earlier run in the --out folder first (without it, "
                  "such a folder is refused)");
    cmd->add_option("--video", c->video, "also encode the frames into this video file (H.264 through ffmpeg)");
    c->frames = cmd->add_option("--frames", c->options.frames,
                                "frames to record (with --scene, by default as many as the scene lasts)")
                    ->check(wholeWithin(1, 1000000))
                    ->capture_default_str();
    cmd->add_option("--fps", c->options.fps,
                    "frames per simulated second (each frame is round(step_hz / fps) fixed steps)")
        ->check(within(1.0, 1000.0))
        ->capture_default_str();
    c->shared = std::make_unique<SessionCommandLine>(cmd, SessionCommandLine::Uses{});
    return [c, &global] { return c->command->parsed() ? run(global, *c) : -1; };
}

} // namespace wisp
