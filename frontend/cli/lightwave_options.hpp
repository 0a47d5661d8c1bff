// The Light Wave techniques of `vplkit render` ([LW]: lightwave-direct, -faked,
// -unshadowed, -accurate, -integrated): their options, each scoped to the techniques that read
// it, the pipeline settings made from them, and the images `render` writes.
#pragma once

#include <string>

#include "frontend/cli/options.hpp"
#include "frontend/techniques/lightwave/lightwave_pipeline.hpp"

namespace vplkit::cli {

struct lightwave_options {
  lightwave_settings settings;             ///< the fields the options below set
  std::string shadow_variant = "importance";
  std::string energy = "flux";
};

/// Whether `technique` is one of the Light Wave family.
bool is_lightwave_technique(const std::string& technique);

/// The scene the Light Wave techniques render: --scene, else boxes.
std::string lightwave_scene_name(const common_options& common);

/// --ray-angle, --vpls-per-ray, --vpl-energy, --vpl-max-distance, --shadow-maps, --shadow-variant,
/// --integrated-steps, --shadow-map-scale, --faked-multiplier.
void add_lightwave_options(CLI::App& command, lightwave_options& options, option_scope& scope);

/// The pipeline settings for `technique`. Throws usage_error for settings the pipeline rejects.
lightwave_settings make_lightwave_settings(const std::string& technique, const common_options& common, const lightwave_options& options);

/// `vplkit render` for a Light Wave technique: the final image and, with shadow casters, the
/// indirect shadow factor as grey (<out>-indirect-shadow.png), and the pass times of a frame
/// after the light moved and of one where nothing did.
int render_lightwave(const session& io, const std::string& technique, const common_options& common, const lightwave_options& options,
                     const std::string& out);

}  // namespace vplkit::cli
