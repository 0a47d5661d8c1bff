#include "frontend/cli/technique_options.hpp"

#include "frontend/viewer/technique_view.hpp"

namespace vplkit::cli {

namespace {

bool reads_scene(const std::string& technique) { return !is_final_gather_technique(technique); }

bool reads_seed(const std::string& technique) {
  if (is_lightwave_technique(technique)) return technique == "lightwave-accurate";
  if (is_final_gather_technique(technique)) return false;
  return technique != "direct";
}

}  // namespace

void add_technique_options(CLI::App& command, technique_options& options, bool with_raw_indirect) {
  command
      .add_option("--technique", options.technique,
                  "rendering technique: direct and rsm-* (reflective shadow maps, docs/papers.md [RSMV]), lightwave-* (Light Wave, [LW]), "
                  "finalgather-* and envmap (robust final gathering, [FG])")
      ->check(CLI::IsMember(technique_names()))
      ->capture_default_str();
  options.scope.add(add_scene_option(command, options.common, "cornell-box; boxes for lightwave-*"), "the rsm-* and lightwave-* techniques", reads_scene);
  add_common_options(command, options.common, "512; 1280x720 for lightwave-*");
  add_pose_options(command, options.common);
  add_exposure_option(command, options.common);
  options.scope.add(command.add_option("--seed", options.common.seed, "seed of the sampling patterns (rsm-*) and of the accurate shadows' VPLs")
                        ->capture_default_str(),
                    "the rsm-* techniques and lightwave-accurate", reads_seed);
  add_rsm_frame_options(command, options.rsm, &options.scope);
  options.scope.add(command.get_option("--rsm-size"), "the RSM techniques (direct, rsm-*)", is_rsm_technique);
  add_rsm_gather_options(command, options.rsm, options.scope, with_raw_indirect);
  add_lightwave_options(command, options.lightwave, options.scope);
  add_final_gather_options(command, options.final_gather, options.scope);
}

}  // namespace vplkit::cli
