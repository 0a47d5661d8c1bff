// vplkit view: any technique in a window with live controls (frontend/viewer/viewer.hpp); use
// xvfb-run without a display. It takes render's options (technique_options), so a pose or a
// setting seen in the window renders headless with the same arguments.
#include <algorithm>

#include "frontend/cli/commands.hpp"
#include "frontend/cli/output.hpp"
#include "frontend/cli/technique_options.hpp"
#include "frontend/core/named_table.hpp"
#include "frontend/viewer/viewer.hpp"

namespace vplkit::cli {

namespace {

struct view_state {
  technique_options options;
  int frames = 0;
  std::string screenshot;
  bool hide_panel = false;
};

}  // namespace

command add_view_command(CLI::App& app) {
  auto state = std::make_shared<view_state>();
  CLI::App* view = app.add_subcommand("view", "show any technique in a window with live controls (use xvfb-run without a display)");
  add_technique_options(*view, state->options, false);
  view->add_option("--frames", state->frames, "close after this many frames (0: when the window is closed)")
      ->check(CLI::NonNegativeNumber)->capture_default_str();
  view->add_option("--screenshot", state->screenshot,
                   "where the P key saves the window (.png; <stem>-indirect.pfm next to it) [output/<scene or object>-<technique>-view.png]; "
                   "with --frames, saved after the last frame as well");
  view->add_flag("--hide-panel", state->hide_panel, "start with the panel hidden (H shows it)");
  return {view, [state](const session& io) {
            const view_state& s = *state;
            const technique_options& o = s.options;
            o.scope.require_read_by(o.technique, "technique");
            const bool final_gather = is_final_gather_technique(o.technique);
            const std::string shown_scene = final_gather ? o.final_gather.object : is_lightwave_technique(o.technique) ? lightwave_scene_name(o.common) : o.common.scene;
            output_set files(s.screenshot, "output/" + std::filesystem::path(shown_scene).stem().string() + "-" + o.technique + "-view.png", ".png",
                             "--screenshot", "<stem>-indirect.pfm goes next to it");
            // Every family's settings from the same options, so that the panel can switch to any
            // technique; the chosen family's are checked here (a usage error, exit 2).
            viewer_options options;
            options.technique = o.technique;
            options.panel = !s.hide_panel;
            options.screenshot = files.main();
            viewer_scenes& scenes = options.scenes;
            const auto family_settings = [&](const std::vector<std::string>& names, auto make) {
              const bool chosen = std::find(names.begin(), names.end(), o.technique) != names.end();
              return make(chosen ? o.technique : names.front());
            };
            scenes.rsm_setup = family_settings(names_of(rsm_techniques()), [&](const std::string& t) { return make_rsm_settings(t, o.common, o.rsm); });
            scenes.lightwave_setup =
                family_settings(names_of(lightwave_techniques()), [&](const std::string& t) { return make_lightwave_settings(t, o.common, o.lightwave); });
            scenes.final_gather_setup = family_settings(names_of(final_gather_techniques()),
                                                           [&](const std::string& t) { return make_final_gather_settings(t, o.common, o.final_gather); });
            // One window size for every family: the chosen technique's.
            const glm::ivec2 size = final_gather                           ? glm::ivec2(scenes.final_gather_setup.width, scenes.final_gather_setup.height)
                                    : is_lightwave_technique(o.technique) ? glm::ivec2(scenes.lightwave_setup.width, scenes.lightwave_setup.height)
                                                                          : glm::ivec2(scenes.rsm_setup.width, scenes.rsm_setup.height);
            scenes.rsm_setup.width = scenes.lightwave_setup.width = scenes.final_gather_setup.width = size.x;
            scenes.rsm_setup.height = scenes.lightwave_setup.height = scenes.final_gather_setup.height = size.y;
            if (io.dry_run) return 0;

            scenes.rsm = load_scene(o.common, o.common.scene);
            const std::string lightwave_scene = lightwave_scene_name(o.common);
            scenes.lightwave = lightwave_scene == o.common.scene ? scenes.rsm : load_scene(o.common, lightwave_scene);
            scenes.final_gather = make_final_gather_scene(o.final_gather.object, o.final_gather.object_position, o.final_gather.object_size);
            apply_poses(o.common, scenes.final_gather.view, scenes.final_gather.light);
            window_context window(size.x, size.y, "vplkit view - " + shown_scene);
            const shader_library shaders(o.common.shaders());
            return run_viewer(window, shaders, std::move(options), s.frames, s.frames > 0 && !s.screenshot.empty(), io.out);
          }, restorer(state)};
}

}  // namespace vplkit::cli
