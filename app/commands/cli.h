// app/commands/cli.h: the `wisp` command line (CLI11): parses the subcommands and their options into
// settings, runs them, and turns errors into one line on stderr and an exit status
// (0 success, 2 bad input or environment, 3 the GPU device lost, 1 internal error or validation
// messages).
#pragma once

namespace wisp {

int runCli(int argc, char** argv);

} // namespace wisp
