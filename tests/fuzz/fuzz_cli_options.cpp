// Fuzz target: the command line's parsing and checks (frontend/cli/cli.hpp) in check_only mode, which
// stops before a GL context or a file is opened. The input is the arguments after `vplkit`,
// separated by NUL bytes (at most 32). Every command line must end in exit code 0, 1 or 2, with
// no exception escaping. One command_line serves every input (building its hundreds of options
// cost forty times a parse); every 256th input is also run on a new one, and both must agree, so a
// state that leaked from one parse into the next would show.
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include "frontend/cli/cli.hpp"
#include "frontend/cli/commands.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view input(reinterpret_cast<const char*>(data), size);
  std::vector<std::string> arguments{"vplkit"};
  for (std::size_t start = 0; start <= input.size() && arguments.size() <= 32;) {
    const std::size_t end = input.find('\0', start);
    arguments.emplace_back(input.substr(start, end == std::string_view::npos ? std::string_view::npos : end - start));
    if (end == std::string_view::npos) break;
    start = end + 1;
  }
  std::vector<const char*> argv;
  for (const std::string& argument : arguments) argv.push_back(argument.c_str());
  static vplkit::command_line parser({vplkit::cli::add_view_command});
  static unsigned runs = 0;
  std::ostringstream out, err;
  const int status = parser.run(static_cast<int>(argv.size()), argv.data(), out, err, vplkit::command_line_mode::check_only);
  if (++runs % 256 == 0) {
    std::ostringstream fresh_out, fresh_err;
    const int fresh = vplkit::run_command_line(static_cast<int>(argv.size()), argv.data(), fresh_out, fresh_err, vplkit::command_line_mode::check_only,
                                                     {vplkit::cli::add_view_command});
    if (fresh != status || fresh_out.str() != out.str() || fresh_err.str() != err.str()) {
      std::fprintf(stderr, "fuzz_cli_options: a reused parser answered %d, a new one %d:\n%s%s\n--\n%s%s\n", status, fresh, out.str().c_str(),
                   err.str().c_str(), fresh_out.str().c_str(), fresh_err.str().c_str());
      std::abort();
    }
  }
  if (status != 0 && status != 1 && status != 2) {
    std::fprintf(stderr, "fuzz_cli_options: exit code %d\n", status);
    std::abort();
  }
  if (status != 0 && err.str().empty() && out.str().empty()) {
    std::fprintf(stderr, "fuzz_cli_options: exit code %d without a message\n", status);
    std::abort();
  }
  return 0;
}
