// Scenes the frontend renders: triangle geometry with a diffuse albedo per vertex, a camera and a
// spot light. Built-in scenes are made in code, so the default job needs no files.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include <vplkit/direct_light.hpp>

namespace vplkit {

struct vertex {
  glm::vec3 position;
  glm::vec3 normal;
  glm::vec3 albedo;
};

struct mesh {
  std::vector<vertex> vertices;
  std::vector<std::uint32_t> indices;  // triangles, counter-clockwise seen from the normal side
};

struct camera {
  glm::vec3 position{0.0f, 1.0f, 3.8f};
  glm::vec3 target{0.0f, 1.0f, 0.0f};
  glm::vec3 up{0.0f, 1.0f, 0.0f};
  float vertical_fov_degrees = 40.0f;
  float near_plane = 0.05f;
  float far_plane = 20.0f;
};

struct scene {
  std::string name;
  mesh geometry;
  camera view;
  spot_light<float> light;
};

/// Names accepted by built_in_scene, for help texts and messages.
std::vector<std::string> built_in_scene_names();

/// The Cornell box (2 x 2 x 2, floor at y = 0, open towards +z) with a tall and a short block,
/// red left wall, green right wall, and a spot light under the ceiling pointing down.
scene make_cornell_box();

/// Throws vplkit::error listing the known names when `name` is not one of them.
scene built_in_scene(const std::string& name);

/// Appends an axis-aligned quad-faced box (outward normals), rotated about y by `yaw_degrees`.
void add_box(mesh& target, glm::vec3 centre, glm::vec3 size, float yaw_degrees, glm::vec3 albedo);

/// Appends the quad a, b, c, d (counter-clockwise seen from where `normal` points).
void add_quad(mesh& target, glm::vec3 a, glm::vec3 b, glm::vec3 c, glm::vec3 d, glm::vec3 normal, glm::vec3 albedo);

}  // namespace vplkit
