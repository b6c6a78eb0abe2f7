// app/commands/render_command.cpp: `wisp render`: one frame offscreen into a PNG after --frames simulated
// frames (the head, its hair, a scene's moment), or --profile N: per-pass GPU times of whole frames
// as JSON.
#include "app/commands/commands.h"

#include "app/image/image_io.h"
#include "app/session/hair_session.h"
#include "app/session/headless.h"
#include "app/session/reference_render.h"
#include "app/settings/settings_table.h"
#include "core/error.h"
#include "gpu/check.h"
#include "renderer/renderer.h"

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <chrono>
#include <cstdio>
#include <iostream>
#include <memory>
#include <unistd.h>

namespace wisp {

namespace {

struct RenderCommand {
    CLI::App* command = nullptr;
    CLI::Option* out = nullptr;
    std::unique_ptr<SessionCommandLine> shared;
    std::string outFile;
    uint32_t frames = 0;
    float fps = 30.0f;
    uint32_t profileFrames = 0; // > 0: time this many frames (after profileWarmup) instead of writing a picture
    uint32_t profileWarmup = 60;
    bool still = false;     // --still: the timed frames take no steps
    bool reference = false; // path-trace the frame instead (app/session/reference_render.h)
    ReferenceOptions referenceOptions;
    CLI::Option* spp = nullptr;
    CLI::Option* seed = nullptr;
    CLI::Option* bounces = nullptr;
};

// The reference's progress on stderr: a bar redrawn in place on a terminal, a line every 10% in a log.
void referenceProgress(uint32_t done, uint32_t total, double elapsed)
{
    bool tty = isatty(STDERR_FILENO) != 0;
    uint32_t step = std::max(1u, total / 10);
    if (!tty && done != total && (done / step) == ((done - 1) / step))
        return;
    constexpr int kWidth = 30;
    int filled = int(double(kWidth) * done / std::max(total, 1u));
    double eta = done > 0 ? elapsed / done * (total - done) : 0.0;
    std::fprintf(stderr, "%sreference [%s%s] %u/%u samples, %.1f s, ETA %.1f s%s", tty ? "\r" : "",
                 std::string(size_t(filled), '#').c_str(), std::string(size_t(kWidth - filled), '.').c_str(), done,
                 total, elapsed, eta, tty && done != total ? "" : "\n");
    std::fflush(stderr);
}

int runReference(const GlobalOptions& g, SessionOptions& o, const RenderCommand& c)
{
    checkImageOutput(c.outFile); // fail before any GPU work
    RenderSettings& settings = o.settings.render;
    GroomedHead scene = buildCheckedHead(g, o, &settings);
    vk::Context ctx(contextOptions(g));
    ReferenceRender reference;
    try {
        HairSession session(ctx, std::move(scene), o.settings.sim, o.timeline, o.source);
        // The bar's time is the tracing's, as the summary's is.
        reference = renderReference(ctx, session, settings, c.frames, c.fps, c.referenceOptions, referenceProgress);
    } catch (const vk::DeviceLost& e) {
        throw vk::DeviceLost(e.what() + std::string("; ") + c.outFile + " was not written");
    }
    int status = validationStatus(ctx);
    if (status != 0)
        return status; // nothing written
    if (isExrPath(c.outFile))
        writeExr(c.outFile, reference.picture.width, reference.picture.height, reference.picture.linear);
    else
        writePng(c.outFile, reference.picture.width, reference.picture.height, reference.picture.rgba);
    std::cout << c.outFile << "\n" << describeReference(reference, c.referenceOptions) << "\n";
    return 0;
}

int runProfile(const GlobalOptions& g, SessionOptions& o, const RenderCommand& c)
{
    RenderSettings& settings = o.settings.render; // its samples and a loaded groom's density are chosen into it
    o.source.noHair = false;
    GroomedHead scene = buildCheckedHead(g, o, &settings);
    vk::Context ctx(contextOptions(g));
    HairSession session(ctx, std::move(scene), o.settings.sim, o.timeline, o.source);
    OitStats oit;
    RasterStats raster;
    std::vector<PassTiming> timings =
        profileFrames(ctx, session, settings, c.fps, c.profileWarmup, c.profileFrames, &oit, &raster, !c.still);
    HairRaster path = resolveHairRaster(settings.hairRaster);
    StrandCounts counts = strandCounts(uint32_t(session.scene().strands.strandCount()), settings.strands);
    nlohmann::json out = {{"device", ctx.report().name},
                          {"width", settings.width},
                          {"height", settings.height},
                          {"guides", counts.guides},
                          {"vertices_per_strand", session.scene().strands.verticesPerStrand},
                          {"strands_per_guide", counts.strandsPerGuide},
                          {"divisions", counts.divisions},
                          {"strands", counts.strands()},
                          {"segments", counts.segments()},
                          {"samples", settings.samples},
                          {"warmup_frames", c.profileWarmup},
                          {"timed_frames", c.profileFrames},
                          {"timed_steps", !c.still},
                          {"transparency", settings.transparency.mode == Transparency::Oit ? "oit" : "msaa"},
                          {"oit_fragments", oit.fragments},
                          {"oit_overflow", oit.overflow},
                          {"oit_capacity", oit.capacity},
                          {"shadow_size", settings.shadows.mapSize},
                          {"hair_raster_drawn", path == HairRaster::Compute ? "compute" : "graphics"},
                          {"settings", settingsJson(o.settings)}};
    if (path == HairRaster::Compute)
        out["raster"] = {{"segments", raster.segments}, {"hidden", raster.hidden},      {"fragments", raster.fragments},
                         {"capacity", raster.capacity}, {"overflow", raster.overflow},  {"max_pixel", raster.maxPixel},
                         {"pieces", raster.pieces},     {"one_walk", raster.oneWalk()}, {"spilled", raster.spilled}};
    for (const PassTiming& t : timings)
        out["ms"][t.name] = {{"median", t.medianMs}, {"p95", t.p95Ms}};
    std::cout << out.dump() << "\n";
    return validationStatus(ctx);
}

int run(const GlobalOptions& g, const RenderCommand& c)
{
    if (c.profileFrames == 0 && !*c.out)
        throw UserError("render: --out FILE.png is required (or --profile N to time frames)");
    if (!c.reference && (*c.spp || *c.seed || *c.bounces))
        throw UserError("render: --spp, --sample-seed and --bounces are options of --reference");
    if (c.still && c.profileFrames == 0)
        throw UserError("render: --still is an option of --profile");
    if (c.reference && c.profileFrames > 0)
        throw UserError("render: --reference renders a picture; it cannot be timed with --profile");
    SessionOptions o = c.shared->resolve();
    if (c.profileFrames > 0)
        return runProfile(g, o, c);
    if (c.reference)
        return runReference(g, o, c);
    if (isExrPath(c.outFile))
        throw UserError("render: --out " + c.outFile +
                        ": linear output (.exr) is written by --reference; the real-time frame is tone-mapped as "
                        "it is shaded, so it is written as a .png");
    checkPngOutput(c.outFile); // fail before any GPU work
    RenderSettings& settings = o.settings.render;
    GroomedHead scene = buildCheckedHead(g, o, &settings);
    vk::Context ctx(contextOptions(g));
    // What loading the hair did (placement, short strands), printed after the picture.
    std::vector<std::string> loaded = o.source.noHair ? std::vector<std::string>{} : describeLoadedHair(scene);
    Picture picture;
    try {
        HairSession session(ctx, std::move(scene), o.settings.sim, o.timeline, o.source);
        picture = renderPicture(ctx, session, settings, c.frames, c.fps);
    } catch (const vk::DeviceLost& e) {
        throw vk::DeviceLost(e.what() + std::string("; ") + c.outFile + " was not written");
    }
    int status = validationStatus(ctx);
    if (status != 0)
        return status; // a picture made with validation errors is not trusted: nothing written
    writePng(c.outFile, picture.width, picture.height, picture.rgba);
    std::cout << c.outFile << "\n";
    for (const std::string& line : loaded)
        std::cout << line << "\n";
    if (!picture.hairCounts.empty())
        std::cout << picture.hairCounts << "\n";
    if (picture.raster.capacity > 0) {
        std::cout << describeRasterStats(picture.raster) << "\n";
        if (picture.raster.overflow > 0) // (drawn again with the pieces it needed: only past kRasterMaxPieces)
            std::cerr << "wisp: warning: the frame needed " << picture.raster.pieces
                      << " pieces of the compute path's fragment buffer, more than the " << gpu::kRasterMaxPieces
                      << " a frame records: " << picture.raster.overflow << " of " << picture.raster.fragments
                      << " hair fragments were not drawn; raise fragment_budget, or lower the resolution or "
                         "strands_per_guide\n";
    }
    if (picture.oit.capacity > 0) {
        std::cout << "oit: " << picture.oit.fragments << " hair fragments, pool of " << picture.oit.capacity << "\n";
        if (picture.oit.overflow > 0)
            std::cerr << "wisp: warning: " << oitOverflowAdvice(picture.oit, settings.width, settings.height) << "\n";
    }
    return 0;
}

} // namespace

CommandRun addRenderCommand(CLI::App& app, const GlobalOptions& global)
{
    auto c = std::make_shared<RenderCommand>();
    CLI::App* cmd = app.add_subcommand(
        "render", "render one frame offscreen into a PNG: the head and its simulated hair, shaded and shadowed");
    c->command = cmd;
    c->out = cmd->add_option("--out", c->outFile,
                             "output PNG file (its folder must exist); with --reference also .exr: linear radiance "
                             "before exposure and tone mapping, coverage as alpha");
    cmd->add_option(
           "--profile", c->profileFrames,
           "time this many frames (physics and every pass, after --warmup frames) and print per-pass GPU ms as "
           "JSON, instead of writing a picture")
        ->check(wholeWithin(1, 100000));
    cmd->add_option("--warmup", c->profileWarmup, "frames before timing with --profile")
        ->check(wholeWithin(0, 100000))
        ->capture_default_str();
    cmd->add_flag("--still", c->still,
                  "with --profile: the timed frames take no simulation steps (the hair holds where the "
                  "warm-up left it); against a profile without it, what the physics costs a frame");
    cmd->add_option("--frames", c->frames, "simulated frames before the picture (each 1/fps seconds of fixed steps)")
        ->check(wholeWithin(0, 100000))
        ->capture_default_str();
    cmd->add_option("--fps", c->fps, "simulated frames per second")->check(within(1.0, 1000.0))->capture_default_str();
    cmd->add_flag("--reference", c->reference,
                  "path-trace the frame instead (the same scene, camera, lights and look; the exact fibre BSDF of "
                  "Chiang et al. 2016): the reference a real-time picture is compared with");
    c->spp = cmd->add_option("--spp", c->referenceOptions.samples, "with --reference: samples per pixel")
                 ->check(wholeWithin(1, 1000000))
                 ->capture_default_str();
    c->seed = cmd->add_option("--sample-seed", c->referenceOptions.seed,
                              "with --reference: the random sequence (the same seed, the same picture)")
                  ->check(wholeWithin(0, 4294967295.0))
                  ->capture_default_str();
    c->bounces = cmd->add_option("--bounces", c->referenceOptions.maxBounces,
                                 "with --reference: the most scattering events of a path (Russian roulette ends "
                                 "most paths sooner)")
                     ->check(wholeWithin(1, 1000))
                     ->capture_default_str();
    c->shared = std::make_unique<SessionCommandLine>(cmd, SessionCommandLine::Uses{});
    return [c, &global] { return c->command->parsed() ? run(global, *c) : -1; };
}

} // namespace wisp
