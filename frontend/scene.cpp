#include "frontend/scene.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <tuple>
#include <limits>

#include <cstdlib>
#include <filesystem>
#include <map>
#include <queue>

#include "frontend/error.hpp"
#include "frontend/obj_loader.hpp"

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

scene make_boxes_scene() {
  scene s;
  s.name = "boxes";
  add_box(s.geometry, {0.0f, -0.05f, 0.0f}, {3.0f, 0.1f, 3.0f}, 0.0f, white);                  // the floor slab
  add_box(s.geometry, {-0.45f, 0.35f, -0.2f}, {0.5f, 0.7f, 0.5f}, 20.0f, red);                // a tall red box
  add_box(s.geometry, {0.45f, 0.2f, 0.25f}, {0.6f, 0.4f, 0.6f}, -15.0f, green);               // a low green box
  s.view.position = {0.0f, 1.6f, 3.2f};
  s.view.target = {0.0f, 0.2f, 0.0f};
  s.view.vertical_fov_degrees = 45.0f;
  s.light.kind = light_kind::spot;
  s.light.spot.position = {0.6f, 2.2f, 0.8f};
  s.light.spot.direction = glm::normalize(glm::vec3(-0.6f, -2.2f, -0.8f));
  s.light.spot.intensity = glm::vec3(8.0f);
  s.light.spot.cos_inner = std::cos(glm::radians(35.0f));
  s.light.spot.cos_outer = std::cos(glm::radians(50.0f));
  return s;
}

mesh refine_longest_edges(const mesh& source, std::size_t target_triangles) {
  // Weld: one vertex per distinct position.
  mesh welded;
  std::map<std::tuple<float, float, float>, std::uint32_t> index_of;
  std::vector<glm::vec3> normal_sums;
  for (std::size_t corner = 0; corner < source.indices.size(); ++corner) {
    const vertex& v = source.vertices[source.indices[corner]];
    const auto key = std::make_tuple(v.position.x, v.position.y, v.position.z);
    auto [found, inserted] = index_of.emplace(key, static_cast<std::uint32_t>(welded.vertices.size()));
    if (inserted) {
      welded.vertices.push_back(v);
      normal_sums.push_back(glm::vec3(0.0f));
    }
    normal_sums[found->second] += v.normal;
    welded.indices.push_back(found->second);
  }
  for (std::size_t i = 0; i < welded.vertices.size(); ++i)
    if (glm::length(normal_sums[i]) > 0.0f) welded.vertices[i].normal = glm::normalize(normal_sums[i]);

  // Triangles as index triples; edges (low, high) -> the triangles that have them.
  std::vector<std::array<std::uint32_t, 3>> triangles;
  for (std::size_t t = 0; t + 2 < welded.indices.size(); t += 3)
    triangles.push_back({welded.indices[t], welded.indices[t + 1], welded.indices[t + 2]});
  using edge = std::pair<std::uint32_t, std::uint32_t>;
  const auto key_of = [](std::uint32_t a, std::uint32_t b) { return a < b ? edge(a, b) : edge(b, a); };
  std::map<edge, std::vector<std::size_t>> edges;
  const auto length_of = [&](const edge& e) { return glm::length(welded.vertices[e.first].position - welded.vertices[e.second].position); };
  std::priority_queue<std::pair<float, edge>> longest;
  const auto add_triangle_edges = [&](std::size_t t) {
    for (int k = 0; k < 3; ++k) {
      const edge e = key_of(triangles[t][static_cast<std::size_t>(k)], triangles[t][static_cast<std::size_t>((k + 1) % 3)]);
      edges[e].push_back(t);
      longest.emplace(length_of(e), e);
    }
  };
  for (std::size_t t = 0; t < triangles.size(); ++t) add_triangle_edges(t);
  const auto remove_triangle_edges = [&](std::size_t t) {
    for (int k = 0; k < 3; ++k) {
      auto& list = edges[key_of(triangles[t][static_cast<std::size_t>(k)], triangles[t][static_cast<std::size_t>((k + 1) % 3)])];
      list.erase(std::remove(list.begin(), list.end(), t), list.end());
    }
  };
  while (triangles.size() < target_triangles && !longest.empty()) {
    const edge e = longest.top().second;
    longest.pop();
    const auto found = edges.find(e);
    if (found == edges.end() || found->second.empty()) continue;  // split already
    const std::vector<std::size_t> sharing = found->second;
    const vertex& a = welded.vertices[e.first];
    const vertex& b = welded.vertices[e.second];
    const glm::vec3 normal_sum = a.normal + b.normal;
    const vertex middle{0.5f * (a.position + b.position), glm::length(normal_sum) > 0.0f ? glm::normalize(normal_sum) : a.normal,
                        0.5f * (a.albedo + b.albedo)};
    const auto m = static_cast<std::uint32_t>(welded.vertices.size());
    welded.vertices.push_back(middle);
    for (std::size_t t : sharing) {
      remove_triangle_edges(t);
      std::array<std::uint32_t, 3> tri = triangles[t];
      // Rotate so that the split edge is (tri[0], tri[1]), keeping the winding.
      while (key_of(tri[0], tri[1]) != e) tri = {tri[1], tri[2], tri[0]};
      triangles[t] = {tri[0], m, tri[2]};
      triangles.push_back({m, tri[1], tri[2]});
      add_triangle_edges(t);
      add_triangle_edges(triangles.size() - 1);
    }
    edges.erase(e);
  }
  mesh refined;
  refined.vertices = std::move(welded.vertices);
  for (const auto& tri : triangles) refined.indices.insert(refined.indices.end(), tri.begin(), tri.end());
  return refined;
}

scene make_teapot_scene(int copies) {
  namespace fs = std::filesystem;
  const char* from_environment = std::getenv("VPLKIT_MESH_DIR");
  const fs::path folder = from_environment && *from_environment ? fs::path(from_environment) : fs::path(VPLKIT_SOURCE_MESH_DIR);
  const fs::path path = folder / "teapot.obj";
  if (!fs::exists(path))
    throw error("scene " + std::string(copies == 1 ? "teapot" : "teapots") + " needs " + path.string() +
                " (scripts/setup.sh fetches the npm package teapot and converts it; or set VPLKIT_MESH_DIR)");
  mesh teapot = refine_longest_edges(load_obj(path), 6565);
  // The npm teapot is about 6.4 units wide; scale it to 0.6 and stand it on the floor.
  const bounding_box box = bounds(teapot);
  const float scale = 0.6f / std::max(box.maximum.x - box.minimum.x, 1e-6f);
  scene s;
  s.name = copies == 1 ? "teapot" : "teapots";
  const int columns = copies == 1 ? 1 : 5;
  for (int copy = 0; copy < copies; ++copy) {
    const glm::vec3 offset(copies == 1 ? 0.0f : -1.4f + 0.7f * static_cast<float>(copy % columns), 0.0f,
                           copies == 1 ? 0.0f : -0.35f + 0.7f * static_cast<float>(copy / columns));
    const auto base = static_cast<std::uint32_t>(s.geometry.vertices.size());
    for (vertex v : teapot.vertices) {
      v.position = (v.position - glm::vec3(box.centre().x, box.minimum.y, box.centre().z)) * scale + offset;
      v.albedo = copy % 2 == 0 ? glm::vec3(0.8f, 0.7f, 0.3f) : glm::vec3(0.3f, 0.5f, 0.8f);
      s.geometry.vertices.push_back(v);
    }
    for (std::uint32_t index : teapot.indices) s.geometry.indices.push_back(base + index);
  }
  add_box(s.geometry, {0.0f, -0.05f, 0.0f}, {copies == 1 ? 3.0f : 4.5f, 0.1f, 3.0f}, 0.0f, white);
  s.view.position = {0.0f, 1.4f, copies == 1 ? 2.0f : 3.4f};
  s.view.target = {0.0f, 0.2f, 0.0f};
  s.view.vertical_fov_degrees = 45.0f;
  s.light.kind = light_kind::spot;
  s.light.spot.position = {0.7f, 2.4f, 0.9f};
  s.light.spot.direction = glm::normalize(glm::vec3(-0.7f, -2.4f, -0.9f));
  s.light.spot.intensity = glm::vec3(8.0f);
  s.light.spot.cos_inner = std::cos(glm::radians(40.0f));
  s.light.spot.cos_outer = std::cos(glm::radians(55.0f));
  return s;
}

float spot_light_frustum_half_angle(const spot_light<float>& light) {
  return glm::min(std::acos(glm::clamp(light.cos_outer, -1.0f, 1.0f)) + glm::radians(2.0f), glm::radians(85.0f));
}

std::vector<std::string> built_in_scene_names() { return {"cornell-box", "indirect-shadow", "instanced", "boxes", "teapot", "teapots"}; }

scene built_in_scene(const std::string& name) {
  if (name == "cornell-box") return make_cornell_box();
  if (name == "indirect-shadow") return make_indirect_shadow_scene();
  if (name == "instanced") return make_instanced_scene();
  if (name == "boxes") return make_boxes_scene();
  if (name == "teapot") return make_teapot_scene(1);
  if (name == "teapots") return make_teapot_scene(10);
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
