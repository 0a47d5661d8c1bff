// The subcommands of vplkit, one file each (info.cpp, render.cpp, sweep.cpp, view.cpp,
// compare.cpp, reference.cpp, export_scene.cpp, shader.cpp). Each registers only the options it reads on its own CLI11 subcommand and
// returns what to run once the command line has parsed.
#pragma once

#include <CLI/CLI.hpp>

#include <functional>
#include <memory>

#include "frontend/cli/options.hpp"

namespace vplkit::cli {

struct command {
  CLI::App* app = nullptr;                    ///< parsed() tells whether it was chosen
  std::function<int(const session&)> run;     ///< 0 on success; throws on failure
  std::function<void()> reset;                ///< back to the state right after registration
};

/// What puts a command's state back to its values right after registration (the end of its
/// add_*_command): a command_line parsed again starts from the state a new one has, which is what
/// lets the option fuzzer parse thousands of command lines a second with one CLI11 App.
template <typename State>
std::function<void()> restorer(const std::shared_ptr<State>& state) {
  return [state, initial = *state] { *state = initial; };
}

command add_info_command(CLI::App& app);
command add_render_command(CLI::App& app);
command add_sweep_command(CLI::App& app);
/// In the vplkit_view_command library (the viewer's), which the executable links.
command add_view_command(CLI::App& app);
command add_compare_command(CLI::App& app);
command add_reference_command(CLI::App& app);
command add_export_scene_command(CLI::App& app);
command add_shader_command(CLI::App& app);
/// `shader block` (shader_block.cpp), a subcommand of `shader`, which add_shader_command registers.
command add_shader_block_command(CLI::App& shader);

}  // namespace vplkit::cli
