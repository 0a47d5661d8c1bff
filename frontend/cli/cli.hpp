// The vplkit command line as a function, so that the executable, the CLI tests and the option
// fuzzer (tests/fuzz/fuzz_cli_options.cpp) run the same parser and the same checks.
#pragma once

#include <functional>
#include <memory>
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

/// The same parser built once and run on many command lines: each run starts from the state a new
/// one has (CLI11's results cleared, every command's state restored), so a run's outcome does not
/// depend on the ones before it. Building the parser (hundreds of options) costs far more than a
/// parse: the option fuzzer keeps one.
class command_line {
 public:
  explicit command_line(const std::vector<command_adder>& more_commands = {});
  ~command_line();
  command_line(const command_line&) = delete;
  command_line& operator=(const command_line&) = delete;
  int run(int argc, const char* const* argv, std::ostream& out, std::ostream& err, command_line_mode mode = command_line_mode::run);

 private:
  struct parser;
  std::unique_ptr<parser> parser_;
};

}  // namespace vplkit
