// The final-gathering techniques of `vplkit render` ([FG]: finalgather-polygon,
// finalgather-point and the envmap baseline): their options, the pipeline settings made from
// them, and the images `render` writes. They render their own room around one dynamic object,
// so they read no --scene.
#pragma once

#include <string>

#include "frontend/cli/options.hpp"
#include "frontend/techniques/final_gather/final_gather_pipeline.hpp"

namespace vplkit::cli {

struct final_gather_options {
  final_gather_settings settings;  ///< resolution and face size from the options below
  std::string object = "sphere";
  std::string object_position_text = "0,0.7,0";
  glm::vec3 object_position{0.0f, 0.7f, 0.0f};
  float object_size = 0.5f;
};

/// Largest coordinate of --object-position: the room is [-1, 1] x [0, 2] x [-1, 1].
constexpr float max_object_coordinate = 1000.0f;

/// Whether `technique` is one of the final-gathering family.
bool is_final_gather_technique(const std::string& technique);

/// --object, --object-position, --object-size, --cube-resolution, --face-size.
void add_final_gather_options(CLI::App& command, final_gather_options& options, option_scope& scope);

/// The pipeline settings for `technique`. Throws usage_error for settings the pipeline rejects.
final_gather_settings make_final_gather_settings(const std::string& technique, const common_options& common, const final_gather_options& options);

/// `vplkit render` for a final-gathering technique: the final image and the object's indirect
/// irradiance (<out>-indirect.png).
int render_final_gather(const session& io, const std::string& technique, const common_options& common, const final_gather_options& options,
                        const std::string& out);

}  // namespace vplkit::cli
