// vplkit render: one frame of any technique, headless, to images. --technique picks the family
// (rsm_options, lightwave_options, final_gather_options); each family registers its own options,
// scoped to the techniques that read them, so that an option the technique ignores is an error.
#include "frontend/cli/commands.hpp"
#include "frontend/cli/final_gather_options.hpp"
#include "frontend/cli/lightwave_options.hpp"
#include "frontend/cli/rsm_options.hpp"
#include "frontend/core/named_table.hpp"

namespace vplkit::cli {

namespace {

struct render_state {
  std::string technique = rsm_pipeline_settings().technique;
  std::string out;
  common_options common;
  rsm_options rsm;
  lightwave_options lightwave;
  final_gather_options final_gather;
  option_scope scope;
};

bool reads_scene(const std::string& technique) { return !is_final_gather_technique(technique); }

bool reads_seed(const std::string& technique) {
  if (is_lightwave_technique(technique)) return technique == "lightwave-accurate";
  if (is_final_gather_technique(technique)) return false;
  return technique != "direct";
}

}  // namespace

command add_render_command(CLI::App& app) {
  auto state = std::make_shared<render_state>();
  CLI::App* render = app.add_subcommand("render", "render a scene headless to PNG images (and the linear indirect light as PFM)");
  std::vector<std::string> techniques = names_of(rsm_techniques());
  for (const std::string& name : names_of(lightwave_techniques())) techniques.push_back(name);
  for (const std::string& name : names_of(final_gather_techniques())) techniques.push_back(name);
  render->add_option("--technique", state->technique,
                     "rendering technique: direct and rsm-* (reflective shadow maps, docs/papers.md [RSMV]), lightwave-* (Light Wave, [LW]), "
                     "finalgather-* and envmap (robust final gathering, [FG])")
      ->check(CLI::IsMember(techniques))->capture_default_str();
  state->scope.add(add_scene_option(*render, state->common, "cornell-box; boxes for lightwave-*"), "the rsm-* and lightwave-* techniques", reads_scene);
  add_common_options(*render, state->common, "512; 1280x720 for lightwave-*");
  state->scope.add(render->add_option("--seed", state->common.seed, "seed of the sampling patterns (rsm-*) and of the accurate shadows' VPLs")
                       ->capture_default_str(),
                   "the rsm-* techniques and lightwave-accurate", reads_seed);
  add_rsm_frame_options(*render, state->rsm, &state->scope);
  state->scope.add(render->get_option("--rsm-size"), "the RSM techniques (direct, rsm-*)", is_rsm_technique);
  add_rsm_gather_options(*render, state->rsm, state->scope, true);
  add_lightwave_options(*render, state->lightwave, state->scope);
  add_final_gather_options(*render, state->final_gather, state->scope);
  render->add_option("--out", state->out, "final image path (.png; folders are created) [output/<scene or object>-<technique>.png]; the other "
                                          "images go next to it");
  return {render, [state](const session& io) {
            const render_state& s = *state;
            s.scope.require_read_by(s.technique, "technique");
            if (is_lightwave_technique(s.technique)) return render_lightwave(io, s.technique, s.common, s.lightwave, s.out);
            if (is_final_gather_technique(s.technique)) return render_final_gather(io, s.technique, s.common, s.final_gather, s.out);
            return render_rsm(io, s.technique, s.common, s.rsm, s.out);
          }};
}

}  // namespace vplkit::cli
