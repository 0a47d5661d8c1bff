#include "frontend/scene.hpp"

#include <cmath>

#include "frontend/error.hpp"

namespace vplkit {

void add_quad(mesh& target, glm::vec3 a, glm::vec3 b, glm::vec3 c, glm::vec3 d, glm::vec3 normal, glm::vec3 albedo) {
  const auto base = static_cast<std::uint32_t>(target.vertices.size());
  for (const glm::vec3& corner : {a, b, c, d}) target.vertices.push_back({corner, normal, albedo});
  for (std::uint32_t index : {0u, 1u, 2u, 0u, 2u, 3u}) target.indices.push_back(base + index);
}

void add_box(mesh& target, glm::vec3 centre, glm::vec3 size, float yaw_degrees, glm::vec3 albedo) {
  const float yaw = glm::radians(yaw_degrees);
  const glm::vec3 axis_x(std::cos(yaw), 0.0f, -std::sin(yaw));
  const glm::vec3 axis_y(0.0f, 1.0f, 0.0f);
  const glm::vec3 axis_z(std::sin(yaw), 0.0f, std::cos(yaw));
  const glm::vec3 hx = axis_x * (0.5f * size.x), hy = axis_y * (0.5f * size.y), hz = axis_z * (0.5f * size.z);
  auto corner = [&](float sx, float sy, float sz) { return centre + sx * hx + sy * hy + sz * hz; };
  add_quad(target, corner(-1, -1, 1), corner(1, -1, 1), corner(1, 1, 1), corner(-1, 1, 1), axis_z, albedo);      // front
  add_quad(target, corner(1, -1, -1), corner(-1, -1, -1), corner(-1, 1, -1), corner(1, 1, -1), -axis_z, albedo);  // back
  add_quad(target, corner(1, -1, 1), corner(1, -1, -1), corner(1, 1, -1), corner(1, 1, 1), axis_x, albedo);      // right
  add_quad(target, corner(-1, -1, -1), corner(-1, -1, 1), corner(-1, 1, 1), corner(-1, 1, -1), -axis_x, albedo);  // left
  add_quad(target, corner(-1, 1, 1), corner(1, 1, 1), corner(1, 1, -1), corner(-1, 1, -1), axis_y, albedo);      // top
  add_quad(target, corner(-1, -1, -1), corner(1, -1, -1), corner(1, -1, 1), corner(-1, -1, 1), -axis_y, albedo);  // bottom
}

scene make_cornell_box() {
  scene box;
  box.name = "cornell-box";
  const glm::vec3 white(0.73f), red(0.63f, 0.065f, 0.05f), green(0.14f, 0.45f, 0.091f);
  mesh& m = box.geometry;
  // Room interior: normals point into the room.
  add_quad(m, {-1, 0, 1}, {1, 0, 1}, {1, 0, -1}, {-1, 0, -1}, {0, 1, 0}, white);     // floor
  add_quad(m, {-1, 2, -1}, {1, 2, -1}, {1, 2, 1}, {-1, 2, 1}, {0, -1, 0}, white);    // ceiling
  add_quad(m, {-1, 0, -1}, {1, 0, -1}, {1, 2, -1}, {-1, 2, -1}, {0, 0, 1}, white);   // back wall
  add_quad(m, {-1, 0, 1}, {-1, 0, -1}, {-1, 2, -1}, {-1, 2, 1}, {1, 0, 0}, red);     // left wall
  add_quad(m, {1, 0, -1}, {1, 0, 1}, {1, 2, 1}, {1, 2, -1}, {-1, 0, 0}, green);      // right wall
  add_box(m, {-0.33f, 0.6f, -0.3f}, {0.58f, 1.2f, 0.58f}, 18.0f, white);           // tall block
  add_box(m, {0.36f, 0.3f, 0.36f}, {0.58f, 0.6f, 0.58f}, -17.0f, white);           // short block
  box.light.position = {0.0f, 1.92f, 0.0f};
  box.light.direction = {0.0f, -1.0f, 0.0f};
  box.light.intensity = glm::vec3(6.0f);
  box.light.cos_inner = std::cos(glm::radians(50.0f));
  box.light.cos_outer = std::cos(glm::radians(65.0f));
  return box;
}

std::vector<std::string> built_in_scene_names() { return {"cornell-box"}; }

scene built_in_scene(const std::string& name) {
  if (name == "cornell-box") return make_cornell_box();
  std::string known;
  for (const std::string& candidate : built_in_scene_names()) known += (known.empty() ? "" : ", ") + candidate;
  throw error("unknown scene '" + name + "' (built-in scenes: " + known + ")");
}

}  // namespace vplkit
