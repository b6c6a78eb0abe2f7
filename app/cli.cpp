// app/cli.cpp: subcommands render, view, info and inspect, their options and ranges, and the
// error-to-exit-status policy (core/error.h: bad input 2, a lost device 3, anything else 1).
#include "app/cli.h"

#include "app/bsdf_command.h"
#include "app/headless.h"
#include "app/image_io.h"
#include "app/record.h"
#include "app/scene.h"
#include "app/session_options.h"
#include "app/settings_table.h"
#include "app/sweep.h"
#include "app/workload.h"
#include "app/simulate.h"
#include "app/viewer.h"
#include "app/window.h"
#include "renderer/hair_pass.h"
#include "core/error.h"
#include "physics/hair_scene.h"
#include "assets/head.h"
#include "gpu/check.h"
#include "gpu/context.h"

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <iostream>
#include <map>
#include <optional>
#include <sstream>

namespace wisp {

namespace {

struct GlobalOptions {
    bool validation = false;
    bool syncValidation = false;
    std::string gpu;
};

vk::ContextOptions contextOptions(const GlobalOptions& g)
{
    return {.validation = g.validation || g.syncValidation,
            .synchronizationValidation = g.syncValidation,
            .gpu = g.gpu,
            .instanceExtensions = {},
            .presentation = false};
}

// With validation on, any message is a bug: report it as a failure of the run.
int validationStatus(const vk::Context& ctx)
{
    uint32_t n = ctx.validationMessages();
    if (n == 0)
        return 0;
    std::fprintf(stderr, "wisp: %u Vulkan validation message%s (printed above)\n", n, n == 1 ? "" : "s");
    return kExitInternalError;
}

// A closed range for a floating-point option. CLI::Range lets "nan" through (every comparison with
// NaN is false); this one asks for lo <= value <= hi, which NaN and the infinities fail.
CLI::Validator within(double lo, double hi)
{
    std::ostringstream text;
    text << "in [" << lo << " - " << hi << "]";
    return CLI::Validator(
        [lo, hi](std::string& input) {
            double value = 0.0;
            if (!CLI::detail::lexical_cast(input, value) || !(value >= lo && value <= hi)) {
                std::ostringstream why;
                why << "Value " << input << " not in range " << lo << " to " << hi;
                return why.str();
            }
            return std::string();
        },
        text.str());
}

// The head and the hair `o` describes, built once the workload is checked (counts that must fit 32
// bits, GPU memory against the device it will run on): before guides are grown, and for hair files
// once they are loaded (only then is their strand count known). Nothing is allocated on the device
// yet. `render`: the drawing's settings (null: simulate).
HairScene buildCheckedScene(const GlobalOptions& g, const SessionOptions& o, const RenderSettings* render,
                            bool window = false)
{
    const HairSource& h = o.source;
    const GrowthSettings& growth = o.settings.growth;
    auto check = [&](uint64_t guides) {
        Workload w{.guides = guides, .verticesPerStrand = growth.verticesPerStrand, .sim = o.settings.sim, .render = render};
        checkCounts(w);
        std::vector<vk::DeviceReport> devices = vk::enumerateDevices();
        checkWorkload(w, vk::selectDevice(devices, g.gpu, window));
    };
    if (h.noHair || h.hairFiles.empty())
        check(h.noHair ? 0 : growth.guides);
    HairScene scene = h.buildScene(o.settings);
    if (!h.noHair && !h.hairFiles.empty())
        check(scene.strands.strandCount());
    return scene;
}

// Every point of a sweep's grid of grown hair, checked before the first one runs.
void checkSweepGrid(const vk::DeviceReport& device, const std::vector<SweepAxis>& axes, const SessionOptions& base)
{
    if (!base.source.hairFiles.empty())
        return;  // loaded per point; the solver checks its own memory
    std::vector<size_t> at(axes.size(), 0);
    for (size_t axis = 0; axis < axes.size();) {
        Settings s = base.settings;
        for (size_t a = 0; a < axes.size(); ++a)
            applySetting(s, axes[a].name + "=" + axes[a].values[at[a]]);
        checkWorkload({.guides = s.growth.guides, .verticesPerStrand = s.growth.verticesPerStrand, .sim = s.sim,
                       .render = &s.render},
                      device);
        for (axis = 0; axis < axes.size() && ++at[axis] == axes[axis].values.size(); ++axis)
            at[axis] = 0;  // the next point, odometer-wise
    }
    if (axes.empty())
        checkWorkload({.guides = base.settings.growth.guides, .verticesPerStrand = base.settings.growth.verticesPerStrand,
                       .sim = base.settings.sim, .render = &base.settings.render},
                      device);
}

int runInfo(bool json)
{
    std::vector<vk::DeviceReport> devices = vk::enumerateDevices();
    if (devices.empty())
        throw UserError("no Vulkan device found: install a GPU driver, or Mesa's CPU driver "
                        "(Debian package mesa-vulkan-drivers), and check VK_ICD_FILENAMES");
    if (json) {
        nlohmann::json out = nlohmann::json::array();
        for (const vk::DeviceReport& d : devices)
            out.push_back({{"index", d.index},
                           {"name", d.name},
                           {"type", d.typeName()},
                           {"api", std::to_string(VK_API_VERSION_MAJOR(d.apiVersion)) + "." +
                                       std::to_string(VK_API_VERSION_MINOR(d.apiVersion)) + "." +
                                       std::to_string(VK_API_VERSION_PATCH(d.apiVersion))},
                           {"driver", d.driverName + " " + d.driverInfo},
                           {"usable", d.missing(false).empty()},
                           {"missing", d.missing(false)},
                           {"tessellation_shader", d.tessellationShader},
                           {"geometry_shader", d.geometryShader},
                           {"fragment_stores_and_atomics", d.fragmentStoresAndAtomics},
                           {"timestamps", d.timestamps},
                           {"timestamp_valid_bits", d.timestampValidBits},
                           {"timestamp_period_ns", d.timestampPeriodNs},
                           {"pipeline_statistics", d.pipelineStatisticsQuery},
                           {"float_atomic_add", d.floatAtomicAdd},
                           {"int64_atomics", d.int64Atomics},
                           {"push_descriptor", d.pushDescriptor},
                           {"max_tessellation_generation_level", d.maxTessellationGenerationLevel},
                           {"max_tessellation_patch_size", d.maxTessellationPatchSize},
                           {"device_local_bytes", d.deviceLocalBytes}});
        std::cout << out.dump(2) << "\n";
        return 0;
    }
    auto yes = [](bool b) { return b ? "yes" : "no"; };
    for (const vk::DeviceReport& d : devices) {
        std::vector<std::string> missing = d.missing(false);
        std::cout << "device " << d.index << ": " << d.name << " (" << d.typeName() << ", Vulkan "
                  << VK_API_VERSION_MAJOR(d.apiVersion) << "." << VK_API_VERSION_MINOR(d.apiVersion) << "."
                  << VK_API_VERSION_PATCH(d.apiVersion) << ", " << d.driverName << " " << d.driverInfo << ")\n"
                  << "  usable by wisp:               " << (missing.empty() ? "yes" : "NO") << "\n";
        for (const std::string& m : missing)
            std::cout << "    missing: " << m << "\n";
        std::cout << "  tessellation shader:          " << yes(d.tessellationShader) << " (max level "
                  << d.maxTessellationGenerationLevel << ", max patch size " << d.maxTessellationPatchSize << ")\n"
                  << "  geometry shader:              " << yes(d.geometryShader) << " (max output vertices "
                  << d.maxGeometryOutputVertices << ")\n"
                  << "  fragment stores and atomics:  " << yes(d.fragmentStoresAndAtomics) << "\n"
                  << "  float atomic add (buffers):   " << yes(d.floatAtomicAdd) << "\n"
                  << "  64-bit integer atomics:       " << yes(d.int64Atomics)
                  << " (the deterministic fixed-point hair grid" << (d.int64Atomics ? ")" : "; float atomics instead)") << "\n"
                  << "  timestamps:                   " << yes(d.timestamps) << " (" << d.timestampValidBits
                  << " valid bits, " << d.timestampPeriodNs << " ns per tick)\n"
                  << "  pipeline statistics:          " << yes(d.pipelineStatisticsQuery) << "\n"
                  << "  push descriptors:             " << yes(d.pushDescriptor) << "\n"
                  << "  device-local memory:          " << d.deviceLocalBytes / (1024 * 1024) << " MiB\n";
    }
    return 0;
}

int runInspect(const std::string& file)
{
    std::string ext = std::filesystem::path(file).extension().string();
    if (ext == ".tfx" || ext == ".hair") {
        std::cout << describeHairAsset(loadHairAsset(file)).dump() << "\n";
        return 0;
    }
    Mesh mesh = loadMesh(file);
    Bounds b = mesh.bounds();
    nlohmann::json out = {{"kind", "mesh"},
                          {"vertices", mesh.sourceVertices},
                          {"triangles", mesh.triangleCount()},
                          {"bbox", {{b.min.x, b.min.y, b.min.z}, {b.max.x, b.max.y, b.max.z}}}};
    std::cout << out.dump() << "\n";
    return 0;
}

struct RenderOptions {
    std::string out;
    SessionOptions session;
    uint32_t frames = 0;
    float fps = 30.0f;
    uint32_t profileFrames = 0;  // > 0: time this many frames (after profileWarmup) instead of writing a picture
    uint32_t profileWarmup = 60;
};

int runRenderProfile(const GlobalOptions& g, RenderOptions& o)
{
    const RenderSettings& settings = o.session.settings.render;
    o.session.source.noHair = false;
    HairScene scene = buildCheckedScene(g, o.session, &settings);
    vk::Context ctx(contextOptions(g));
    HairSession session(ctx, std::move(scene), o.session.settings.sim, o.session.timeline, o.session.source);
    OitStats oit;
    std::vector<PassTiming> timings = profileFrames(ctx, session, settings, o.fps, o.profileWarmup, o.profileFrames, &oit);
    HairDrawCounts c = hairDrawCounts(uint32_t(session.scene().strands.strandCount()), settings.strands);
    nlohmann::json out = {{"device", ctx.report().name},
                          {"width", settings.width},
                          {"height", settings.height},
                          {"guides", c.guides},
                          {"vertices_per_strand", session.scene().strands.verticesPerStrand},
                          {"strands_per_guide", c.strandsPerGuide},
                          {"divisions", c.divisions},
                          {"strands", c.strands()},
                          {"segments", c.segments()},
                          {"samples", settings.samples},
                          {"warmup_frames", o.profileWarmup},
                          {"timed_frames", o.profileFrames},
                          {"transparency", settings.transparency.mode == Transparency::Oit ? "oit" : "msaa"},
                          {"oit_fragments", oit.fragments},
                          {"oit_overflow", oit.overflow},
                          {"oit_capacity", oit.capacity},
                          {"shadow_size", settings.shadows.mapSize},
                          {"settings", settingsJson(o.session.settings)}};
    for (const PassTiming& t : timings)
        out["ms"][t.name] = {{"median", t.medianMs}, {"p95", t.p95Ms}};
    std::cout << out.dump() << "\n";
    return validationStatus(ctx);
}

int runRender(const GlobalOptions& g, RenderOptions& o)
{
    if (o.profileFrames > 0)
        return runRenderProfile(g, o);
    checkPngOutput(o.out);  // fail before any GPU work
    const RenderSettings& settings = o.session.settings.render;
    HairScene scene = buildCheckedScene(g, o.session, &settings);
    vk::Context ctx(contextOptions(g));
    Picture picture;
    try {
        HairSession session(ctx, std::move(scene), o.session.settings.sim, o.session.timeline, o.session.source);
        picture = renderPicture(ctx, session, settings, o.frames, o.fps);
    } catch (const vk::DeviceLost& e) {
        throw vk::DeviceLost(e.what() + std::string("; ") + o.out + " was not written");
    }
    int status = validationStatus(ctx);
    if (status != 0)
        return status;  // a picture made with validation errors is not trusted: nothing written
    writePng(o.out, picture.width, picture.height, picture.rgba);
    std::cout << o.out << "\n";
    if (!picture.hairCounts.empty())
        std::cout << picture.hairCounts << "\n";
    if (picture.oit.capacity > 0) {
        std::cout << "oit: " << picture.oit.fragments << " hair fragments, pool of " << picture.oit.capacity << "\n";
        if (picture.oit.overflow > 0)
            std::cerr << "wisp: warning: the OIT pool was full: " << picture.oit.overflow << " of "
                      << picture.oit.fragments
                      << " hair fragments were dropped; raise oit_nodes_per_pixel (--set oit_nodes_per_pixel=N)\n";
    }
    return 0;
}

}  // namespace

int runCli(int argc, char** argv)
{
    CLI::App app{"Wisp: real-time hair simulation and rendering (Vulkan).", "wisp"};
    app.require_subcommand(1);
    app.fallthrough();
    GlobalOptions g;
    app.add_flag("--validation", g.validation, "enable the Vulkan validation layer; any message fails the run");
    app.add_flag("--sync-validation", g.syncValidation, "also the validation layer's synchronization checks");
    app.add_option("--gpu", g.gpu, "Vulkan device: an index or part of a name from 'wisp info' (default: best)")
        ->check(CLI::Validator(
            [](std::string& v) {  // an index past what std::stoul reads would be an internal error later
                bool digits = !v.empty() && v.find_first_not_of("0123456789") == std::string::npos;
                return digits && v.size() > 6 ? "device index " + v + " is out of range (see 'wisp info')" : std::string();
            },
            "INDEX|NAME"));

    RenderOptions ro;
    CLI::App* render = app.add_subcommand("render", "render one frame offscreen into a PNG: the head and its simulated hair, shaded and shadowed");
    CLI::Option* outOption = render->add_option("--out", ro.out, "output PNG file (its folder must exist)");
    render->add_option("--profile", ro.profileFrames,
                       "time this many frames (physics and every pass, after --warmup frames) and print per-pass GPU ms as JSON, "
                       "instead of writing a picture")
        ->check(CLI::Range(1u, 100000u));
    render->add_option("--warmup", ro.profileWarmup, "frames before timing with --profile")->check(CLI::Range(0u, 100000u))->capture_default_str();
    render->add_option("--frames", ro.frames, "simulated frames before the picture (each 1/fps seconds of fixed steps)")
        ->check(CLI::Range(0u, 100000u))
        ->capture_default_str();
    render->add_option("--fps", ro.fps, "simulated frames per second")->check(within(1.0, 1000.0))->capture_default_str();
    SessionCommandLine renderSession(render, {});

    WindowOptions windowOptions;
    CLI::App* view = app.add_subcommand(
        "view", "the interactive window: the hair simulated live, a panel of settings, counts and GPU times, keys for the sphere, "
                "the light, the head and the wind (listed by 'wisp view --help')");
    view->footer("Keys and mouse: " + viewerHelp());
    SessionCommandLine viewSession(view, {});
    view->add_option("--frames", windowOptions.maxFrames, "close after this many frames (0 = run until closed)")
        ->check(CLI::NonNegativeNumber);
    view->add_option("--screenshot", windowOptions.screenshot, "write the last frame to this PNG when closing");
    view->add_flag("--screenshot-panel", windowOptions.screenshotPanel, "the --screenshot includes the ImGui panel");
    view->add_option("--script", windowOptions.script,
                     "replay timed input events from this file: lines 'FRAME press|release|tap KEY' or "
                     "'FRAME drag-sphere|drag-light|orbit DX DY' or 'FRAME set NAME=VALUE' (a setting, as typed into the "
                     "panel) (KEY: left right up down pageup pagedown j l i k a d w plus minus space n r p f5 o h t f2 f3 escape)")
        ->check(CLI::ExistingFile);

    SimulateOptions sim;
    CLI::App* simulate = app.add_subcommand("simulate", "physics only, headless: quality metrics as text or JSON");
    simulate->add_option("--steps", sim.steps, "fixed simulation steps to run")->check(CLI::Range(1u, 10000000u))->capture_default_str();
    simulate->add_flag("--json", sim.json, "print one JSON object");
    simulate->add_option("--sample-every", sim.sampleEvery, "steps between samples of the kinetic energy (each reads the state back)")
        ->check(CLI::Range(1u, 10000000u))
        ->capture_default_str();
    simulate->add_flag("--profile", sim.profile,
                       "time each kernel: --warmup steps, then --steps steps each timed on its own (median and p95)");
    simulate->add_option("--warmup", sim.warmup, "steps before timing with --profile")->check(CLI::Range(0u, 100000u))->capture_default_str();
    SessionCommandLine simulateSession(simulate, {.scene = true, .noHair = false, .draws = false});

    RecordOptions rec;
    std::string recOut, recVideo;
    CLI::App* record = app.add_subcommand(
        "record", "render a run frame by frame into a folder of PNGs (+ a video through ffmpeg, + a contact sheet); reproducible");
    record->add_option("--out", recOut, "output folder for frame_00000.png ... and contact_sheet.png (created; its parent must exist)")
        ->required();
    record->add_option("--video", recVideo, "also encode the frames into this video file (H.264 through ffmpeg)");
    record->add_option("--frames", rec.frames, "frames to record (with --scene, by default as many as the scene lasts)")
        ->check(CLI::Range(1u, 1000000u))
        ->capture_default_str();
    record->add_option("--fps", rec.fps, "frames per simulated second (each frame is round(step_hz / fps) fixed steps)")
        ->check(within(1.0, 1000.0))
        ->capture_default_str();
    SessionCommandLine recordSession(record, {});

    SweepOptions sweepOptions;
    std::string sweepOut;
    std::vector<std::string> sweepVaries;
    CLI::App* sweep = app.add_subcommand(
        "sweep", "per-pass GPU timings over a grid of settings: results.csv, fps.png and passes.png (python3-matplotlib)");
    sweep->add_option("--out", sweepOut, "output folder (created)")->required();
    sweep->add_option("--vary", sweepVaries, "NAME=V1,V2,... for a setting from 'wisp settings'; several make a grid")->required();
    sweep->add_option("--warmup", sweepOptions.warmup, "frames before timing each point")->check(CLI::Range(0u, 100000u))->capture_default_str();
    sweep->add_option("--frames", sweepOptions.frames, "frames timed at each point (median and p95)")
        ->check(CLI::Range(1u, 100000u))
        ->capture_default_str();
    SessionCommandLine sweepSession(sweep, {.scene = false, .noHair = false, .draws = true});

    std::function<int()> runBsdf = addBsdfCommand(app);

    bool settingsJsonOutput = false;
    CLI::App* settingsCmd = app.add_subcommand(
        "settings", "list every setting --set takes: names, units, allowed values, defaults, what a change needs, options");
    settingsCmd->add_flag("--json", settingsJsonOutput, "print JSON instead of text");

    bool infoJson = false;
    CLI::App* info = app.add_subcommand("info", "list Vulkan devices and the features Wisp uses");
    info->add_flag("--json", infoJson, "print JSON instead of text");

    std::string inspectFile;
    CLI::App* inspect = app.add_subcommand("inspect", "print what a hair or mesh file holds, as one JSON object");
    inspect->add_option("file", inspectFile,
                        "a hair file (.tfx: TressFX 2/3/4, .hair: cyHair) or a mesh (.obj through tinyobjloader, others through assimp)")
        ->required();

    // CLI11 reports a mistyped command only as "a subcommand is required": name it instead.
    for (int i = 1; i < argc; ++i) {
        std::string arg = argv[i];
        if (arg == "--gpu") {
            ++i;
            continue;
        }
        if (arg.starts_with("-"))
            continue;
        bool known = false;
        std::string names;
        for (const CLI::App* sub : app.get_subcommands([](const CLI::App*) { return true; })) {
            known = known || sub->get_name() == arg;
            names += (names.empty() ? "" : ", ") + sub->get_name();
        }
        if (!known) {
            std::fprintf(stderr, "wisp: unknown command '%s' (commands: %s; see 'wisp --help')\n", arg.c_str(),
                         names.c_str());
            return kExitUserError;
        }
        break;
    }

    try {
        app.parse(argc, argv);
    } catch (const CLI::CallForHelp& e) {
        return app.exit(e);
    } catch (const CLI::CallForAllHelp& e) {
        return app.exit(e);
    } catch (const CLI::ParseError& e) {
        std::fprintf(stderr, "wisp: %s (see 'wisp --help')\n", e.what());
        return kExitUserError;
    }

    try {
        if (int status = runBsdf(); status >= 0)
            return status;
        if (*record) {
            SessionOptions session = recordSession.resolve();
            rec.outDir = recOut;
            rec.video = recVideo;
            rec.settings = session.settings.render;
            if (session.scene && record->get_option("--frames")->count() == 0 && session.sceneLength() > 0.0)
                rec.frames = std::max(1u, uint32_t(std::ceil(session.sceneLength() * double(rec.fps) - 1e-6)));
            checkRecordOutputs(rec);  // before any loading
            HairScene scene = buildCheckedScene(g, session, &rec.settings);
            vk::Context ctx(contextOptions(g));
            HairSession hair(ctx, std::move(scene), session.settings.sim, session.timeline, session.source);
            return runRecord(ctx, hair, rec);
        }
        if (*sweep) {
            SessionOptions base = sweepSession.resolve();
            for (const std::string& v : sweepVaries)
                sweepOptions.axes.push_back(parseSweepAxis(v, base.settings));
            sweepOptions.outDir = sweepOut;
            vk::Context ctx(contextOptions(g));
            checkSweepGrid(ctx.report(), sweepOptions.axes, base);
            return runSweep(ctx, sweepOptions, base);
        }
        if (*settingsCmd) {
            if (settingsJsonOutput)
                std::cout << settingsTableJson().dump(2) << "\n";
            else
                std::cout << settingsTable();
            return 0;
        }
        if (*render) {
            if (ro.profileFrames == 0 && !*outOption)
                throw UserError("render: --out FILE.png is required (or --profile N to time frames)");
            ro.session = renderSession.resolve();
            return runRender(g, ro);
        }
        if (*view) {
            requireDisplay();  // before any loading
            SessionOptions session = viewSession.resolve();
            windowOptions.context = contextOptions(g);
            // The window starts from the scene's state at time 0 (its sphere, wind and light).
            SceneState initial = session.timeline.at(0.0);
            windowOptions.scene = buildCheckedScene(g, session, &session.settings.render, /*window=*/true);
            windowOptions.timeline = session.timeline;
            windowOptions.sceneLength = session.sceneLength();
            windowOptions.source = session.source;
            windowOptions.settings = session.settings;
            windowOptions.settings.sim.wind = initial.wind;
            windowOptions.sphere = initial.sphere;
            windowOptions.settings.render.light = initial.light;
            return runWindow(std::move(windowOptions));
        }
        if (*simulate) {
            SessionOptions session = simulateSession.resolve();
            session.source.noHair = false;
            sim.settings = session.settings;
            HairScene scene = buildCheckedScene(g, session, nullptr);
            vk::Context ctx(contextOptions(g));
            HairSession hair(ctx, std::move(scene), session.settings.sim, session.timeline, session.source);
            return runSimulate(ctx, hair, sim);
        }
        if (*info)
            return runInfo(infoJson);
        if (*inspect)
            return runInspect(inspectFile);
    } catch (const UserError& e) {
        std::fprintf(stderr, "wisp: %s\n", e.what());
        return kExitUserError;
    } catch (const vk::DeviceLost& e) {
        std::string command = app.get_subcommands().empty() ? "" : " " + app.get_subcommands().front()->get_name();
        std::fprintf(stderr, "wisp: the GPU device was lost (VK_ERROR_DEVICE_LOST) during wisp%s: %s\n",
                     command.c_str(), e.what());
        return kExitDeviceLost;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "wisp: internal error: %s\n", e.what());
        return kExitInternalError;
    }
    return kExitInternalError;
}

}  // namespace wisp
