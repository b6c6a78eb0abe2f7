// app/commands/command.h: what the commands share. Each command registers itself on the command line
// (app/commands/commands.h: addRenderCommand, ...): it adds its subcommand and its own options, keeps them
// to itself, and returns the function that runs it after parsing (-1 when another command was
// chosen). The global options (--gpu, --validation) and the checks before any loading live here.
#pragma once

#include "app/scene/session_options.h"
#include "gpu/context.h"
#include "physics/groomed_head.h"

#include <functional>
#include <string>

namespace CLI {
class App;
class Validator;
} // namespace CLI

namespace wisp {

struct GlobalOptions {
    bool validation = false;
    bool syncValidation = false;
    std::string gpu;
};
// Runs the command when it was chosen, returning its exit status; -1 otherwise.
using CommandRun = std::function<int()>;

vk::ContextOptions contextOptions(const GlobalOptions& global);
// With validation on, any message is a bug: the run fails (exit 1, the count on stderr).
int validationStatus(const vk::Context& ctx);
// The head and the hair `options` describe, built once the workload is checked (counts that must
// fit 32 bits, GPU memory against the device it will run on): before guides are grown, and for hair
// files once they are loaded (only then is their strand count known). Nothing is allocated on the
// device yet. `render`: the drawing's settings (null: simulate), its samples set to what the device
// draws of them (useDeviceSamples), and a loaded groom's strands_per_guide chosen there
// (loadedStrandsPerGuide) unless the command line or the scene gave it; `window`: the device must
// present.
GroomedHead buildCheckedHead(const GlobalOptions& global, const SessionOptions& options, RenderSettings* render,
                             bool window = false);
// Sets render.samples to what `device` draws of them (RenderTarget::samplesFor: the most of the
// asked number, half of it, ... that it has); returns the one line that says so when that is fewer
// ("" otherwise), for the caller to print once the run is not refused.
std::string useDeviceSamples(RenderSettings& render, const vk::DeviceReport& device);

} // namespace wisp
