// vplkit render: one frame of any technique, headless, to images. --technique picks the family
// (rsm_options, lightwave_options, final_gather_options); each family registers its own options,
// scoped to the techniques that read them, so that an option the technique ignores is an error.
#include "frontend/cli/commands.hpp"
#include "frontend/cli/technique_options.hpp"

namespace vplkit::cli {

namespace {

struct render_state {
  technique_options options;
  std::string out;
};

}  // namespace

command add_render_command(CLI::App& app) {
  auto state = std::make_shared<render_state>();
  CLI::App* render = app.add_subcommand("render", "render a scene headless to PNG images (and the linear indirect light as PFM)");
  add_technique_options(*render, state->options, true);
  add_rsm_sequence_options(*render, state->options.rsm, state->options.scope);
  render->add_option("--out", state->out, "final image path (.png; folders are created) [output/<scene or object>-<technique>.png]; the other "
                                          "images go next to it");
  return {render, [state](const session& io) {
            const technique_options& o = state->options;
            o.scope.require_read_by(o.technique, "technique");
            if (is_lightwave_technique(o.technique)) return render_lightwave(io, o.technique, o.common, o.lightwave, state->out);
            if (is_final_gather_technique(o.technique)) return render_final_gather(io, o.technique, o.common, o.final_gather, state->out);
            return render_rsm(io, o.technique, o.common, o.rsm, state->out);
          }};
}

}  // namespace vplkit::cli
