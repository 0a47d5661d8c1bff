// The vplkit executable: frontend/cli/cli.hpp does the work; the executable adds the viewer's
// `view` command, which the headless library does not link.
#include <iostream>

#include "frontend/cli/cli.hpp"
#include "frontend/cli/commands.hpp"

int main(int argc, char** argv) {
  return vplkit::run_command_line(argc, argv, std::cout, std::cerr, vplkit::command_line_mode::run, {vplkit::cli::add_view_command});
}
