// The scene of the final-gathering techniques, built on the CPU: the box room and the dynamic
// object, kept apart (the cube map leaves the object out).
#pragma once

#include <string>

#include <glm/glm.hpp>

#include <vplkit/direct_light.hpp>

#include "frontend/scene/camera.hpp"
#include "frontend/scene/scene.hpp"

namespace vplkit {

/// The room (the environment) and the dynamic object, kept apart: the cube map leaves the object out.
struct final_gather_scene {
  std::string name;
  /// What make_final_gather_scene was given ("sphere" or the .obj file) and the object's size:
  /// the setup a new scene comes from (final_gather_pipeline::apply_settings keeps the scene
  /// only while they are the same). Empty for a scene made otherwise.
  std::string object_source;
  float object_size = 0.0f;
  mesh room;
  mesh object;
  /// The object centred at the origin, scaled: `object` is it moved to the reference point, the
  /// same sum wherever it moves, so a moved object is the object built at its new place, bit for bit.
  mesh local_object;
  glm::vec3 reference_point{0.0f};  ///< the object's centre (its bounding box's)
  float object_radius = 0.0f;       ///< of its bounding sphere around the reference point
  camera view;
  spot_light<float> light;
};

/// The Cornell room without its blocks, closed by a front wall, the object ("sphere": 2304 triangles, or an OBJ file
/// such as the npm bunny) scaled to `size` across and centred at `position`. Throws
/// vplkit::error when the object file fails to load.
final_gather_scene make_final_gather_scene(const std::string& object, glm::vec3 position, float size);

}  // namespace vplkit
