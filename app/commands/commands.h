// app/commands/commands.h: every command of `wisp`, each registering itself on the command line as
// app/commands/command.h says (`bsdf`, which needs no device, is app/commands/bsdf_command.h; `inspect` is
// app/commands/inspect.h; `compare` needs no device either). runCli (app/commands/cli.cpp) adds them in this order,
// which `wisp --help` lists.
#pragma once

#include "app/commands/bsdf_command.h"
#include "app/commands/command.h"
#include "app/commands/inspect.h"

namespace wisp {

CommandRun addRenderCommand(CLI::App& app, const GlobalOptions& global);   // render_command.cpp
CommandRun addViewCommand(CLI::App& app, const GlobalOptions& global);     // view_command.cpp
CommandRun addSimulateCommand(CLI::App& app, const GlobalOptions& global); // simulate_command.cpp
CommandRun addGroomCommand(CLI::App& app, const GlobalOptions& global);    // groom_command.cpp
CommandRun addRecordCommand(CLI::App& app, const GlobalOptions& global);   // record_command.cpp
CommandRun addSweepCommand(CLI::App& app, const GlobalOptions& global);    // sweep_command.cpp
CommandRun addSettingsCommand(CLI::App& app);                              // settings_command.cpp
CommandRun addInfoCommand(CLI::App& app);                                  // info_command.cpp
CommandRun addCompareCommand(CLI::App& app);                               // compare_command.cpp

} // namespace wisp
