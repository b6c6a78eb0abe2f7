// app/cli.cpp: subcommands render, view, info and inspect, their options and ranges, and the
// error-to-exit-status policy (core/error.h: bad input 2, a lost device 3, anything else 1).
#include "app/cli.h"

#include "app/bsdf_command.h"
#include "app/headless.h"
#include "app/image_io.h"
#include "app/inspect.h"
#include "app/hair_options.h"
#include "app/record.h"
#include "app/scene.h"
#include "app/settings_registry.h"
#include "app/sweep.h"
#include "app/workload.h"
#include "app/simulate.h"
#include "app/viewer.h"
#include "app/window.h"
#include "renderer/hair_pass.h"
#include "renderer/renderer.h"
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

std::filesystem::path headPathOrDefault(const std::string& head)
{
    return head.empty() ? defaultHeadPath() : std::filesystem::path(head);
}

// The head and the hair the options describe (none with `noHair`), built once the workload is
// checked (counts that must fit 32 bits, GPU memory against the device it will run on): before
// guides are grown, and for hair files once they are loaded (only then is their strand count
// known). Nothing is allocated on the device yet.
HairScene buildCheckedScene(const GlobalOptions& g, const HairOptions& h, const std::filesystem::path& head,
                            const RenderSettings* render, bool noHair, bool window = false)
{
    auto check = [&](uint64_t guides) {
        Workload w{.guides = guides, .verticesPerStrand = h.growth.verticesPerStrand, .sim = h.sim, .render = render};
        checkCounts(w);
        std::vector<vk::DeviceReport> devices = vk::enumerateDevices();
        checkWorkload(w, vk::selectDevice(devices, g.gpu, window));
    };
    if (noHair || h.hairFiles.empty())
        check(noHair ? 0 : h.growth.guides);
    if (noHair) {
        HairScene scene;
        scene.head = loadHead(head);
        return scene;
    }
    HairScene scene = h.buildScene(head);
    if (!h.hairFiles.empty())
        check(scene.strands.strandCount());
    for (const std::string& w : scene.warnings)
        std::fprintf(stderr, "wisp: warning: %s\n", w.c_str());
    return scene;
}

// Every point of a sweep's grid of grown hair, checked before the first one runs.
void checkSweepGrid(const vk::DeviceReport& device, const std::vector<SweepAxis>& axes, const HairOptions& hair,
                    const RenderSettings& render)
{
    if (!hair.hairFiles.empty())
        return;  // loaded per point; the solver checks its own memory
    std::vector<size_t> at(axes.size(), 0);
    for (size_t axis = 0; axis < axes.size();) {
        HairOptions h = hair;
        RenderSettings r = render;
        for (size_t a = 0; a < axes.size(); ++a)
            applySetting({&h.growth, &h.sim, &r}, axes[a].name + "=" + axes[a].values[at[a]]);
        checkWorkload({.guides = h.growth.guides, .verticesPerStrand = h.growth.verticesPerStrand, .sim = h.sim, .render = &r},
                      device);
        for (axis = 0; axis < axes.size() && ++at[axis] == axes[axis].values.size(); ++axis)
            at[axis] = 0;  // the next point, odometer-wise
    }
    if (axes.empty())
        checkWorkload({.guides = hair.growth.guides, .verticesPerStrand = hair.growth.verticesPerStrand, .sim = hair.sim,
                       .render = &render},
                      device);
}

void addImageSize(CLI::App* cmd, RenderSettings& s)
{
    auto range = CLI::Range(static_cast<uint32_t>(kImageSizeRange.min), static_cast<uint32_t>(kImageSizeRange.max));
    cmd->add_option("--width", s.width, "image width in pixels")->check(range)->capture_default_str();
    cmd->add_option("--height", s.height, "image height in pixels")->check(range)->capture_default_str();
}

void addLookOptions(CLI::App* cmd, RenderSettings& s)
{
    cmd->add_option("--samples", s.samples, "MSAA samples for meshes (1, 2, 4 or 8)")
        ->check(CLI::IsMember({1u, 2u, 4u, 8u}))
        ->capture_default_str();
    cmd->add_option("--light-azimuth", s.light.azimuthDeg, "key light angle around the up axis, degrees (0 = front)")
        ->check(within(-360.0, 360.0))
        ->capture_default_str();
    cmd->add_option("--light-elevation", s.light.elevationDeg, "key light angle above the horizon, degrees")
        ->check(within(kLightElevationRange.min, kLightElevationRange.max))
        ->capture_default_str();
    cmd->add_option("--light-intensity", s.light.intensity, "key light strength")
        ->check(within(kLightIntensityRange.min, kLightIntensityRange.max))
        ->capture_default_str();
}

void addHairOptions(CLI::App* cmd, HairOptions& h)
{
    cmd->add_option("--guides", h.growth.guides, "guide strands to grow on the scalp")
        ->check(CLI::Range(uint32_t(kGuidesRange.min), uint32_t(kGuidesRange.max)))
        ->capture_default_str();
    cmd->add_option("--vertices", h.growth.verticesPerStrand, "vertices per guide strand")
        ->check(CLI::Range(kMinVerticesPerStrand, kMaxVerticesPerStrand))
        ->capture_default_str();
    cmd->add_option("--hair-length", h.growth.lengthMetres, "mean grown strand length, metres (scaled to the head's units)")
        ->check(within(kHairLengthRange.min, kHairLengthRange.max))
        ->capture_default_str();
    cmd->add_option("--length-variation", h.growth.lengthVariation, "relative spread of grown strand lengths")
        ->check(within(kLengthVariationRange.min, kLengthVariationRange.max))
        ->capture_default_str();
    cmd->add_option("--curl", h.growth.curlRadiusMetres, "curl radius of grown strands, metres (0 = straight)")
        ->check(within(kCurlRange.min, kCurlRange.max))
        ->capture_default_str();
    cmd->add_flag("--poisson", h.growth.poissonDisk, "blue-noise (Poisson-disk) roots instead of area-weighted random");
    cmd->add_option("--seed", h.growth.seed, "seed for root sampling and strand variation")->capture_default_str();
    cmd->add_option("--substeps", h.sim.substeps, "integrate/FTL substeps per step")->check(CLI::Range(1u, 16u))->capture_default_str();
    cmd->add_option("--step-hz", h.sim.stepHz, "fixed simulation steps per simulated second")
        ->check(within(30.0, 1000.0))
        ->capture_default_str();
    cmd->add_option("--grid", h.sim.gridResolution, "hair-hair grid nodes per axis")->check(CLI::Range(8u, 256u))->capture_default_str();
    cmd->add_option("--friction", h.sim.gridFriction, "hair-hair friction (blend toward the grid velocity)")
        ->check(within(0.0, 1.0))
        ->capture_default_str();
    cmd->add_option("--grid-atomics", h.sim.gridAtomics,
                    "hair grid sums: fixed (64-bit fixed point, deterministic) or float (float atomics)")
        ->transform(CLI::CheckedTransformer(std::map<std::string, SimSettings::GridAtomics>{
            {"fixed", SimSettings::GridAtomics::Fixed}, {"float", SimSettings::GridAtomics::Float}}))
        ->capture_default_str();
    cmd->add_option("--repulsion", h.sim.gridRepulsion, "hair-hair repulsion along the density gradient (keeps volume; 0 = off)")
        ->check(within(kRepulsionRange.min, kRepulsionRange.max))
        ->capture_default_str();
    cmd->add_option("--hair", h.hairFiles,
                    "hair file to load instead of growing guides (TressFX .tfx 2/3/4, cyHair .hair); repeat for a groom in parts")
        ->check(CLI::ExistingFile);
    cmd->add_option("--hair-scale", h.hairScale, "scale loaded hair by this (default: automatic when units clearly differ)")
        ->check(within(kHairScaleRange.min, kHairScaleRange.max));
    cmd->add_option("--hair-offset", h.hairOffset, "move loaded hair by x,y,z (head units) after scaling")->delimiter(',')->expected(3);
    cmd->add_option("--hair-z-up", h.zUp, "loaded hair is z-up: turn it y-up (default: automatic, true for cyHair)");
    cmd->add_option("--hair-mirror-z", h.mirrorZ, "mirror loaded hair's z (default: automatic, true for TressFX 3)");
    cmd->add_option("--part", h.partOverrides,
                    "one part's parameters: PART:key=value,... with PART its index or file name, keys global, local, damping, drag");
    auto stiffness = within(kStiffnessRange.min, kStiffnessRange.max);
    cmd->add_option("--global-stiffness", h.globalStiffness, "pull toward the rest pose per step at the root, every part")
        ->check(stiffness);
    cmd->add_option("--local-stiffness", h.localStiffness, "pull of each segment toward its rest direction per step, every part")
        ->check(stiffness);
    cmd->add_option("--damping", h.damping, "FTL velocity correction s_damp (Muller 2012), every part")->check(stiffness);
    cmd->add_option("--drag", h.drag, "air drag, 1/s, every part")->check(within(kDragRange.min, kDragRange.max));
    cmd->add_option("--sphere", h.sphere, "collision sphere x,y,z,r in the head's units")->delimiter(',')->expected(4);
    cmd->add_option("--wind", h.wind, "wind x,y,z in m/s^2 (scaled to the head's units)")->delimiter(',')->expected(3);
}

void addSceneOption(CLI::App* cmd, std::string& file)
{
    cmd->add_option("--scene", file,
                    "scene file (.json, see scenes/): head, hair, colliders, settings, physics and keyframes over time; "
                    "options given on the command line override the scene's values (and replace the keys of --wind, "
                    "--sphere, --light-*)");
}

// The scene's keys over the command line's base (its sphere, wind and light). A channel the
// command line names explicitly (--wind, --sphere, --light-azimuth, ...) is the command line's
// value throughout: the scene's keys for it are dropped.
SceneTimeline commandTimeline(const std::optional<Scene>& scene, const CLI::App* cmd, const HairOptions& hair,
                              const LightSettings& light)
{
    SceneState base;
    base.sphere = hair.sphereOrNone();
    base.wind = hair.sim.wind;
    base.light = light;
    if (!scene)
        return SceneTimeline({}, SceneInterpolation::Smooth, base);
    auto given = [&](const char* name) {  // `simulate` has no light options
        const CLI::Option* option = cmd->get_option_no_throw(name);
        return option && option->count() > 0;
    };
    std::vector<SceneKey> keys = scene->keys;
    for (SceneKey& k : keys) {
        if (given("--wind"))
            k.wind.reset();
        if (given("--sphere"))
            k.sphere.reset();
        if (given("--light-azimuth"))
            k.lightAzimuthDeg.reset();
        if (given("--light-elevation"))
            k.lightElevationDeg.reset();
        if (given("--light-intensity"))
            k.lightIntensity.reset();
    }
    return SceneTimeline(keys, scene->interpolation, base, scene->loop ? scene->length() : 0.0);
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

struct RenderOptions {
    std::string out;
    std::string headFile;
    std::string sceneFile;
    SceneTimeline timeline;  // the scene's keys (or the command line's still sphere, wind and light)
    RenderSettings settings;
    HairOptions hair;
    bool noHair = false;
    uint32_t frames = 0;
    float fps = 30.0f;
    uint32_t profileFrames = 0;  // > 0: time this many frames (after profileWarmup) instead of writing a picture
    uint32_t profileWarmup = 60;
};

int runRenderProfile(const GlobalOptions& g, RenderOptions& o)
{
    o.hair.apply();
    HairScene scene = buildCheckedScene(g, o.hair, headPathOrDefault(o.headFile), &o.settings, /*noHair=*/false);
    vk::Context ctx(contextOptions(g));
    HairRun run{.scene = &scene, .sim = o.hair.sim, .frames = 0, .framesPerSecond = o.fps, .sphere = o.hair.sphereOrNone()};
    OitStats oit;
    RasterStats raster;
    std::vector<PassTiming> timings =
        profileFrames(ctx, scene.head, o.settings, run, o.profileWarmup, o.profileFrames, &oit, &raster);
    HairRaster path = resolveHairRaster(o.settings.hairRaster, ctx.report().type);
    HairDrawCounts c = hairDrawCounts(uint32_t(scene.strands.strandCount()), o.settings.strands);
    nlohmann::json out = {{"device", ctx.report().name},
                          {"width", o.settings.width},
                          {"height", o.settings.height},
                          {"guides", c.guides},
                          {"vertices_per_strand", scene.strands.verticesPerStrand},
                          {"strands_per_guide", c.strandsPerGuide},
                          {"divisions", c.divisions},
                          {"strands", c.strands()},
                          {"segments", c.segments()},
                          {"samples", o.settings.samples},
                          {"warmup_frames", o.profileWarmup},
                          {"timed_frames", o.profileFrames},
                          {"transparency", o.settings.transparency.mode == Transparency::Oit ? "oit" : "msaa"},
                          {"oit_fragments", oit.fragments},
                          {"oit_overflow", oit.overflow},
                          {"oit_capacity", oit.capacity},
                          {"shadow_size", o.settings.shadows.mapSize},
                          {"hair_raster_drawn", path == HairRaster::Compute ? "compute" : "graphics"}};
    if (path == HairRaster::Compute)
        out["raster"] = {{"segments", raster.segments}, {"fragments", raster.fragments}, {"capacity", raster.capacity},
                         {"overflow", raster.overflow}, {"max_pixel", raster.maxPixel}};
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
    o.hair.apply();
    std::filesystem::path headPath = headPathOrDefault(o.headFile);
    HairScene scene = buildCheckedScene(g, o.hair, headPath, &o.settings, o.noHair);
    vk::Context ctx(contextOptions(g));
    HairRun run{.scene = &scene, .sim = o.hair.sim, .frames = o.frames, .framesPerSecond = o.fps, .sphere = o.hair.sphereOrNone()};
    Picture picture;
    try {
        picture = renderPicture(ctx, scene.head, o.settings, o.noHair ? nullptr : &run, &o.timeline);
    } catch (const vk::DeviceLost& e) {
        throw vk::DeviceLost(e.what() + std::string("; ") + o.out + " was not written");
    }
    int status = validationStatus(ctx);
    if (status != 0)
        return status;  // a picture made with validation errors is not trusted: nothing written
    writePng(o.out, picture.width, picture.height, picture.rgba);
    std::cout << o.out << "\n";
    if (!o.noHair)
        for (const std::string& line : describeLoadedHair(scene))
            std::cout << line << "\n";
    if (!picture.hairCounts.empty())
        std::cout << picture.hairCounts << "\n";
    if (picture.raster.capacity > 0) {
        std::cout << "compute raster: " << picture.raster.segments << " segments on screen, " << picture.raster.fragments
                  << " hair fragments (at most " << picture.raster.maxPixel << " in a pixel), buffer of "
                  << picture.raster.capacity << "\n";
        if (picture.raster.overflow > 0)
            std::cerr << "wisp: warning: the compute path's fragment buffer was full: " << picture.raster.overflow << " of "
                      << picture.raster.fragments << " hair fragments were dropped ('" << ctx.report().name
                      << "' holds no larger buffer); lower the resolution or strands_per_guide\n";
    }
    if (picture.oit.capacity > 0) {
        std::cout << "oit: " << picture.oit.fragments << " hair fragments, pool of " << picture.oit.capacity << "\n";
        if (picture.oit.overflow > 0)
            std::cerr << "wisp: warning: " << oitOverflowAdvice(picture.oit, o.settings.width, o.settings.height) << "\n";
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
    render->add_option("--head", ro.headFile, "head: a description (.json) or a mesh (.obj, .fbx, .gltf, .ply, ...); default models/head.json");
    render->add_option("--frames", ro.frames, "simulated frames before the picture (each 1/fps seconds of fixed steps)")
        ->check(CLI::Range(0u, 100000u))
        ->capture_default_str();
    render->add_option("--fps", ro.fps, "simulated frames per second")->check(within(1.0, 1000.0))->capture_default_str();
    render->add_flag("--no-hair", ro.noHair, "draw the head alone");
    addSceneOption(render, ro.sceneFile);
    addImageSize(render, ro.settings);
    addLookOptions(render, ro.settings);
    addHairOptions(render, ro.hair);
    std::vector<std::string> renderSets;
    render->add_option("--set", renderSets, "NAME=VALUE for any setting in 'wisp settings' (repeatable)");

    WindowOptions windowOptions;
    HairOptions viewHair;
    std::string viewHead;
    bool viewNoHair = false;
    CLI::App* view = app.add_subcommand(
        "view", "the interactive window: the hair simulated live, a panel of settings, counts and GPU times, keys for the sphere, "
                "the light, the head and the wind (listed by 'wisp view --help')");
    view->footer("Keys and mouse: " + viewerHelp());
    view->add_option("--head", viewHead, "head description (.json) or mesh file; default models/head.json");
    view->add_flag("--no-hair", viewNoHair, "show the head alone");
    std::string viewScene;
    addSceneOption(view, viewScene);
    addHairOptions(view, viewHair);
    std::vector<std::string> viewSets;
    view->add_option("--set", viewSets, "NAME=VALUE for any setting in 'wisp settings' (repeatable)");
    addImageSize(view, windowOptions.settings);
    addLookOptions(view, windowOptions.settings);
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
    HairOptions simHair;
    CLI::App* simulate = app.add_subcommand("simulate", "physics only, headless: quality metrics as text or JSON");
    std::string simHead;
    simulate->add_option("--head", simHead, "head description (.json) or mesh file; default models/head.json");
    simulate->add_option("--steps", sim.steps, "fixed simulation steps to run")->check(CLI::Range(1u, 10000000u))->capture_default_str();
    simulate->add_flag("--json", sim.json, "print one JSON object");
    simulate->add_option("--sample-every", sim.sampleEvery, "steps between samples of the kinetic energy (each reads the state back)")
        ->check(CLI::Range(1u, 10000000u))
        ->capture_default_str();
    simulate->add_flag("--profile", sim.profile,
                       "time each kernel: --warmup steps, then --steps steps each timed on its own (median and p95)");
    simulate->add_option("--warmup", sim.warmup, "steps before timing with --profile")->check(CLI::Range(0u, 100000u))->capture_default_str();
    addHairOptions(simulate, simHair);
    std::string simScene;
    RenderSettings simSceneRender;  // a scene's render settings: read and checked, unused by the physics
    addSceneOption(simulate, simScene);
    std::vector<std::string> simulateSets;
    simulate->add_option("--set", simulateSets, "NAME=VALUE for any setting in 'wisp settings' (repeatable)");

    RecordOptions rec;
    HairOptions recHair;
    std::string recHead, recOut, recVideo, recScene;
    bool recNoHair = false;
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
    record->add_option("--head", recHead, "head description (.json) or mesh file; default models/head.json");
    record->add_flag("--no-hair", recNoHair, "record the head alone");
    addSceneOption(record, recScene);
    addImageSize(record, rec.settings);
    addLookOptions(record, rec.settings);
    addHairOptions(record, recHair);
    std::vector<std::string> recordSets;
    record->add_option("--set", recordSets, "NAME=VALUE for any setting in 'wisp settings' (repeatable)");

    SweepOptions sweepOptions;
    HairOptions sweepHair;
    RenderSettings sweepRender;
    std::string sweepOut, sweepHead;
    std::vector<std::string> sweepVaries, sweepSets;
    CLI::App* sweep = app.add_subcommand(
        "sweep", "per-pass GPU timings over a grid of settings: results.csv, fps.png and passes.png (python3-matplotlib)");
    sweep->add_option("--out", sweepOut, "output folder (created)")->required();
    sweep->add_option("--vary", sweepVaries, "NAME=V1,V2,... for a setting from 'wisp settings'; several make a grid")->required();
    sweep->add_option("--warmup", sweepOptions.warmup, "frames before timing each point")->check(CLI::Range(0u, 100000u))->capture_default_str();
    sweep->add_option("--frames", sweepOptions.frames, "frames timed at each point (median and p95)")
        ->check(CLI::Range(1u, 100000u))
        ->capture_default_str();
    sweep->add_option("--head", sweepHead, "head description (.json) or mesh file; default models/head.json");
    addImageSize(sweep, sweepRender);
    addHairOptions(sweep, sweepHair);
    sweep->add_option("--set", sweepSets, "NAME=VALUE every point starts from (repeatable)");

    std::function<int()> runBsdf = addBsdfCommand(app);

    CLI::App* settingsCmd = app.add_subcommand("settings", "list every setting --set takes: names, units, ranges and defaults");

    bool infoJson = false;
    CLI::App* info = app.add_subcommand("info", "list Vulkan devices and the features Wisp uses");
    info->add_flag("--json", infoJson, "print JSON instead of text");

    std::function<int()> runInspect = addInspectCommand(app);

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
        if (int status = runInspect(); status >= 0)
            return status;
        // A scene first, then the command line over it: the scene's values go into the variables
        // the options write, and the command line is parsed again, so what it names wins.
        std::optional<Scene> sceneFromFile;
        CLI::App* sceneCommand = *render ? render : *record ? record : *view ? view : *simulate ? simulate : nullptr;
        std::string sceneFile = *render ? ro.sceneFile : *record ? recScene : *view ? viewScene : *simulate ? simScene : "";
        if (sceneCommand && !sceneFile.empty()) {
            if (*view)
                requireDisplay();  // before any loading
            sceneFromFile = loadScene(sceneFile);
            const Scene& s = *sceneFromFile;
            if (*render)
                applyScene(s, sceneFile, {&ro.hair, &ro.settings, &ro.headFile});
            else if (*record)
                applyScene(s, sceneFile, {&recHair, &rec.settings, &recHead});
            else if (*simulate)
                applyScene(s, sceneFile, {&simHair, &simSceneRender, &simHead});
            else
                applyScene(s, sceneFile, {&viewHair, &windowOptions.settings, &viewHead});
            try {
                app.parse(argc, argv);
            } catch (const CLI::ParseError& e) {
                throw UserError(std::string(e.what()) + " (see 'wisp --help')");
            }
            if (sceneCommand->get_option("--hair")->count() > 0) {  // other files: the scene's per-file values do not apply
                ro.hair.scenePartOverrides.clear();
                recHair.scenePartOverrides.clear();
                viewHair.scenePartOverrides.clear();
                simHair.scenePartOverrides.clear();
            }
        }
        if (*record) {
            for (const std::string& a : recordSets)
                applySetting({&recHair.growth, &recHair.sim, &rec.settings}, a);
            recHair.apply();
            rec.outDir = recOut;
            rec.video = recVideo;
            rec.sim = recHair.sim;
            rec.timeline = commandTimeline(sceneFromFile, record, recHair, rec.settings.light);
            if (sceneFromFile && record->get_option("--frames")->count() == 0 && sceneFromFile->length() > 0.0)
                rec.frames = std::max(1u, uint32_t(std::ceil(sceneFromFile->length() * double(rec.fps) - 1e-6)));
            checkRecordOutputs(rec);  // before any loading
            HairScene scene = buildCheckedScene(g, recHair, headPathOrDefault(recHead), &rec.settings, recNoHair);
            vk::Context ctx(contextOptions(g));
            return runRecord(ctx, scene, rec);
        }
        if (*sweep) {
            for (const std::string& a : sweepSets)
                applySetting({&sweepHair.growth, &sweepHair.sim, &sweepRender}, a);
            sweepHair.apply();
            HairOptions probeHair = sweepHair;
            RenderSettings probeRender = sweepRender;
            for (const std::string& v : sweepVaries)
                sweepOptions.axes.push_back(parseSweepAxis(v, {&probeHair.growth, &probeHair.sim, &probeRender}));
            sweepOptions.outDir = sweepOut;
            sweepOptions.headFile = headPathOrDefault(sweepHead).string();
            vk::Context ctx(contextOptions(g));
            checkSweepGrid(ctx.report(), sweepOptions.axes, sweepHair, sweepRender);
            return runSweep(ctx, sweepOptions, sweepHair, sweepRender);
        }
        if (*settingsCmd) {
            std::cout << settingsTable();
            return 0;
        }
        if (*render) {
            if (ro.profileFrames == 0 && !*outOption)
                throw UserError("render: --out FILE.png is required (or --profile N to time frames)");
            for (const std::string& a : renderSets)
                applySetting({&ro.hair.growth, &ro.hair.sim, &ro.settings}, a);
            ro.hair.apply();
            ro.timeline = commandTimeline(sceneFromFile, render, ro.hair, ro.settings.light);
            return runRender(g, ro);
        }
        if (*view) {
            requireDisplay();  // before any loading
            windowOptions.context = contextOptions(g);
            for (const std::string& a : viewSets)
                applySetting({&viewHair.growth, &viewHair.sim, &windowOptions.settings}, a);
            viewHair.apply();
            // The window starts from the scene's state at time 0 (its sphere, wind and light).
            SceneState initial = commandTimeline(sceneFromFile, view, viewHair, windowOptions.settings.light).at(0.0);
            HairScene scene = buildCheckedScene(g, viewHair, headPathOrDefault(viewHead), &windowOptions.settings, viewNoHair,
                                                /*window=*/true);
            windowOptions.scene = &scene;
            windowOptions.timeline = commandTimeline(sceneFromFile, view, viewHair, windowOptions.settings.light);
            windowOptions.sceneLength = sceneFromFile ? sceneFromFile->length() : 0.0;
            windowOptions.headFile = viewHead;
            windowOptions.hair = viewHair;
            windowOptions.sim = viewHair.sim;
            windowOptions.sim.wind = initial.wind;
            windowOptions.sphere = initial.sphere;
            windowOptions.settings.light = initial.light;
            return runWindow(windowOptions);
        }
        if (*simulate) {
            sim.context = contextOptions(g);
            for (const std::string& a : simulateSets)
                applySetting({&simHair.growth, &simHair.sim, nullptr}, a);
            simHair.apply();
            sim.sim = simHair.sim;
            if (!simHair.sphere.empty())
                sim.sphere = simHair.sphereOrNone();
            if (sceneFromFile)
                sim.timeline = commandTimeline(sceneFromFile, simulate, simHair, simSceneRender.light);
            HairScene scene = buildCheckedScene(g, simHair, headPathOrDefault(simHead), nullptr, /*noHair=*/false);
            return runSimulate(sim, scene);
        }
        if (*info)
            return runInfo(infoJson);
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
