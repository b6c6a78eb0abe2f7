// app/commands/bsdf_command.h: `wisp bsdf`: the hair BSDF on the CPU from the command line: the reference
// f (Chiang 2016 as pbrt-v3) for one pair of directions, a real-time model instead (--model), or
// every real-time model's error against the reference over the sphere (--compare). No GPU.
#pragma once

#include <functional>

namespace CLI {
class App;
}

namespace wisp {

// Registers `bsdf` and its options on `app`. After app.parse(), call the returned function: it runs
// the command and returns its exit status when `bsdf` was chosen, else returns -1. Bad values CLI11
// cannot check throw UserError (runCli turns it into one line and exit status 2).
std::function<int()> addBsdfCommand(CLI::App& app);

} // namespace wisp
