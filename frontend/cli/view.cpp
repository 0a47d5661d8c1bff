// vplkit view: any technique in a window with live controls (frontend/viewer/viewer.hpp); use
// xvfb-run without a display. It takes render's options (technique_options), so a pose or a
// setting seen in the window renders headless with the same arguments. It lives in its own
// library with the viewer (GLFW, Dear ImGui), which the executable links and the headless
// command-line library does not.
#include <map>

#include "frontend/cli/commands.hpp"
#include "frontend/cli/output.hpp"
#include "frontend/cli/technique_options.hpp"
#include "frontend/viewer/viewer.hpp"

namespace vplkit::cli {

namespace {

struct view_state {
  technique_options options;
  int frames = 0;
  std::string screenshot;
  bool hide_panel = false;
  bool dock_panel = false;
};

int run_view(const session& io, const view_state& s) {
  const technique_options& o = s.options;
  o.scope.require_read_by(o.technique, "technique");
  // The chosen technique's settings (a usage error, exit 2, when refused), then every other
  // family's from the options it reads, so that the panel can switch to any technique.
  const std::unique_ptr<technique_settings> chosen = make_technique_settings(o.given, o.technique);
  const std::string shown_scene = drawn_scene_name(o.common, *chosen);
  output_set files(s.screenshot, "output/" + std::filesystem::path(shown_scene).stem().string() + "-" + o.technique + "-view.png", ".png", "--screenshot",
                   "<stem>-indirect.pfm goes next to it");
  viewer_options options;
  options.technique = o.technique;
  options.panel = !s.hide_panel;
  options.docked_panel_width = s.dock_panel ? docked_panel_width : 0;
  options.screenshot = files.main();
  options.exposure_ev = o.common.exposure_ev;
  options.auto_exposure = o.common.auto_exposure;
  // One window size for every family: the chosen technique's.
  const std::string size = chosen->get("size");
  for (const technique_family& family : technique_families()) {
    viewer_family& state = options.scenes.families[family.name];
    if (family.has(o.technique)) {
      state.settings = chosen->clone();
      continue;
    }
    state.settings = family.make_settings(family.techniques.front().name);
    for (const auto& [name, value] : o.given.values)
      if (state.settings->reads(name)) state.settings->set(name, value);
    state.settings->set("size", size);
  }
  if (io.dry_run) return 0;

  const auto [width, height] = *parse_extent(size);
  std::map<std::string, scene> loaded;  // a scene named for both families is read once
  for (const technique_family& family : technique_families()) {
    if (!family.draws_scene(o.common.scene_given)) continue;  // final gathering without --scene: its own room
    const std::string name = o.common.scene_given ? o.common.scene : family.default_scene;
    if (!loaded.count(name)) loaded.emplace(name, load_scene(o.common, name));
    options.scenes.families[family.name].source = loaded.at(name);
    // The file's index of each light drawn, for the pose text (viewer::pose_arguments).
    options.scenes.families[family.name].file_lights = o.common.light_choice;
  }
  window_context window(width + options.docked_panel_width, height, "vplkit view - " + shown_scene);
  const shader_library shaders(o.common.shaders());
  // The poses of a family without a scene: from a pipeline built once at the start.
  for (const technique_family& family : technique_families())
    if (!family.draws_scene(o.common.scene_given) && (o.common.camera_pose || o.common.light_pose || o.common.light_intensity)) {
      viewer_family& state = options.scenes.families[family.name];
      std::unique_ptr<scene> none;
      const std::unique_ptr<pipeline> posed = make_posed_pipeline(shaders, o.common, *state.settings, none);
      state.view = posed->current_camera();
      state.lights = posed->current_lights();
    }
  return run_viewer(window, shaders, std::move(options), s.frames, s.frames > 0 && !s.screenshot.empty(), io.out);
}

}  // namespace

command add_view_command(CLI::App& app) {
  auto state = std::make_shared<view_state>();
  CLI::App* view = app.add_subcommand("view", "show any technique in a window with live controls (use xvfb-run without a display)");
  add_technique_options(*view, state->options);
  view->add_option("--frames", state->frames, "close after this many frames (0: when the window is closed)")
      ->check(CLI::NonNegativeNumber)->capture_default_str();
  view->add_option("--screenshot", state->screenshot,
                   "where the P key saves the window (.png; <stem>-indirect.pfm next to it) [output/<scene or object>-<technique>-view.png]; "
                   "with --frames, saved after the last frame as well");
  view->add_flag("--hide-panel", state->hide_panel, "start with the panel hidden (H shows it)");
  view->add_flag("--dock-panel", state->dock_panel, "put the panel in a column beside the image (the window is that much wider) instead of over it");
  return {view, [state](const session& io) { return run_view(io, *state); }, restorer(state)};
}

}  // namespace vplkit::cli
