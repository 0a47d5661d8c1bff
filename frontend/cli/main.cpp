// The vplkit executable: frontend/cli/cli.hpp does the work; the executable adds the viewer's
// `view` command, which the headless library does not link.
//
// Everything printed to standard output (results, tables, "wrote" lines, help) goes through one
// checked buffer, std::cout's own included (scene notes print there): a write that fails (a full
// disk, `> /dev/full`, a closed descriptor) loses output, and the command then exits 1 with the
// system's reason instead of 0.
#include <unistd.h>

#include <iostream>
#include <system_error>

#include "frontend/cli/cli.hpp"
#include "frontend/cli/commands.hpp"
#include "frontend/core/files.hpp"

int main(int argc, char** argv) {
  int code = 0;
  int lost = 0;
  {
    vplkit::descriptor_output standard_output(STDOUT_FILENO);
    std::streambuf* const previous = std::cout.rdbuf(&standard_output);
    code = vplkit::run_command_line(argc, argv, std::cout, std::cerr, vplkit::command_line_mode::run, {vplkit::cli::add_view_command});
    std::cout.flush();
    std::cout.rdbuf(previous);
    lost = standard_output.failure();
  }
  if (lost != 0) {
    std::cerr << "vplkit: error: cannot write to standard output: " << std::generic_category().message(lost) << "\n";
    return code == 0 ? 1 : code;
  }
  return code;
}
