// The built-in scenes (scene.hpp lists them): made in code, so that the default job needs no
// files; only the teapots read meshes/teapot.obj.
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "frontend/core/error.hpp"
#include "frontend/scene/obj_loader.hpp"
#include "frontend/scene/scene.hpp"

namespace vplkit {

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
  box.lights.push_back(scene_light{light_kind::spot, ceiling_spot(), {}, {}});
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
  scene_light& light = s.lights.emplace_back();
  light.kind = light_kind::directional;
  light.directional.direction = glm::normalize(glm::vec3(-1.0f, -0.45f, 0.0f));
  light.directional.irradiance = glm::vec3(3.0f);
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
  scene_light& light = s.lights.emplace_back();
  light.kind = light_kind::spot;
  light.spot = ceiling_spot();
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
  scene_light& light = s.lights.emplace_back();
  light.kind = light_kind::spot;
  light.spot.position = {0.6f, 2.2f, 0.8f};
  light.spot.direction = glm::normalize(glm::vec3(-0.6f, -2.2f, -0.8f));
  // The thesis gives no intensity. Light Wave's indirect light does not scale with the light
  // (Eq. 4.5 has no flux), so the intensity sets the share of direct light in the image; 1 puts
  // "direct lighting only" at 85.7 % similar to the default (1280 x 720), near the thesis's
  // 84.4 % (Table 5.9), the one number used to choose it.
  light.spot.intensity = glm::vec3(1.0f);
  light.spot.cos_inner = std::cos(glm::radians(35.0f));
  light.spot.cos_outer = std::cos(glm::radians(50.0f));
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
  scene_light& light = s.lights.emplace_back();
  light.kind = light_kind::spot;
  light.spot.position = {1.2f, 1.7f, 0.0f};
  light.spot.direction = glm::normalize(glm::vec3(-1.5f, 0.6f, 0.0f) - light.spot.position);
  light.spot.intensity = glm::vec3(9.0f);
  light.spot.cos_inner = std::cos(glm::radians(35.0f));
  light.spot.cos_outer = std::cos(glm::radians(50.0f));
  return s;
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
  scene_light& light = s.lights.emplace_back();
  light.kind = light_kind::directional;
  light.directional.direction = glm::normalize(glm::vec3(0.25f, -1.0f, -0.35f));
  light.directional.irradiance = glm::vec3(3.0f);
  return s;
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
  scene_light& light = s.lights.emplace_back();
  light.kind = light_kind::spot;
  light.spot.position = {0.7f, 2.4f, 0.9f};
  light.spot.direction = glm::normalize(glm::vec3(-0.7f, -2.4f, -0.9f));
  light.spot.intensity = glm::vec3(8.0f);
  light.spot.cos_inner = std::cos(glm::radians(40.0f));
  light.spot.cos_outer = std::cos(glm::radians(55.0f));
  return s;
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
