// app/commands/command.cpp: the global options' context, the validation status, the float ranges of
// options, and the workload checked before the hair is built.
#include "app/commands/command.h"

#include "app/settings/workload.h"
#include "core/error.h"
#include "renderer/render_target.h"

#include <CLI/CLI.hpp>

#include <algorithm>
#include <cstdio>
#include <sstream>

namespace wisp {

vk::ContextOptions contextOptions(const GlobalOptions& g)
{
    return {.validation = g.validation || g.syncValidation,
            .synchronizationValidation = g.syncValidation,
            .gpu = g.gpu,
            .instanceExtensions = {},
            .presentation = false};
}

int validationStatus(const vk::Context& ctx)
{
    uint32_t n = ctx.validationMessages();
    if (n == 0)
        return 0;
    std::fprintf(stderr, "wisp: %u Vulkan validation message%s (printed above)\n", n, n == 1 ? "" : "s");
    return kExitInternalError;
}

std::string useDeviceSamples(RenderSettings& render, const vk::DeviceReport& device)
{
    uint32_t asked = std::max(render.samples, 1u);
    render.samples = RenderTarget::samplesFor(device.colorDepthSampleCounts, asked);
    if (render.samples == asked)
        return "";
    std::string has;
    for (uint32_t s = 1; s <= 64; s <<= 1)
        if ((device.colorDepthSampleCounts & s) != 0)
            has += (has.empty() ? "" : ", ") + std::to_string(s);
    return "wisp: samples " + std::to_string(asked) + ": '" + device.name + "' draws " + (has.empty() ? "1" : has) +
           "; drawing with " + std::to_string(render.samples);
}

GroomedHead buildCheckedHead(const GlobalOptions& g, const SessionOptions& o, RenderSettings* render, bool window)
{
    const HairSource& h = o.source;
    const GrowthSettings& growth = o.settings.growth;
    bool samplesSettled = false;
    std::string samplesNote; // said once the workload is not refused: a refusal is one line
    auto check = [&](uint64_t guides) {
        Workload w{
            .guides = guides, .verticesPerStrand = growth.verticesPerStrand, .sim = o.settings.sim, .render = render};
        checkCounts(w);
        std::vector<vk::DeviceReport> devices = vk::enumerateDevices();
        const vk::DeviceReport& device = vk::selectDevice(devices, g.gpu, window);
        if (render && !samplesSettled)
            samplesNote = useDeviceSamples(*render, device); // before the estimate: the samples size the target
        samplesSettled = true;
        checkWorkload(w, device);
    };
    if (h.noHair || h.hairFiles.empty())
        check(h.noHair ? 0 : growth.guides);
    GroomedHead scene = h.buildGroomedHead(o.settings);
    if (!h.noHair && !h.hairFiles.empty()) {
        // A loaded groom is drawn at a density chosen from it, unless strands_per_guide is given.
        uint64_t strands = scene.strands.strandCount();
        // An artist's groom has the lengths it was given: its drawn strands are not trimmed unless asked.
        if (render && !o.settingGiven("strand_length_jitter"))
            render->strands.lengthJitter = 0.0f;
        if (render && !o.settingGiven("strands_per_guide")) {
            render->strands.strandsPerGuide = loadedStrandsPerGuide(strands, render->strands.strandsPerGuide);
            scene.notes.push_back("hair density: " + std::to_string(strands) + " strands in the file" +
                                  (h.hairFiles.size() > 1 ? "s" : "") + ", each drawn as " +
                                  std::to_string(render->strands.strandsPerGuide) + " (strands_per_guide, about " +
                                  std::to_string(kLoadedGroomStrands) +
                                  " strands in all; --set strands_per_guide=N to choose)");
        }
        check(strands);
    }
    if (!samplesNote.empty())
        std::fprintf(stderr, "%s\n", samplesNote.c_str());
    for (const std::string& w : scene.warnings)
        std::fprintf(stderr, "wisp: warning: %s\n", w.c_str());
    return scene;
}

} // namespace wisp
