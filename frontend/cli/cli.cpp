// The vplkit command line: `info`, `render` (headless, the main job), `sweep`, `compare`,
// `reference`, `export-scene` and `shader expand`, one file each (commands.hpp), and `view` (a window), which the
// executable adds (view.cpp, with the viewer library). Every option is range-checked as it
// is parsed (non-finite numbers included); the checks that need several options, and the
// scoping of options to the techniques and methods that read them, run before anything is
// opened or read.
#include "frontend/cli/cli.hpp"

#include <CLI/CLI.hpp>

#include <new>
#include <sstream>
#include <string_view>

#include <vplkit/version.hpp>

#include "frontend/cli/commands.hpp"
#include "frontend/core/error.hpp"
#include "frontend/gl/debug_output.hpp"

namespace vplkit {

namespace {

// `text` with every argument longer than max_echoed_characters (or its value after '=') replaced
// by its excerpt.
std::string without_long_arguments(std::string text, int argc, const char* const* argv) {
  for (int i = 1; i < argc; ++i) {
    const std::string_view argument = argv[i];
    const std::size_t equals = argument.find('=');
    for (const std::string_view long_text : {argument, equals == std::string_view::npos ? std::string_view() : argument.substr(equals + 1)}) {
      if (long_text.size() <= max_echoed_characters) continue;
      const std::string shortened = excerpt(long_text);
      for (std::size_t at = text.find(long_text); at != std::string::npos; at = text.find(long_text, at + shortened.size()))
        text.replace(at, long_text.size(), shortened);
    }
  }
  return text;
}

}  // namespace

struct command_line::parser {
  // Named, not argv[0]: the help says "Usage: vplkit ..." wherever the executable is (a path with a
  // space was cut in two in the usage line).
  CLI::App app{"vplkit: real-time one-bounce indirect illumination (reflective shadow maps with visibility, Light Wave, robust final gathering)", "vplkit"};
  std::vector<cli::command> commands;

  explicit parser(const std::vector<command_adder>& more_commands) {
    // At most one subcommand; an unknown word is then reported by name as an unexpected argument
    // (require_subcommand(1) would only say that a subcommand is required).
    app.require_subcommand(0, 1);
    app.set_version_flag("--version", version_string);
    commands = {cli::add_info_command(app), cli::add_render_command(app), cli::add_sweep_command(app)};
    for (const command_adder& add : more_commands) commands.push_back(add(app));
    for (const auto& add : {cli::add_compare_command, cli::add_reference_command, cli::add_export_scene_command, cli::add_shader_command})
      commands.push_back(add(app));
  }
};

command_line::command_line(const std::vector<command_adder>& more_commands) : parser_(std::make_unique<parser>(more_commands)) {}
command_line::~command_line() = default;

int command_line::run(int argc, const char* const* argv, std::ostream& out, std::ostream& err, command_line_mode mode) {
  CLI::App& app = parser_->app;
  app.clear();
  for (const cli::command& command : parser_->commands) command.reset();
  const std::vector<cli::command>& commands = parser_->commands;
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& parse_error) {
    // CLI11 prints the message (or the help); its exit codes (105 for a failed check, ...) all
    // become 2, the conventional code for a command line that does not parse. Its message may
    // echo an argument whole (a 100,000-character --technique): a long one is cut where shown.
    std::ostringstream message;
    const int code = app.exit(parse_error, out, message);
    err << without_long_arguments(message.str(), argc, argv);
    return code == 0 ? 0 : 2;
  }
  const cli::session io{out, mode == command_line_mode::check_only};
  try {
    cli::check_environment();
    int status = -1;
    for (const cli::command& command : commands)
      if (command.app->parsed()) status = command.run(io);
    if (status < 0) {
      std::string names;
      for (const cli::command& command : commands) names += (names.empty() ? "" : ", ") + command.app->get_name();
      err << "vplkit: error: a subcommand is required: " << names << " (see vplkit --help)\n";
      return 2;
    }
    // A GL error that no check point turned into an exception still fails the command.
    if (status == 0 && unchecked_gl_error_count() > 0) {
      err << "vplkit: error: the GL driver reported " << unchecked_gl_error_count()
          << " error(s) through KHR_debug that no check point saw; the output is not trustworthy\n";
      return 1;
    }
    return status;
  } catch (const cli::usage_error& usage) {
    err << "vplkit: error: " << usage.what() << "\n";
    return 2;
  } catch (const std::bad_alloc&) {
    err << "vplkit: error: out of memory (the input asks for more than this machine has)\n";
    return 1;
  } catch (const std::exception& failure) {
    err << "vplkit: error: " << failure.what() << "\n";
    return 1;
  }
}

int run_command_line(int argc, const char* const* argv, std::ostream& out, std::ostream& err, command_line_mode mode,
                     const std::vector<command_adder>& more_commands) {
  return command_line(more_commands).run(argc, argv, out, err, mode);
}

}  // namespace vplkit
