#include "frontend/scene.hpp"

#include <cmath>
#include <limits>

#include "frontend/error.hpp"

namespace vplkit {

bounding_box bounds(const mesh& geometry) {
  bounding_box box;
  box.minimum = glm::vec3(std::numeric_limits<float>::max());
  box.maximum = glm::vec3(std::numeric_limits<float>::lowest());
  for (const vertex& v : geometry.vertices) {
    box.minimum = glm::min(box.minimum, v.position);
    box.maximum = glm::max(box.maximum, v.position);
  }
  if (geometry.vertices.empty()) box = {};
  return box;
}

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

void add_sphere(mesh& target, glm::vec3 centre, float radius, int stacks, int slices, glm::vec3 albedo) {
  const auto base = static_cast<std::uint32_t>(target.vertices.size());
  const float pi = 3.14159265358979f;
  for (int i = 0; i <= stacks; ++i) {
    const float polar = pi * static_cast<float>(i) / static_cast<float>(stacks);
    for (int j = 0; j <= slices; ++j) {
      const float azimuth = 2.0f * pi * static_cast<float>(j) / static_cast<float>(slices);
      const glm::vec3 normal(std::sin(polar) * std::cos(azimuth), std::cos(polar), -std::sin(polar) * std::sin(azimuth));
      target.vertices.push_back({centre + radius * normal, normal, albedo});
    }
  }
  const auto row = static_cast<std::uint32_t>(slices + 1);
  for (std::uint32_t i = 0; i < static_cast<std::uint32_t>(stacks); ++i) {
    for (std::uint32_t j = 0; j < static_cast<std::uint32_t>(slices); ++j) {
      const std::uint32_t a = base + i * row + j, b = a + row, c = b + 1, d = a + 1;
      for (std::uint32_t index : {a, b, c, a, c, d}) target.indices.push_back(index);
    }
  }
}

namespace {

const glm::vec3 white(0.73f), red(0.63f, 0.065f, 0.05f), green(0.14f, 0.45f, 0.091f);

void add_cornell_room(mesh& m) {
  // Room interior: normals point into the room.
  add_quad(m, {-1, 0, 1}, {1, 0, 1}, {1, 0, -1}, {-1, 0, -1}, {0, 1, 0}, white);     // floor
  add_quad(m, {-1, 2, -1}, {1, 2, -1}, {1, 2, 1}, {-1, 2, 1}, {0, -1, 0}, white);    // ceiling
  add_quad(m, {-1, 0, -1}, {1, 0, -1}, {1, 2, -1}, {-1, 2, -1}, {0, 0, 1}, white);   // back wall
  add_quad(m, {-1, 0, 1}, {-1, 0, -1}, {-1, 2, -1}, {-1, 2, 1}, {1, 0, 0}, red);     // left wall
  add_quad(m, {1, 0, -1}, {1, 0, 1}, {1, 2, 1}, {1, 2, -1}, {-1, 0, 0}, green);      // right wall
}

spot_light<float> ceiling_spot() {
  spot_light<float> light;
  light.position = {0.0f, 1.92f, 0.0f};
  light.direction = {0.0f, -1.0f, 0.0f};
  light.intensity = glm::vec3(6.0f);
  light.cos_inner = std::cos(glm::radians(50.0f));
  light.cos_outer = std::cos(glm::radians(65.0f));
  return light;
}

}  // namespace

scene make_cornell_box() {
  scene box;
  box.name = "cornell-box";
  add_cornell_room(box.geometry);
  add_box(box.geometry, {-0.33f, 0.6f, -0.3f}, {0.58f, 1.2f, 0.58f}, 18.0f, white);   // tall block
  add_box(box.geometry, {0.36f, 0.3f, 0.36f}, {0.58f, 0.6f, 0.58f}, -17.0f, white);   // short block
  box.light.kind = light_kind::spot;
  box.light.spot = ceiling_spot();
  return box;
}

scene make_indirect_shadow_scene() {
  scene s;
  s.name = "indirect-shadow";
  mesh& m = s.geometry;
  add_quad(m, {-2, 0, 2}, {2, 0, 2}, {2, 0, -2}, {-2, 0, -2}, {0, 1, 0}, white);          // floor (receiver)
  add_quad(m, {-1.5f, 0, 1.5f}, {-1.5f, 0, -1.5f}, {-1.5f, 2, -1.5f}, {-1.5f, 2, 1.5f}, {1, 0, 0}, red);  // lit wall
  add_box(m, {-0.6f, 0.45f, 0.0f}, {0.06f, 0.9f, 1.0f}, 0.0f, white);                     // occluding panel
  s.view.position = {1.2f, 2.6f, 4.2f};
  s.view.target = {-0.3f, 0.3f, 0.0f};
  s.view.vertical_fov_degrees = 45.0f;
  s.light.kind = light_kind::directional;
  s.light.directional.direction = glm::normalize(glm::vec3(-1.0f, -0.45f, 0.0f));
  s.light.directional.irradiance = glm::vec3(3.0f);
  return s;
}

scene make_instanced_scene() {
  scene s;
  s.name = "instanced";
  add_cornell_room(s.geometry);
  for (int i = 0; i < 16; ++i)
    for (int j = 0; j < 16; ++j) {
      const glm::vec3 centre(-0.9f + 0.12f * static_cast<float>(i), 0.05f, -0.9f + 0.12f * static_cast<float>(j));
      add_sphere(s.geometry, centre, 0.05f, 16, 32, (i + j) % 2 == 0 ? white : glm::vec3(0.2f, 0.3f, 0.7f));
    }
  s.light.kind = light_kind::spot;
  s.light.spot = ceiling_spot();
  return s;
}

std::vector<std::string> built_in_scene_names() { return {"cornell-box", "indirect-shadow", "instanced"}; }

scene built_in_scene(const std::string& name) {
  if (name == "cornell-box") return make_cornell_box();
  if (name == "indirect-shadow") return make_indirect_shadow_scene();
  if (name == "instanced") return make_instanced_scene();
  std::string known;
  for (const std::string& candidate : built_in_scene_names()) known += (known.empty() ? "" : ", ") + candidate;
  throw error("unknown scene '" + name + "' (built-in scenes: " + known + ", or a path to an .obj file)");
}

scene frame_mesh(std::string name, mesh geometry) {
  scene s;
  s.name = std::move(name);
  const bounding_box box = bounds(geometry);
  const float radius = std::max(box.radius(), 1e-3f);
  // A floor under the mesh gives its light somewhere to bounce.
  const float floor_y = box.minimum.y;
  const glm::vec3 c = box.centre();
  const float extent = 3.0f * radius;
  add_quad(geometry, {c.x - extent, floor_y, c.z + extent}, {c.x + extent, floor_y, c.z + extent},
           {c.x + extent, floor_y, c.z - extent}, {c.x - extent, floor_y, c.z - extent}, {0, 1, 0}, white);
  s.geometry = std::move(geometry);
  s.view.target = c;
  s.view.position = c + glm::vec3(0.0f, 0.6f * radius, 3.2f * radius);
  s.view.near_plane = 0.02f * radius;
  s.view.far_plane = 20.0f * radius;
  s.light.kind = light_kind::spot;
  s.light.spot.position = c + glm::vec3(0.8f * radius, 2.5f * radius, 0.8f * radius);
  s.light.spot.direction = glm::normalize(glm::vec3(c.x, floor_y, c.z) - s.light.spot.position);
  s.light.spot.intensity = glm::vec3(6.0f * radius * radius);
  s.light.spot.cos_inner = std::cos(glm::radians(35.0f));
  s.light.spot.cos_outer = std::cos(glm::radians(50.0f));
  return s;
}

}  // namespace vplkit
