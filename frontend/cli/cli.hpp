// The vplkit command line as a function, so that the executable, the CLI tests and the option
// fuzzer (tests/fuzz/fuzz_cli_options.cpp) run the same parser and the same checks.
#pragma once

#include <functional>
#include <ostream>
#include <vector>

namespace CLI {
class App;
}

namespace vplkit {

namespace cli {
struct command;
}

/// A subcommand registered beside the headless ones (the viewer's `view`, which the executable
/// links and the headless library does not).
using command_adder = std::function<cli::command(CLI::App&)>;

enum class command_line_mode {
  run,         ///< do what the command says
  check_only,  ///< parse and check every option, then stop before a GL context or a file is opened
};

/// Runs `vplkit <argv[1..]>`: 0 on success, 1 for a failure while running (a message on `err`
/// naming what and where), 2 for a command line that does not parse (CLI11's message).
int run_command_line(int argc, const char* const* argv, std::ostream& out, std::ostream& err, command_line_mode mode = command_line_mode::run,
                     const std::vector<command_adder>& more_commands = {});

}  // namespace vplkit
