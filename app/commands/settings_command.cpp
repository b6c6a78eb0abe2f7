// app/commands/settings_command.cpp: `wisp settings`: the settings table as people read it (name, unit,
// allowed values, default, what a change needs, the option, help) or as JSON (--json).
#include "app/commands/commands.h"

#include "app/settings/settings_table.h"

#include <CLI/CLI.hpp>

#include <iostream>
#include <memory>

namespace wisp {

CommandRun addSettingsCommand(CLI::App& app)
{
    auto json = std::make_shared<bool>(false);
    CLI::App* cmd = app.add_subcommand(
        "settings",
        "list every setting --set takes: names, units, allowed values, defaults, what a change needs, options");
    cmd->add_flag("--json", *json, "print JSON instead of text");
    return [cmd, json] {
        if (!cmd->parsed())
            return -1;
        if (*json)
            std::cout << settingsTableJson().dump(2) << "\n";
        else
            std::cout << settingsTable();
        return 0;
    };
}

} // namespace wisp
