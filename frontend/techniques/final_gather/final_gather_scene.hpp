// The scene of the final-gathering techniques, built on the CPU: the box room and the dynamic
// object, kept apart (the cube map leaves the object out).
#pragma once

#include <string>
#include <vector>

#include <glm/glm.hpp>

#include <vplkit/direct_light.hpp>

#include "frontend/scene/camera.hpp"
#include "frontend/scene/scene.hpp"
#include "frontend/techniques/final_gather/final_gather_settings.hpp"

namespace vplkit {

/// The room (the environment) and the dynamic object, kept apart: the cube map leaves the object out.
struct final_gather_scene {
  std::string name;
  /// object_key of the setup make_final_gather_scene was given: the object's source and placement
  /// (final_gather_pipeline::apply_settings keeps the scene only while it is the same).
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
  /// The environment's lights (none: unlit), each lighting the cube map's faces and the view's
  /// direct light with its own shadows; the pipeline sums them.
  std::vector<scene_light> lights;
};

/// The Cornell room without its blocks, closed by a front wall, the object ("sphere": 2304 triangles, or an OBJ file
/// such as the npm bunny) scaled to `size` across and centred at `position`. Throws
/// vplkit::error when the object file fails to load.
final_gather_scene make_final_gather_scene(const std::string& object, glm::vec3 position, float size);

/// The built-in room above as a scene (its geometry, the Cornell box's camera and spot): what
/// make_final_gather_scene(object, ...) gathers in, so that the same room written as glTF and
/// given as --scene gathers the same light.
scene final_gather_box();

/// The user's scene as the environment (--scene): its geometry (every triangle: the object is
/// not part of it), its camera and all its lights (spots, point lights, suns, or none), lighting
/// the cube map's faces with direct light as for the box; the object as above. Throws
/// vplkit::error naming the scene for an invalid light or a scene without triangles. A position
/// inside geometry or outside the scene is found by the pipeline's cube-map check.
final_gather_scene make_final_gather_scene(const scene& environment, const std::string& object, glm::vec3 position, float size);

/// The scene of a setup: the environment (`environment`, or the built-in room when null) and the
/// object: the node setup.object_node names, taken out of the environment with its materials
/// (its subtree's triangles; an unknown name is refused with the scene's node names), or
/// setup.object; placed by setup.object_at (the bottom centre of its bounding box at x,y,z,
/// scaled; refused when the box leaves the scene's bounds), else a node where the scene has it,
/// else a file's object setup.object_size across, centred at setup.object_position. Throws
/// vplkit::error naming the scene and what is wrong.
final_gather_scene make_final_gather_scene(const scene* environment, const final_gather_setup& setup);

}  // namespace vplkit
