// app/commands/info_command.cpp: `wisp info`: the Vulkan devices and the features Wisp uses (--json for one
// array of objects); says what to install when there is no device.
#include "app/commands/commands.h"

#include "core/error.h"
#include "gpu/context.h"

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <iostream>
#include <memory>

namespace wisp {

namespace {

// The MSAA sample counts colour and depth targets both support (what `samples` can draw).
std::vector<uint32_t> sampleCounts(const vk::DeviceReport& d)
{
    std::vector<uint32_t> counts;
    for (uint32_t s = 1; s <= 64; s <<= 1)
        if ((d.colorDepthSampleCounts & s) != 0)
            counts.push_back(s);
    return counts;
}

int run(bool json)
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
                           {"msaa_samples", sampleCounts(d)},
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
                  << " (the deterministic fixed-point hair grid" << (d.int64Atomics ? ")" : "; float atomics instead)")
                  << "\n"
                  << "  timestamps:                   " << yes(d.timestamps) << " (" << d.timestampValidBits
                  << " valid bits, " << d.timestampPeriodNs << " ns per tick)\n"
                  << "  pipeline statistics:          " << yes(d.pipelineStatisticsQuery) << "\n"
                  << "  MSAA samples (colour, depth): " << nlohmann::json(sampleCounts(d)).dump() << "\n"
                  << "  push descriptors:             " << yes(d.pushDescriptor) << "\n"
                  << "  device-local memory:          " << d.deviceLocalBytes / (1024 * 1024) << " MiB\n";
    }
    return 0;
}

} // namespace

CommandRun addInfoCommand(CLI::App& app)
{
    auto json = std::make_shared<bool>(false);
    CLI::App* cmd = app.add_subcommand("info", "list Vulkan devices and the features Wisp uses");
    cmd->add_flag("--json", *json, "print JSON instead of text");
    return [cmd, json] { return cmd->parsed() ? run(*json) : -1; };
}

} // namespace wisp
