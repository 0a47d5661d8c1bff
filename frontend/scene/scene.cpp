#include "frontend/scene/scene.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <tuple>
#include <limits>

#include <cstdlib>
#include <filesystem>
#include <map>
#include <queue>

#include "frontend/core/error.hpp"
#include "frontend/scene/obj_loader.hpp"

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

}  // namespace

void add_cornell_room(mesh& m) {
  // Room interior: normals point into the room.
  add_quad(m, {-1, 0, 1}, {1, 0, 1}, {1, 0, -1}, {-1, 0, -1}, {0, 1, 0}, white);     // floor
  add_quad(m, {-1, 2, -1}, {1, 2, -1}, {1, 2, 1}, {-1, 2, 1}, {0, -1, 0}, white);    // ceiling
  add_quad(m, {-1, 0, -1}, {1, 0, -1}, {1, 2, -1}, {-1, 2, -1}, {0, 0, 1}, white);   // back wall
  add_quad(m, {-1, 0, 1}, {-1, 0, -1}, {-1, 2, -1}, {-1, 2, 1}, {1, 0, 0}, red);     // left wall
  add_quad(m, {1, 0, -1}, {1, 0, 1}, {1, 2, 1}, {1, 2, -1}, {-1, 0, 0}, green);      // right wall
}

namespace {

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
  // The thesis gives no intensity. Light Wave's indirect light does not scale with the light
  // (Eq. 4.5 has no flux), so the intensity sets the share of direct light in the image; 1 puts
  // "direct lighting only" at 85.7 % similar to the default (1280 x 720), near the thesis's
  // 84.4 % (Table 5.9), the one number used to choose it.
  s.light.spot.intensity = glm::vec3(1.0f);
  s.light.spot.cos_inner = std::cos(glm::radians(35.0f));
  s.light.spot.cos_outer = std::cos(glm::radians(50.0f));
  return s;
}

scene make_occluder_scene(bool dark_panel) {
  scene s;
  s.name = dark_panel ? "occluder" : "occluder-white";
  mesh& m = s.geometry;
  add_quad(m, {-1.5f, 0, 1.5f}, {1.5f, 0, 1.5f}, {1.5f, 0, -1.5f}, {-1.5f, 0, -1.5f}, {0, 1, 0}, white);              // floor
  add_quad(m, {-1.5f, 0, 1.5f}, {-1.5f, 0, -1.5f}, {-1.5f, 2, -1.5f}, {-1.5f, 2, 1.5f}, {1, 0, 0}, red);                // lit wall
  add_box(m, {-1.0f, 0.35f, 0.0f}, {0.04f, 0.7f, 1.4f}, 0.0f, dark_panel ? glm::vec3(0.03f) : white);                  // the panel
  s.view.position = {1.7f, 1.6f, 2.7f};
  s.view.target = {-0.7f, 0.3f, 0.0f};
  s.view.vertical_fov_degrees = 45.0f;
  s.light.kind = light_kind::spot;
  s.light.spot.position = {1.2f, 1.7f, 0.0f};
  s.light.spot.direction = glm::normalize(glm::vec3(-1.5f, 0.6f, 0.0f) - s.light.spot.position);
  s.light.spot.intensity = glm::vec3(9.0f);
  s.light.spot.cos_inner = std::cos(glm::radians(35.0f));
  s.light.spot.cos_outer = std::cos(glm::radians(50.0f));
  return s;
}

void add_cylinder(mesh& target, glm::vec3 base, float radius, float height, int segments, int stacks, glm::vec3 albedo) {
  const auto first = static_cast<std::uint32_t>(target.vertices.size());
  const float pi = 3.14159265358979f;
  for (int i = 0; i <= stacks; ++i)
    for (int j = 0; j <= segments; ++j) {
      const float angle = 2.0f * pi * static_cast<float>(j) / static_cast<float>(segments);
      const glm::vec3 normal(std::cos(angle), 0.0f, -std::sin(angle));
      target.vertices.push_back({base + radius * normal + glm::vec3(0.0f, height * static_cast<float>(i) / static_cast<float>(stacks), 0.0f), normal, albedo});
    }
  const auto row = static_cast<std::uint32_t>(segments + 1);
  for (std::uint32_t i = 0; i < static_cast<std::uint32_t>(stacks); ++i)
    for (std::uint32_t j = 0; j < static_cast<std::uint32_t>(segments); ++j) {
      const std::uint32_t a = first + i * row + j, b = a + 1, c = b + row, d = a + row;
      for (std::uint32_t index : {a, b, c, a, c, d}) target.indices.push_back(index);
    }
}

namespace {

// A wall in the plane z = z0 between x0 and x1, from y = spring to y = top, with a semicircular
// opening of diameter x1 - x0 springing at y = spring: both faces (normals +z and -z, `depth`
// apart) and the arch's underside, `segments` steps along the arc.
void add_arch(mesh& m, float x0, float x1, float spring, float top, float z0, float depth, int segments, glm::vec3 albedo) {
  const float pi = 3.14159265358979f, radius = 0.5f * (x1 - x0), cx = 0.5f * (x0 + x1);
  for (int k = 0; k < segments; ++k) {
    const float a0 = pi * static_cast<float>(k) / static_cast<float>(segments), a1 = pi * static_cast<float>(k + 1) / static_cast<float>(segments);
    const glm::vec2 p0(cx + radius * std::cos(a0), spring + radius * std::sin(a0)), p1(cx + radius * std::cos(a1), spring + radius * std::sin(a1));
    for (int side = 0; side < 2; ++side) {
      const float z = side == 0 ? z0 + 0.5f * depth : z0 - 0.5f * depth;
      const glm::vec3 n(0.0f, 0.0f, side == 0 ? 1.0f : -1.0f);
      const glm::vec3 a(p0.x, p0.y, z), b(p1.x, p1.y, z), c(p1.x, top, z), d(p0.x, top, z);
      if (side == 0) add_quad(m, b, a, d, c, n, albedo);
      else add_quad(m, a, b, c, d, n, albedo);
    }
    // The underside faces the arc's centre.
    const glm::vec3 inward = -glm::normalize(glm::vec3(0.5f * (p0 + p1) - glm::vec2(cx, spring), 0.0f));
    add_quad(m, {p0.x, p0.y, z0 + 0.5f * depth}, {p1.x, p1.y, z0 + 0.5f * depth}, {p1.x, p1.y, z0 - 0.5f * depth},
             {p0.x, p0.y, z0 - 0.5f * depth}, inward, albedo);
  }
}

// A curtain hanging in the plane z = z0 from y = top down to y = bottom between x0 and x1, with
// vertical folds (amplitude `fold`), as a grid of columns x rows quads; `facing` is +1 or -1 (the
// side its normals face).
void add_curtain(mesh& m, float x0, float x1, float bottom, float top, float z0, float fold, int columns, int rows, float facing, glm::vec3 albedo) {
  const auto first = static_cast<std::uint32_t>(m.vertices.size());
  const float pi = 3.14159265358979f, folds = 4.0f;
  for (int i = 0; i <= rows; ++i)
    for (int j = 0; j <= columns; ++j) {
      const float u = static_cast<float>(j) / static_cast<float>(columns), v = static_cast<float>(i) / static_cast<float>(rows);
      const float phase = 2.0f * pi * folds * u;
      const float x = x0 + (x1 - x0) * u, y = bottom + (top - bottom) * v, z = z0 + fold * std::sin(phase);
      const float slope = fold * 2.0f * pi * folds * std::cos(phase) / (x1 - x0);  // dz/dx
      m.vertices.push_back({{x, y, z}, glm::normalize(glm::vec3(-slope * facing, 0.0f, facing)), albedo});
    }
  const auto row = static_cast<std::uint32_t>(columns + 1);
  for (std::uint32_t i = 0; i < static_cast<std::uint32_t>(rows); ++i)
    for (std::uint32_t j = 0; j < static_cast<std::uint32_t>(columns); ++j) {
      const std::uint32_t a = first + i * row + j, b = a + 1, c = b + row, d = a + row;
      if (facing > 0.0f) for (std::uint32_t index : {a, b, c, a, c, d}) m.indices.push_back(index);
      else for (std::uint32_t index : {a, c, b, a, d, c}) m.indices.push_back(index);
    }
}

}  // namespace

scene make_atrium_scene(int tessellation) {
  if (tessellation < 4 || tessellation > 512) throw error("atrium tessellation must be in [4, 512], got " + std::to_string(tessellation));
  scene s;
  s.name = "atrium";
  mesh& m = s.geometry;
  const glm::vec3 stone(0.62f, 0.58f, 0.5f);
  const glm::vec3 curtain_colours[3] = {{0.7f, 0.08f, 0.06f}, {0.08f, 0.2f, 0.65f}, {0.1f, 0.5f, 0.12f}};
  const float half_x = 6.0f, court = 3.0f, back = 4.5f, storey = 3.0f, column_radius = 0.16f, spacing = 1.2f;
  const int columns = 11;  // per side and storey, x = -6 .. 6
  add_quad(m, {-half_x, 0, back}, {half_x, 0, back}, {half_x, 0, -back}, {-half_x, 0, -back}, {0, 1, 0}, stone);  // ground
  for (float side : {-1.0f, 1.0f}) {
    const float z_front = side * court, z_back = side * back, inward = -side;
    // Back walls of the galleries (facing the court) and the gallery floors and ceilings.
    add_quad(m, {-half_x, 0, z_back}, {half_x, 0, z_back}, {half_x, 2 * storey, z_back}, {-half_x, 2 * storey, z_back}, {0, 0, inward}, stone);
    for (int level = 1; level <= 2; ++level) {
      const float y = storey * static_cast<float>(level);
      add_box(m, {0.0f, y - 0.1f, 0.5f * (z_front + z_back)}, {2 * half_x, 0.2f, back - court + 0.4f}, 0.0f, stone);
    }
    for (int level = 0; level < 2; ++level) {
      const float y0 = storey * static_cast<float>(level), spring = y0 + 1.9f, top = y0 + storey - 0.2f;
      for (int c = 0; c < columns; ++c) {
        const float cx = -0.5f * spacing * static_cast<float>(columns - 1) + spacing * static_cast<float>(c);
        add_cylinder(m, {cx, y0, z_front}, column_radius, spring - y0, tessellation, tessellation / 2, stone);
        if (c + 1 < columns) {
          add_arch(m, cx, cx + spacing, spring, top, z_front, 0.3f, tessellation, stone);
          // Curtains between every other pair of columns, on both storeys, a colour per bay.
          if ((c + level) % 2 == 0)
            add_curtain(m, cx + column_radius, cx + spacing - column_radius, y0 + 0.25f, spring, z_front + side * 0.2f, 0.05f,
                        tessellation, tessellation, inward, curtain_colours[(c / 2 + level) % 3]);
        }
      }
    }
  }
  // End walls of the court.
  add_quad(m, {-half_x, 0, -back}, {-half_x, 0, back}, {-half_x, 2 * storey, back}, {-half_x, 2 * storey, -back}, {1, 0, 0}, stone);
  add_quad(m, {half_x, 0, back}, {half_x, 0, -back}, {half_x, 2 * storey, -back}, {half_x, 2 * storey, back}, {-1, 0, 0}, stone);
  s.view.position = {5.4f, 1.6f, 0.6f};
  s.view.target = {-3.0f, 2.2f, -1.4f};
  s.view.vertical_fov_degrees = 60.0f;
  s.view.near_plane = 0.05f;
  s.view.far_plane = 40.0f;
  s.light.kind = light_kind::directional;
  s.light.directional.direction = glm::normalize(glm::vec3(0.25f, -1.0f, -0.35f));
  s.light.directional.irradiance = glm::vec3(3.0f);
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
                        0.5f * (a.albedo + b.albedo), 0.5f * (a.texcoord + b.texcoord)};
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

std::optional<mesh> subdivide_long_edges(const mesh& source, float max_edge, std::size_t max_triangles) {
  using triangle = std::array<vertex, 3>;
  const auto longest_edge = [](const triangle& t, float& length) {
    int edge = 0;
    length = -1.0f;
    for (int k = 0; k < 3; ++k) {
      const float candidate = glm::length(t[static_cast<std::size_t>(k)].position - t[static_cast<std::size_t>((k + 1) % 3)].position);
      if (candidate > length) length = candidate, edge = k;
    }
    return static_cast<std::size_t>(edge);
  };
  // One source triangle at a time, so that the output keeps the source's order (a renderer's
  // early depth test depends on it: a floor's underside drawn first would be shaded in full).
  // A split replaces a triangle by two: the count grows by one per split.
  const std::size_t source_triangles = source.indices.size() / 3;
  if (source_triangles > max_triangles) return std::nullopt;
  std::vector<triangle> pending, done;
  for (std::size_t first = 0; first < source_triangles; ++first) {
    pending.push_back({source.vertices[source.indices[3 * first]], source.vertices[source.indices[3 * first + 1]],
                       source.vertices[source.indices[3 * first + 2]]});
    while (!pending.empty()) {
      const triangle t = pending.back();
      pending.pop_back();
      float length = 0.0f;
      const std::size_t a = longest_edge(t, length), b = (a + 1) % 3, c = (a + 2) % 3;
      if (!(length > max_edge)) {
        done.push_back(t);
        continue;
      }
      if (done.size() + pending.size() + 2 + (source_triangles - first - 1) > max_triangles) return std::nullopt;
      vertex middle;
      middle.position = 0.5f * (t[a].position + t[b].position);  // + commutes: both triangles of the edge get the same bits
      // Equal ends keep their normal and albedo bit for bit (a flat face stays one face).
      const glm::vec3 normal = t[a].normal + t[b].normal;
      middle.normal = t[a].normal == t[b].normal || !(glm::length(normal) > 0.0f) ? t[a].normal : glm::normalize(normal);
      middle.albedo = t[a].albedo == t[b].albedo ? t[a].albedo : 0.5f * (t[a].albedo + t[b].albedo);
      pending.push_back({middle, t[b], t[c]});
      pending.push_back({t[a], middle, t[c]});
    }
  }
  mesh out;
  std::map<std::array<float, 9>, std::uint32_t> index_of;
  for (const triangle& t : done)
    for (const vertex& v : t) {
      const std::array<float, 9> key = {v.position.x, v.position.y, v.position.z, v.normal.x, v.normal.y, v.normal.z, v.albedo.x, v.albedo.y, v.albedo.z};
      const auto [found, inserted] = index_of.emplace(key, static_cast<std::uint32_t>(out.vertices.size()));
      if (inserted) out.vertices.push_back(v);
      out.indices.push_back(found->second);
    }
  return out;
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

std::vector<std::string> built_in_scene_names() {
  return {"cornell-box", "indirect-shadow", "occluder", "occluder-white", "atrium", "instanced", "boxes", "teapot", "teapots"};
}

scene built_in_scene(const std::string& name) {
  if (name == "cornell-box") return make_cornell_box();
  if (name == "indirect-shadow") return make_indirect_shadow_scene();
  if (name == "occluder") return make_occluder_scene(true);
  if (name == "occluder-white") return make_occluder_scene(false);
  if (name == "atrium") return make_atrium_scene(atrium_default_tessellation);
  if (name == "instanced") return make_instanced_scene();
  if (name == "boxes") return make_boxes_scene();
  if (name == "teapot") return make_teapot_scene(1);
  if (name == "teapots") return make_teapot_scene(10);
  std::string known;
  for (const std::string& candidate : built_in_scene_names()) known += (known.empty() ? "" : ", ") + candidate;
  throw error("unknown scene '" + excerpt(name) + "' (built-in scenes: " + known + ", or a path to an .obj, .gltf or .glb file)");
}

}  // namespace vplkit

namespace vplkit {

namespace {

bool finite(const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

std::string text_of(const glm::vec3& v) {
  // Built with += rather than "(" + string: GCC 12 gives a false -Wrestrict on the latter (bug 105329).
  std::string text = "(";
  text += std::to_string(v.x) + ", " + std::to_string(v.y) + ", " + std::to_string(v.z) + ")";
  return text;
}

std::string power_limit_text() {
  char text[32];
  std::snprintf(text, sizeof text, "%g", static_cast<double>(max_light_power));
  return text;
}

}  // namespace

void check_mesh(const mesh& geometry, const std::string& name) {
  const auto fail = [&](const std::string& what) { throw error(name + ": " + what); };
  if (geometry.indices.empty() || geometry.indices.size() % 3 != 0) fail("no triangles, or an index count that is not a multiple of 3");
  for (std::size_t i = 0; i < geometry.vertices.size(); ++i) {
    const vertex& v = geometry.vertices[i];
    if (!finite(v.position) || glm::any(glm::greaterThan(glm::abs(v.position), glm::vec3(max_scene_coordinate))))
      fail("vertex " + std::to_string(i) + " at " + text_of(v.position) + " is not finite or beyond " +
           std::to_string(static_cast<long>(max_scene_coordinate)) + " (vplkit works in float; scale the scene down)");
    if (!finite(v.normal) || !finite(v.albedo)) fail("vertex " + std::to_string(i) + " has a non-finite normal or albedo");
    if (!std::isfinite(v.texcoord.x) || !std::isfinite(v.texcoord.y)) fail("vertex " + std::to_string(i) + " has a non-finite texture coordinate");
  }
  for (const std::uint32_t index : geometry.indices)
    if (index >= geometry.vertices.size()) fail("index " + std::to_string(index) + " is past the " + std::to_string(geometry.vertices.size()) + " vertices");
  check_materials(geometry, name);
}

bool has_alpha_cutouts(const mesh& geometry) {
  if (!geometry.materials) return false;
  for (const surface_material& material : geometry.materials->materials)
    if (material.alpha_mask) return true;
  return false;
}

void check_materials(const mesh& geometry, const std::string& name) {
  const auto fail = [&](const std::string& what) { throw error(name + ": " + what); };
  if (geometry.material_ranges.empty()) return;
  if (!geometry.materials) fail("material ranges without materials");
  const material_library& library = *geometry.materials;
  std::uint64_t end = 0;
  for (std::size_t r = 0; r < geometry.material_ranges.size(); ++r) {
    const material_range& range = geometry.material_ranges[r];
    const std::string where = "material range " + std::to_string(r);
    if (range.first_index < end || range.first_index % 3 != 0 || range.index_count % 3 != 0 ||
        std::uint64_t{range.first_index} + range.index_count > geometry.indices.size())
      fail(where + " does not lie in order on whole triangles within the " + std::to_string(geometry.indices.size()) + " indices");
    end = std::uint64_t{range.first_index} + range.index_count;
    if (range.material >= library.materials.size()) fail(where + " names material " + std::to_string(range.material) + ", but there are " + std::to_string(library.materials.size()));
  }
  for (std::size_t m = 0; m < library.materials.size(); ++m) {
    const surface_material& material = library.materials[m];
    const std::string where = "material " + std::to_string(m) + " '" + material.name + "'";
    if (material.texture >= static_cast<int>(library.textures.size()) || material.texture < -1) fail(where + " names a texture that does not exist");
    const glm::vec4 matrix(material.texture_matrix[0], material.texture_matrix[1]);
    if (!finite(glm::vec3(matrix)) || !std::isfinite(matrix.w) || !std::isfinite(material.texture_offset.x) || !std::isfinite(material.texture_offset.y))
      fail(where + ": its texture transform is not finite");
    if (!(material.alpha_factor >= 0.0f && material.alpha_factor <= 1.0f) || !(material.alpha_cutoff >= 0.0f && material.alpha_cutoff <= 1.0f))
      fail(where + ": alpha factor and cutoff must be in [0, 1]");
  }
  for (const texture& t : library.textures) {
    bool consistent = !t.levels.empty();
    for (const texture_level& level : t.levels)
      consistent = consistent && level.width >= 1 && level.height >= 1 &&
                   level.rgba8.size() == static_cast<std::size_t>(level.width) * static_cast<std::size_t>(level.height) * 4;
    if (!consistent) fail("texture '" + t.name + "' has a level whose pixels do not match its size");
  }
}

const surface_material* material_of_triangle(const mesh& geometry, std::size_t triangle) {
  const std::vector<material_range>& ranges = geometry.material_ranges;
  if (ranges.empty() || !geometry.materials) return nullptr;
  const std::size_t first = 3 * triangle;
  // The last range starting at or before the triangle.
  auto after = std::upper_bound(ranges.begin(), ranges.end(), first, [](std::size_t index, const material_range& range) { return index < range.first_index; });
  if (after == ranges.begin()) return nullptr;
  const material_range& range = *(after - 1);
  if (first >= std::size_t{range.first_index} + range.index_count) return nullptr;
  return &geometry.materials->materials[range.material];
}

glm::vec4 surface_albedo_alpha(const mesh& geometry, std::size_t triangle, glm::vec2 barycentric, float lod) {
  const vertex& a = geometry.vertices[geometry.indices[3 * triangle]];
  const vertex& b = geometry.vertices[geometry.indices[3 * triangle + 1]];
  const vertex& c = geometry.vertices[geometry.indices[3 * triangle + 2]];
  const float u = barycentric.x, v = barycentric.y, w = 1.0f - u - v;
  const glm::vec3 factor = w * a.albedo + u * b.albedo + v * c.albedo;
  const surface_material* material = material_of_triangle(geometry, triangle);
  if (!material) return glm::vec4(factor, 1.0f);
  glm::vec4 texel(1.0f);
  if (material->texture >= 0) {
    const glm::vec2 uv = material_texture_coordinate(*material, w * a.texcoord + u * b.texcoord + v * c.texcoord);
    texel = sample_texture(geometry.materials->textures[static_cast<std::size_t>(material->texture)], material->sampler, uv, lod);
  }
  return glm::vec4(factor * glm::vec3(texel), material->alpha_factor * texel.a);
}

bool surface_cut_out(const mesh& geometry, std::size_t triangle, glm::vec2 barycentric, float lod) {
  const surface_material* material = material_of_triangle(geometry, triangle);
  return material && material->alpha_mask && surface_albedo_alpha(geometry, triangle, barycentric, lod).a < material->alpha_cutoff;
}

void set_light_intensity(scene_light& light, float intensity) {
  if (!(intensity >= 0.0f && std::isfinite(intensity))) throw error("the light intensity must be finite and >= 0, got " + std::to_string(intensity));
  glm::vec3& power = light.kind == light_kind::spot ? light.spot.intensity : light.directional.irradiance;
  const float peak = std::max({power.r, power.g, power.b});
  power = (peak > 0.0f ? power / peak : glm::vec3(1.0f)) * intensity;
}

void check_camera(const camera& view, const std::string& owner) {
  if (!finite(view.position) || !finite(view.target) || !finite(view.up) || !std::isfinite(view.vertical_fov_degrees) ||
      !(view.near_plane > 0.0f) || !(view.far_plane > view.near_plane) || !std::isfinite(view.far_plane))
    throw error(owner + ": the camera has a non-finite value or bad near/far planes");
  if (!(view.vertical_fov_degrees > 0.0f && view.vertical_fov_degrees < 180.0f))
    throw error(owner + ": the camera's vertical field of view must be in (0, 180) degrees");
  const glm::vec3 forward = view.target - view.position;
  if (!(glm::dot(forward, forward) > 0.0f)) throw error(owner + ": the camera's position and target are the same point");
  if (!(glm::length(glm::cross(forward, view.up)) > 1e-6f * glm::length(forward) * glm::length(view.up)))
    throw error(owner + ": the camera looks along its up vector");
}

void check_light(const scene_light& light, const std::string& owner) {
  if (light.kind == light_kind::spot) {
    const spot_light<float>& spot = light.spot;
    if (!finite(spot.position) || !finite(spot.direction) || !finite(spot.intensity)) throw error(owner + ": the spot light has a non-finite value");
    if (glm::any(glm::greaterThan(glm::abs(spot.intensity), glm::vec3(max_light_power))))
      throw error(owner + ": the spot light's intensity is beyond " + power_limit_text() + " (vplkit's outputs must stay finite)");
    if (const setting_problem problem = validate(spot)) throw error(owner + ": " + problem.message());
  } else {
    const directional_light<float>& sun = light.directional;
    if (!finite(sun.direction) || !finite(sun.irradiance)) throw error(owner + ": the directional light has a non-finite value");
    if (glm::any(glm::greaterThan(glm::abs(sun.irradiance), glm::vec3(max_light_power))))
      throw error(owner + ": the directional light's irradiance is beyond " + power_limit_text() + " (vplkit's outputs must stay finite)");
    if (const setting_problem problem = validate(sun)) throw error(owner + ": " + problem.message());
  }
}

void check_scene(const scene& s) {
  check_mesh(s.geometry, "scene " + s.name);
  check_camera(s.view, "scene " + s.name);
  check_light(s.light, "scene " + s.name);
}

}  // namespace vplkit
