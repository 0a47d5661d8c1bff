// vplkit view: the RSM pipeline in a window, frame after frame (xvfb-run without a display).
#include "frontend/cli/commands.hpp"
#include "frontend/cli/rsm_options.hpp"
#include "frontend/core/named_table.hpp"
#include "frontend/gl/debug_output.hpp"

namespace vplkit::cli {

namespace {

struct view_state {
  std::string technique = rsm_pipeline_settings().technique;
  common_options common;
  rsm_options rsm;
  option_scope scope;
  int frames = 0;
};

}  // namespace

command add_view_command(CLI::App& app) {
  auto state = std::make_shared<view_state>();
  CLI::App* view = app.add_subcommand("view", "show an RSM technique in a window (use xvfb-run without a display)");
  view->add_option("--technique", state->technique, "RSM technique (direct, rsm-*)")->check(CLI::IsMember(names_of(rsm_techniques())))->capture_default_str();
  add_scene_option(*view, state->common, "cornell-box");
  add_common_options(*view, state->common, "512");
  state->scope.add(view->add_option("--seed", state->common.seed, "seed of the sampling patterns")->capture_default_str(), "the rsm-* techniques",
                   [](const std::string& technique) { return technique != "direct"; });
  add_rsm_frame_options(*view, state->rsm, &state->scope);
  add_rsm_gather_options(*view, state->rsm, state->scope, false);
  view->add_option("--frames", state->frames, "close after this many frames (0: when the window is closed)")
      ->check(CLI::NonNegativeNumber)->capture_default_str();
  return {view, [state](const session& io) {
            const view_state& s = *state;
            s.scope.require_read_by(s.technique, "technique");
            const rsm_pipeline_settings settings = make_rsm_settings(s.technique, s.common, s.rsm);
            if (io.dry_run) return 0;
            window_context window(settings.width, settings.height, "vplkit - " + s.common.scene);
            const shader_library shaders(s.common.shaders());
            rsm_pipeline pipeline(shaders, load_scene(s.common.scene), settings);
            program present = load_program(shaders, "fullscreen.vert", "present.frag");
            gl_vertex_array empty_vertex_array(generate_vertex_array());
            for (int frame = 0; (s.frames == 0 || frame < s.frames) && !window.should_close(); ++frame) {
              pipeline.render();
              const auto [width, height] = window.framebuffer_size();
              glBindFramebuffer(GL_FRAMEBUFFER, 0);
              glViewport(0, 0, width, height);
              present.set("image", 0);
              pipeline.output().bind(0);
              present.use();
              glBindVertexArray(empty_vertex_array.get());
              glDrawArrays(GL_TRIANGLES, 0, 3);
              check_gl("presenting a frame");
              window.swap_and_poll();
            }
            io.out << "closed the window after showing scene " << s.common.scene << "\n";
            return 0;
          }};
}

}  // namespace vplkit::cli
