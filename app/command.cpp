// app/command.cpp: the global options' context, the validation status, the float ranges of
// options, and the workload checked before the hair is built.
#include "app/command.h"

#include "app/workload.h"
#include "core/error.h"

#include <CLI/CLI.hpp>

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

HairScene buildCheckedScene(const GlobalOptions& g, const SessionOptions& o, const RenderSettings* render, bool window)
{
    const HairSource& h = o.source;
    const GrowthSettings& growth = o.settings.growth;
    auto check = [&](uint64_t guides) {
        Workload w{
            .guides = guides, .verticesPerStrand = growth.verticesPerStrand, .sim = o.settings.sim, .render = render};
        checkCounts(w);
        std::vector<vk::DeviceReport> devices = vk::enumerateDevices();
        checkWorkload(w, vk::selectDevice(devices, g.gpu, window));
    };
    if (h.noHair || h.hairFiles.empty())
        check(h.noHair ? 0 : growth.guides);
    HairScene scene = h.buildScene(o.settings);
    if (!h.noHair && !h.hairFiles.empty())
        check(scene.strands.strandCount());
    for (const std::string& w : scene.warnings)
        std::fprintf(stderr, "wisp: warning: %s\n", w.c_str());
    return scene;
}

} // namespace wisp
