// The final-gathering family's settings: its techniques, the pipeline's settings and the setup
// around them (the object in the room), the table every option, control and sweep axis comes from
// (frontend/core/setting.hpp) and validate(). The pipeline (final_gather_pipeline.hpp) draws them.
#pragma once

#include <string>
#include <vector>

#include <glm/glm.hpp>

#include <vplkit/irradiance.hpp>

#include "frontend/core/setting.hpp"
#include "frontend/gl/render_target.hpp"

namespace vplkit {

enum class final_gather_variant { polygon = 0, point = 1, environment_map = 2 };

struct final_gather_technique {
  const char* name = "";
  final_gather_variant variant = final_gather_variant::polygon;
  const char* description = "";
};

/// finalgather-polygon, finalgather-point, envmap.
const std::vector<final_gather_technique>& final_gather_techniques();
const final_gather_technique& find_final_gather_technique(const std::string& name);

/// The largest cube face: the six faces lie side by side in one texture, at most max_image_side wide.
inline constexpr int max_cube_face_size = max_image_side / 6;

struct final_gather_settings {
  std::string technique = "finalgather-polygon";
  int width = 512;               ///< the paper: 700 x 700
  int height = 512;
  int face_size = 256;           ///< the cube map's faces (the paper: 256)
  int resolution = 4;            ///< M: the faces averaged down to M x M (the paper: 4 or 2)
  int environment_resolution = 16;  ///< K x K per face of the baseline's irradiance map
  irradiance_settings<float> irradiance;
  texel_format format = texel_format::rgba32f;
};

std::string validate(const final_gather_settings& settings);

/// The largest coordinate of the object's position: the room is [-1, 1] x [0, 2] x [-1, 1].
constexpr float max_object_coordinate = 1000.0f;

/// What the final-gathering techniques draw and how: the object in the room, and the pipeline's
/// settings. The family's settings (frontend/techniques/registry.hpp) are this.
struct final_gather_setup {
  final_gather_settings pipeline;
  std::string object = "sphere";                 ///< sphere, or an .obj file (meshes/bunny.obj)
  glm::vec3 object_position{0.0f, 0.7f, 0.0f};  ///< its centre
  float object_size = 0.5f;                      ///< across (the room is 2 wide)
  /// --object-node: a named node of --scene's glTF (with its subtree) as the object, taken out of
  /// the environment with its materials; empty (the option's "none"): `object`.
  std::string object_node;
  /// --object-at "x,y,z[,scale]": the bottom centre of the object's bounding box at x,y,z, the
  /// object scale times its own size (the node's as the scene has it, the file's in its units);
  /// instead of object_position and object_size. Empty (the option's "none"): those.
  std::string object_at;
};

/// --object-at parsed: where the bottom centre of the object's bounding box goes, and its scale.
struct object_placement {
  glm::vec3 bottom_centre{0.0f};
  float scale = 1.0f;
};

/// --object-at's text as a placement, or the problem ("expected x,y,z or x,y,z,scale, not ...",
/// a value that is not finite or beyond max_object_coordinate, a scale <= 0).
std::string parse_object_at(const std::string& text, object_placement& placement);

/// What makes a final_gather_scene from a setup: the object's source and placement (a pipeline
/// applies settings in place only while it is the same).
std::string object_key(const final_gather_setup& setup);

/// The description of every setting a user sets (frontend/core/setting.hpp).
const std::vector<setting<final_gather_setup, final_gather_technique>>& final_gather_settings_table();

/// Empty when usable: the table's ranges, then the pipeline's settings.
std::string validate(const final_gather_setup& setup);

}  // namespace vplkit
