// app/commands/cli.cpp: `wisp`'s command line: the global options (--gpu, --validation, --sync-validation),
// every command registered (app/commands/commands.h: render, view, simulate, groom, record, sweep, bsdf,
// compare, settings, info, inspect), and the error-to-exit-status policy (core/error.h: bad input 2, a
// lost device 3, anything else 1).
#include "app/commands/cli.h"

#include "app/commands/commands.h"
#include "core/error.h"
#include "gpu/check.h"

#include <CLI/CLI.hpp>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <iostream>
#include <regex>
#include <string>
#include <unistd.h>
#include <vector>

namespace wisp {

namespace {

// What a command printed (a JSON report, a table, the files it wrote) reaches its reader only if
// standard output takes it: on a full disk or /dev/full the flush fails, and the run fails with it.
int finishStandardOutput(int status)
{
    int why = 0;
    if (std::fflush(stdout) != 0)
        why = errno;
    else if (std::ferror(stdout) || !std::cout) {
        // An earlier write failed (the buffer filled and was flushed mid-print): the output is
        // already short, and one more byte written straight to it says why.
        why = ::write(STDOUT_FILENO, "\n", 1) < 0 ? errno : EIO;
    } else {
        return status;
    }
    std::fprintf(stderr, "wisp: cannot write the standard output: %s\n", std::strerror(why));
    return status == 0 ? kExitUserError : status;
}

// CLI11's own words for what it refuses itself, in the project's form: an option given more often
// than it takes ("--style: At Most 1 required but received 2"), or with more values than it
// takes, says so and how often.
std::string parseErrorText(const std::string& text)
{
    static const std::regex atMost(R"((\S+): At Most (\d+) required but received (\d+))");
    std::smatch m;
    if (std::regex_match(text, m, atMost))
        return m[2].str() == "1" ? m[1].str() + ": given " + m[3].str() + " times; it takes one value (give it once)"
                                 : m[1].str() + ": " + m[3].str() + " values given; it takes at most " + m[2].str();
    return text + " (see 'wisp --help')";
}

} // namespace

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
            [](std::string& v) { // an index past what std::stoul reads would be an internal error later
                bool digits = !v.empty() && v.find_first_not_of("0123456789") == std::string::npos;
                return digits && v.size() > 6 ? "device index " + v + " is out of range (see 'wisp info')"
                                              : std::string();
            },
            "INDEX|NAME"));

    std::vector<CommandRun> commands = {addRenderCommand(app, g), addViewCommand(app, g),   addSimulateCommand(app, g),
                                        addGroomCommand(app, g),  addRecordCommand(app, g), addSweepCommand(app, g),
                                        addBsdfCommand(app),      addCompareCommand(app),   addSettingsCommand(app),
                                        addInfoCommand(app),      addInspectCommand(app)};

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
    } catch (const CLI::ValidationError& e) {
        // A value refused by the project's validators: "--spp: 0 is out of range: allowed 1 .. 1000000".
        std::fprintf(stderr, "wisp: %s\n", e.what());
        return kExitUserError;
    } catch (const CLI::ParseError& e) {
        std::fprintf(stderr, "wisp: %s\n", parseErrorText(e.what()).c_str());
        return kExitUserError;
    }

    try {
        for (const CommandRun& run : commands)
            if (int status = run(); status >= 0)
                return finishStandardOutput(status);
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

} // namespace wisp
