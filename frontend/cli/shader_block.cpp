// vplkit shader block NAME: the GLSL declaration of a std140 uniform block holding one settings
// struct's twin, with its size and every field's offset (vplkit/std140.hpp's std140_block), for
// engines that hand vplkit's settings to the lib files in a uniform buffer. A subcommand of
// `shader` (shader.cpp registers it), kept in its own file.
#include <string>
#include <vector>

#include <vplkit/std140.hpp>

#include "frontend/cli/commands.hpp"

namespace vplkit::cli {

namespace {

struct block_state {
  std::string name, block, member = "settings";
};

int run_block(const session& io, const block_state& s) {
  if (!s.block.empty() && !is_glsl_identifier(s.block)) throw usage_error("shader block: --block " + shown(s.block) + " is not a GLSL identifier");
  if (!is_glsl_identifier(s.member)) throw usage_error("shader block: --member " + shown(s.member) + " is not a GLSL identifier");
  std::string text, known;
  for_each_glsl_twin_type([&](const auto& settings) {
    using settings_type = std::decay_t<decltype(settings)>;
    const std::string name = settings_description<settings_type>::name;
    known += (known.empty() ? "" : ", ") + name;
    if (name == s.name) text = std140_block<settings_type>(s.block.empty() ? name + "_block" : s.block, s.member);
  });
  if (text.empty()) throw usage_error("shader block: no settings struct " + shown(s.name) + " has a GLSL twin (known: " + known + ")");
  // The member is a global name beside the struct's type name, which it would hide.
  if (s.member == s.name) throw usage_error("shader block: --member " + shown(s.member) + " is the struct's own name; GLSL would reject it");
  if (!io.dry_run) io.out << text;
  return 0;
}

}  // namespace

command add_shader_block_command(CLI::App& shader) {
  auto state = std::make_shared<block_state>();
  CLI::App* block = shader.add_subcommand(
      "block", "print the std140 uniform block of a settings struct's GLSL twin, with its size and every field's offset (vplkit/std140.hpp)");
  block->add_option("name", state->name, "the settings struct: irradiance_settings, rsm_gather_settings, ...")->required();
  block->add_option("--block", state->block, "the block's name (default: NAME_block)");
  block->add_option("--member", state->member, "the name of the block's one member, a global name in GLSL (default: settings)");
  return {block, [state](const session& io) { return run_block(io, *state); }, restorer(state)};
}

}  // namespace vplkit::cli
