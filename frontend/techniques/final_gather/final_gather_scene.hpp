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
