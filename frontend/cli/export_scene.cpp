// vplkit export-scene: a built-in scene written as glTF 2.0 (frontend/scene/gltf_scene.hpp), so
// that users can start their own scenes from one; `--scene file.gltf` reads it back.
#include "frontend/cli/commands.hpp"
#include "frontend/cli/output.hpp"
#include "frontend/scene/gltf_scene.hpp"

namespace vplkit::cli {

namespace {

struct export_state {
  std::string scene, out;
};

int run_export_scene(const session& io, const export_state& s) {
  output_set files(s.out, "", ".gltf", "the output");
  if (io.dry_run) return 0;
  files.add_text(files.main(), gltf_text(built_in_scene(s.scene)));
  files.write(io.out);
  return 0;
}

}  // namespace

command add_export_scene_command(CLI::App& app) {
  auto state = std::make_shared<export_state>();
  CLI::App* command = app.add_subcommand("export-scene", "write a built-in scene as glTF 2.0 (mesh, camera, KHR_lights_punctual light)");
  std::string names;
  for (const std::string& name : built_in_scene_names()) names += (names.empty() ? "" : ", ") + name;
  command->add_option("scene", state->scene, "built-in scene (" + names + ")")->required()->check(CLI::IsMember(built_in_scene_names()));
  command->add_option("out", state->out, "output .gltf file (the buffer is embedded)")->required();
  return {command, [state](const session& io) { return run_export_scene(io, *state); }, restorer(state)};
}

}  // namespace vplkit::cli
