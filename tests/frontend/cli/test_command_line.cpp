// One command_line parsing many command lines (frontend/cli/cli.hpp): each answer is the one a new
// parser gives, whatever was parsed before (the option fuzzer relies on it), over the option
// fuzzer's corpus and regressions in order, then in reverse.
#include <doctest/doctest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <vector>

#include "frontend/cli/cli.hpp"

namespace fs = std::filesystem;

namespace {

struct answer {
  int status;
  std::string out, err;
  bool operator==(const answer& other) const { return status == other.status && out == other.out && err == other.err; }
};

// The fuzzer's format: arguments after `vplkit` separated by NUL bytes.
std::vector<std::string> arguments_of(const std::string& bytes) {
  std::vector<std::string> arguments{"vplkit"};
  for (std::size_t start = 0; start <= bytes.size() && arguments.size() <= 32;) {
    const std::size_t end = bytes.find('\0', start);
    arguments.push_back(bytes.substr(start, end == std::string::npos ? std::string::npos : end - start));
    if (end == std::string::npos) break;
    start = end + 1;
  }
  return arguments;
}

answer run(vplkit::command_line* parser, const std::vector<std::string>& arguments) {
  std::vector<const char*> argv;
  for (const std::string& argument : arguments) argv.push_back(argument.c_str());
  std::ostringstream out, err;
  const int status = parser ? parser->run(static_cast<int>(argv.size()), argv.data(), out, err, vplkit::command_line_mode::check_only)
                            : vplkit::run_command_line(static_cast<int>(argv.size()), argv.data(), out, err, vplkit::command_line_mode::check_only);
  return {status, out.str(), err.str()};
}

}  // namespace

TEST_CASE("a command_line parsed again answers every command line like a new one") {
  std::vector<std::vector<std::string>> inputs;
  for (const char* folder : {"corpus", "regressions"})
    for (const fs::directory_entry& entry : fs::directory_iterator(fs::path(VPLKIT_TEST_SOURCE_DIR) / "fuzz" / folder / "cli_options")) {
      std::ifstream in(entry.path(), std::ios::binary);
      inputs.push_back(arguments_of(std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>())));
    }
  // Options that set state another command line must not inherit.
  inputs.push_back({"vplkit", "render", "--size", "64x32", "--scene", "boxes", "--technique", "lightwave-faked", "--faked-multiplier", "2"});
  inputs.push_back({"vplkit", "render", "--faked-multiplier", "2"});  // the default technique does not read it
  inputs.push_back({"vplkit", "reference", "--method", "rsm-brute-force", "--receiver-stride", "4"});
  inputs.push_back({"vplkit", "reference", "--receiver-stride", "4"});
  inputs.push_back({"vplkit", "render", "--camera", "0,1,3,0,1,0"});
  inputs.push_back({"vplkit", "render", "--light", "nonsense"});
  inputs.push_back({"vplkit", "--help"});
  inputs.push_back({"vplkit", "render"});
  REQUIRE(inputs.size() > 10);
  vplkit::command_line parser;
  for (int pass = 0; pass < 2; ++pass) {
    for (const std::vector<std::string>& arguments : inputs) {
      std::string shown;
      for (const std::string& argument : arguments) shown += argument + " ";
      CAPTURE(shown);
      CHECK(run(&parser, arguments) == run(nullptr, arguments));
    }
    std::reverse(inputs.begin(), inputs.end());
  }
}
