// app/cli.cpp: subcommands render, view, info and inspect, their options and ranges, and the
// error-to-exit-status policy.
#include "app/cli.h"

#include "app/headless.h"
#include "app/image_io.h"
#include "app/window.h"
#include "core/error.h"
#include "physics/head.h"
#include "renderer/vk/context.h"

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <cstdio>
#include <iostream>

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

std::filesystem::path headPathOrDefault(const std::string& head)
{
    return head.empty() ? defaultHeadPath() : std::filesystem::path(head);
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
        ->check(CLI::Range(-360.0f, 360.0f))
        ->capture_default_str();
    cmd->add_option("--light-elevation", s.light.elevationDeg, "key light angle above the horizon, degrees")
        ->check(CLI::Range(static_cast<float>(kLightElevationRange.min), static_cast<float>(kLightElevationRange.max)))
        ->capture_default_str();
    cmd->add_option("--light-intensity", s.light.intensity, "key light strength")
        ->check(CLI::Range(static_cast<float>(kLightIntensityRange.min), static_cast<float>(kLightIntensityRange.max)))
        ->capture_default_str();
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
                  << "  float atomic add (buffers):   " << yes(d.floatAtomicAdd)
                  << (d.floatAtomicAdd ? "" : " (the hair grid falls back to fixed point)") << "\n"
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
    Mesh mesh = loadMesh(file);
    Bounds b = mesh.bounds();
    nlohmann::json out = {{"kind", "mesh"},
                          {"vertices", mesh.sourceVertices},
                          {"triangles", mesh.triangleCount()},
                          {"bbox", {{b.min.x, b.min.y, b.min.z}, {b.max.x, b.max.y, b.max.z}}}};
    std::cout << out.dump() << "\n";
    return 0;
}

int runRender(const GlobalOptions& g, const std::string& out, const std::string& headFile, const RenderSettings& settings)
{
    checkPngOutput(out);  // fail before any GPU work
    Head head = loadHead(headPathOrDefault(headFile));
    vk::Context ctx(contextOptions(g));
    Picture picture = renderPicture(ctx, head, settings);
    int status = validationStatus(ctx);
    if (status != 0)
        return status;  // a picture made with validation errors is not trusted: nothing written
    writePng(out, picture.width, picture.height, picture.rgba);
    std::cout << out << "\n";
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
    app.add_option("--gpu", g.gpu, "Vulkan device: an index or part of a name from 'wisp info' (default: best)");

    RenderSettings renderSettings;
    std::string renderOut, renderHead;
    CLI::App* render = app.add_subcommand("render", "render one frame offscreen into a PNG");
    render->add_option("--out", renderOut, "output PNG file (its folder must exist)")->required();
    render->add_option("--head", renderHead, "head: a description (.json) or a mesh (.obj, .fbx, .gltf, .ply, ...); default models/head.json");
    addImageSize(render, renderSettings);
    addLookOptions(render, renderSettings);

    WindowOptions windowOptions;
    CLI::App* view = app.add_subcommand("view", "the interactive window (drag: orbit, wheel: zoom, middle drag: pan, Esc: quit)");
    view->add_option("--head", windowOptions.headFile, "head description (.json) or mesh file; default models/head.json");
    addImageSize(view, windowOptions.settings);
    addLookOptions(view, windowOptions.settings);
    view->add_option("--frames", windowOptions.maxFrames, "close after this many frames (0 = run until closed)")
        ->check(CLI::NonNegativeNumber);
    view->add_option("--screenshot", windowOptions.screenshot, "write the last frame to this PNG when closing");

    bool infoJson = false;
    CLI::App* info = app.add_subcommand("info", "list Vulkan devices and the features Wisp uses");
    info->add_flag("--json", infoJson, "print JSON instead of text");

    std::string inspectFile;
    CLI::App* inspect = app.add_subcommand("inspect", "print what a mesh file holds, as one JSON object");
    inspect->add_option("file", inspectFile, "a mesh file (.obj through tinyobjloader, others through assimp)")->required();

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
        if (*render)
            return runRender(g, renderOut, renderHead, renderSettings);
        if (*view) {
            windowOptions.context = contextOptions(g);
            if (windowOptions.headFile.empty())
                windowOptions.headFile = defaultHeadPath().string();
            return runWindow(windowOptions);
        }
        if (*info)
            return runInfo(infoJson);
        if (*inspect)
            return runInspect(inspectFile);
    } catch (const UserError& e) {
        std::fprintf(stderr, "wisp: %s\n", e.what());
        return kExitUserError;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "wisp: internal error: %s\n", e.what());
        return kExitInternalError;
    }
    return kExitInternalError;
}

}  // namespace wisp
