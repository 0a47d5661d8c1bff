// The frames of the RSM pose study (docs/rsm-study.md, "Any frame"): seven glTF scenes that the
// RSM gather's defaults were not chosen on, and seeded random camera and light poses in each, of
// the kinds where the gather fails first: a sun high and low, a spot at a ceiling, in a corner and
// along a wall, cameras looking at the light, along walls at grazing angles and up at the ceiling,
// thin occluders seen face-on and edge-on, courtyards and a street.
//   build/bench/vplkit_study_set [--out bench]
// writes <out>/scenes/<name>.gltf (written by vplkit's own glTF writer) and
// <out>/poses/{tune,holdout,all}.txt: one frame per line, `--scene FILE --camera ... --light ...`
// (render's options) and a comment naming the scene and the kinds. The split: the first four
// poses of four scenes are the tuning set; their other poses and every pose of the other three
// scenes are held out (never tuned on). Deterministic: the same files on every run.
#include <CLI/CLI.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include <vplkit/hash.hpp>

#include "frontend/core/error.hpp"
#include "frontend/core/files.hpp"
#include "frontend/scene/gltf_scene.hpp"
#include "frontend/scene/pose.hpp"
#include "frontend/scene/scene.hpp"

namespace fs = std::filesystem;
using namespace vplkit;

namespace {

// A seeded stream of uniform numbers (hash.hpp: the same on every machine).
class random_stream {
 public:
  explicit random_stream(std::uint32_t seed) : state_(hash_uint32(seed)) {}
  float uniform() { return uniform_float_from_bits(state_ = hash_combine(state_, ++counter_)); }
  float between(float low, float high) { return low + (high - low) * uniform(); }
  glm::vec3 in_box(glm::vec3 low, glm::vec3 high) { return {between(low.x, high.x), between(low.y, high.y), between(low.z, high.z)}; }
  int index(int count) { return std::min(count - 1, static_cast<int>(uniform() * static_cast<float>(count))); }

 private:
  std::uint32_t state_;
  std::uint32_t counter_ = 0;
};

const glm::vec3 white(0.75f), warm_white(0.78f, 0.74f, 0.66f), grey(0.5f), red(0.7f, 0.12f, 0.08f), blue(0.12f, 0.22f, 0.7f),
    green(0.15f, 0.5f, 0.12f), ochre(0.75f, 0.55f, 0.2f), terracotta(0.7f, 0.35f, 0.22f), wood(0.45f, 0.3f, 0.18f), dark(0.06f);

// The inside of a box room: normals point in. `albedo`: floor, ceiling, -x, +x, -z, +z walls;
// without a ceiling when `ceiling` is false.
void add_room(mesh& m, glm::vec3 lo, glm::vec3 hi, const glm::vec3 (&albedo)[6], bool ceiling = true) {
  add_quad(m, {lo.x, lo.y, hi.z}, {hi.x, lo.y, hi.z}, {hi.x, lo.y, lo.z}, {lo.x, lo.y, lo.z}, {0, 1, 0}, albedo[0]);
  if (ceiling) add_quad(m, {lo.x, hi.y, lo.z}, {hi.x, hi.y, lo.z}, {hi.x, hi.y, hi.z}, {lo.x, hi.y, hi.z}, {0, -1, 0}, albedo[1]);
  add_quad(m, {lo.x, lo.y, hi.z}, {lo.x, lo.y, lo.z}, {lo.x, hi.y, lo.z}, {lo.x, hi.y, hi.z}, {1, 0, 0}, albedo[2]);
  add_quad(m, {hi.x, lo.y, lo.z}, {hi.x, lo.y, hi.z}, {hi.x, hi.y, hi.z}, {hi.x, hi.y, lo.z}, {-1, 0, 0}, albedo[3]);
  add_quad(m, {lo.x, lo.y, lo.z}, {hi.x, lo.y, lo.z}, {hi.x, hi.y, lo.z}, {lo.x, hi.y, lo.z}, {0, 0, 1}, albedo[4]);
  add_quad(m, {hi.x, lo.y, hi.z}, {lo.x, lo.y, hi.z}, {lo.x, hi.y, hi.z}, {hi.x, hi.y, hi.z}, {0, 0, -1}, albedo[5]);
}

// A quad from its four corners, the normal from their winding (counter-clockwise seen from it).
void add_face(mesh& m, glm::vec3 a, glm::vec3 b, glm::vec3 c, glm::vec3 d, glm::vec3 albedo) {
  add_quad(m, a, b, c, d, glm::normalize(glm::cross(b - a, c - a)), albedo);
}

void add_table(mesh& m, glm::vec3 centre, glm::vec2 size, float height, glm::vec3 albedo) {
  add_box(m, {centre.x, height - 0.025f, centre.z}, {size.x, 0.05f, size.y}, 0.0f, albedo);
  for (float sx : {-1.0f, 1.0f})
    for (float sz : {-1.0f, 1.0f})
      add_box(m, {centre.x + sx * (0.5f * size.x - 0.06f), 0.5f * (height - 0.05f), centre.z + sz * (0.5f * size.y - 0.06f)},
              {0.06f, height - 0.05f, 0.06f}, 0.0f, albedo);
}

// Where the poses of a scene may go, and which kinds it draws from.
struct pose_space {
  glm::vec3 camera_low, camera_high;   // camera positions
  glm::vec3 look_low, look_high;       // what the overview cameras look at
  float ceiling = 0.0f;                // spot lights hang just below it (rooms)
  glm::vec3 light_low, light_high;     // spot positions (x, z) under the ceiling, or the sun's court
  std::vector<std::pair<glm::vec3, glm::vec3>> walls;  // a point on a wall at eye height and the wall's inward normal
  glm::vec3 thin_point{0.0f}, thin_normal{0.0f};       // a thin occluder: a point on it and its normal (when any)
  std::vector<std::string> kinds;      // "camera kind/light kind", one per pose, cycled
};

struct study_scene {
  scene content;
  pose_space space;
  bool tuning = false;  // its first four poses are the tuning set
};

study_scene living_room() {
  study_scene s;
  s.tuning = true;
  scene& sc = s.content;
  sc.name = "living-room";
  const glm::vec3 walls[6] = {warm_white, white, red, blue, white, ochre};
  add_room(sc.geometry, {-3, 0, -2.5f}, {3, 3, 2.5f}, walls);
  add_box(sc.geometry, {-1.6f, 0.4f, -1.9f}, {2.0f, 0.8f, 0.9f}, 0.0f, green);   // sofa
  add_box(sc.geometry, {-1.6f, 0.75f, -2.3f}, {2.0f, 0.7f, 0.2f}, 0.0f, green);  // its back
  add_table(sc.geometry, {0.8f, 0.0f, 0.4f}, {1.6f, 0.9f}, 0.75f, wood);
  add_box(sc.geometry, {2.75f, 1.1f, -1.4f}, {0.4f, 2.2f, 1.2f}, 0.0f, wood);     // bookshelf
  add_box(sc.geometry, {-0.2f, 0.9f, 1.2f}, {0.02f, 1.8f, 1.4f}, 30.0f, white);   // a thin screen
  sc.view.position = {2.4f, 1.6f, 2.2f};
  sc.view.target = {-1.0f, 0.8f, -1.0f};
  sc.view.vertical_fov_degrees = 60.0f;
  sc.lights.emplace_back().kind = light_kind::spot;
  sc.lights[0].spot.position = {0.0f, 2.9f, 0.0f};
  sc.lights[0].spot.direction = {0.0f, -1.0f, 0.0f};
  sc.lights[0].spot.intensity = glm::vec3(8.0f);
  sc.lights[0].spot.cos_inner = std::cos(glm::radians(50.0f));
  sc.lights[0].spot.cos_outer = std::cos(glm::radians(70.0f));
  pose_space& p = s.space;
  p.camera_low = {-2.6f, 0.6f, -0.8f};
  p.camera_high = {2.6f, 2.5f, 2.2f};
  p.look_low = {-2.5f, 0.0f, -2.3f};
  p.look_high = {2.5f, 1.5f, 0.5f};
  p.ceiling = 3.0f;
  p.light_low = {-2.4f, 0.0f, -2.0f};
  p.light_high = {2.4f, 0.0f, 2.0f};
  p.walls = {{{-2.8f, 1.4f, 0.0f}, {1, 0, 0}}, {{2.8f, 1.4f, 0.5f}, {-1, 0, 0}}, {{0.0f, 1.4f, -2.3f}, {0, 0, 1}}, {{0.0f, 1.4f, 2.3f}, {0, 0, -1}}};
  p.kinds = {"overview/spot-ceiling", "at-light/spot-corner", "grazing/spot-wall", "up/spot-ceiling",
             "at-light/spot-ceiling", "grazing/spot-corner", "overview/spot-wall", "up/spot-corner"};
  return s;
}

study_scene courtyard() {
  study_scene s;
  s.tuning = true;
  scene& sc = s.content;
  sc.name = "courtyard";
  mesh& m = sc.geometry;
  add_quad(m, {-10, 0, 10}, {10, 0, 10}, {10, 0, -10}, {-10, 0, -10}, {0, 1, 0}, grey);  // ground
  // Walls 4 high and 0.3 thick around an 8 x 8 court, a gate in the south wall.
  add_box(m, {0.0f, 2.0f, -4.15f}, {8.6f, 4.0f, 0.3f}, 0.0f, ochre);
  add_box(m, {-4.15f, 2.0f, 0.0f}, {0.3f, 4.0f, 8.0f}, 0.0f, white);
  add_box(m, {4.15f, 2.0f, 0.0f}, {0.3f, 4.0f, 8.0f}, 0.0f, terracotta);
  add_box(m, {-2.65f, 2.0f, 4.15f}, {3.3f, 4.0f, 0.3f}, 0.0f, blue);
  add_box(m, {2.65f, 2.0f, 4.15f}, {3.3f, 4.0f, 0.3f}, 0.0f, blue);
  // A colonnade along the north wall: pillars under a thin roof slab.
  for (int i = 0; i < 5; ++i) add_box(m, {-3.0f + 1.5f * static_cast<float>(i), 1.4f, -2.4f}, {0.25f, 2.8f, 0.25f}, 0.0f, white);
  add_box(m, {0.0f, 2.85f, -3.2f}, {8.0f, 0.1f, 1.9f}, 0.0f, white);
  add_box(m, {0.5f, 0.3f, 1.0f}, {1.6f, 0.6f, 1.6f}, 0.0f, grey);  // fountain basin
  add_box(m, {0.5f, 0.9f, 1.0f}, {0.3f, 0.6f, 0.3f}, 0.0f, white);
  sc.view.position = {3.2f, 1.7f, 3.2f};
  sc.view.target = {-2.0f, 1.2f, -2.5f};
  sc.view.vertical_fov_degrees = 65.0f;
  sc.view.far_plane = 60.0f;
  sc.lights.emplace_back().kind = light_kind::directional;
  sc.lights[0].directional.direction = glm::normalize(glm::vec3(0.3f, -1.0f, 0.6f));
  sc.lights[0].directional.irradiance = glm::vec3(3.0f);
  pose_space& p = s.space;
  p.camera_low = {-3.6f, 0.5f, -1.8f};
  p.camera_high = {3.6f, 3.5f, 3.6f};
  p.look_low = {-3.8f, 0.0f, -3.8f};
  p.look_high = {3.8f, 2.5f, 3.8f};
  p.walls = {{{-3.7f, 1.6f, 0.0f}, {1, 0, 0}}, {{3.7f, 1.6f, 0.0f}, {-1, 0, 0}}, {{0.0f, 1.6f, 3.7f}, {0, 0, -1}}};
  p.kinds = {"overview/sun-high", "grazing/sun-low", "at-light/sun-low", "overview/sun-low",
             "grazing/sun-high", "overview/sun-low", "at-light/sun-high", "grazing/sun-low"};
  return s;
}

study_scene thin_walls() {
  study_scene s;
  s.tuning = true;
  scene& sc = s.content;
  sc.name = "thin-walls";
  mesh& m = sc.geometry;
  const glm::vec3 walls[6] = {white, white, green, white, red, white};
  add_room(m, {-2.5f, 0, -2.5f}, {2.5f, 2.8f, 2.5f}, walls);
  add_box(m, {0.0f, 0.8f, -1.9f}, {2.2f, 1.6f, 0.01f}, 0.0f, white);   // a sheet 0.6 before the red wall
  add_box(m, {-2.1f, 1.3f, 0.3f}, {0.8f, 0.01f, 1.6f}, 0.0f, white);  // a shelf out of the green wall
  add_box(m, {1.2f, 1.5f, 0.8f}, {0.01f, 1.4f, 1.2f}, 0.0f, blue);     // a hanging panel
  sc.view.position = {1.8f, 1.5f, 2.2f};
  sc.view.target = {-0.4f, 0.7f, -1.6f};
  sc.view.vertical_fov_degrees = 60.0f;
  sc.lights.emplace_back().kind = light_kind::spot;
  sc.lights[0].spot.position = {1.0f, 2.7f, 1.0f};
  sc.lights[0].spot.direction = glm::normalize(glm::vec3(-1.0f, -2.0f, -2.5f));
  sc.lights[0].spot.intensity = glm::vec3(9.0f);
  sc.lights[0].spot.cos_inner = std::cos(glm::radians(40.0f));
  sc.lights[0].spot.cos_outer = std::cos(glm::radians(55.0f));
  pose_space& p = s.space;
  p.camera_low = {-2.2f, 0.5f, 0.2f};
  p.camera_high = {2.2f, 2.4f, 2.2f};
  p.look_low = {-2.0f, 0.0f, -2.3f};
  p.look_high = {2.0f, 1.6f, -0.5f};
  p.ceiling = 2.8f;
  p.light_low = {-2.0f, 0.0f, -1.2f};
  p.light_high = {2.0f, 0.0f, 2.0f};
  p.walls = {{{-2.3f, 1.2f, 0.0f}, {1, 0, 0}}, {{2.3f, 1.2f, 0.0f}, {-1, 0, 0}}, {{0.0f, 1.2f, -2.3f}, {0, 0, 1}}};
  p.thin_point = {0.0f, 0.8f, -1.9f};
  p.thin_normal = {0, 0, 1};
  p.kinds = {"thin-side/spot-ceiling", "overview/spot-corner", "at-light/spot-ceiling", "thin-side/spot-wall",
             "overview/spot-wall", "thin-side/spot-corner", "grazing/spot-ceiling", "at-light/spot-corner"};
  return s;
}

study_scene corridor() {
  study_scene s;
  s.tuning = true;
  scene& sc = s.content;
  sc.name = "corridor";
  mesh& m = sc.geometry;
  // An L: the long arm along x (x 0..9, z 0..2), the short arm along z (x 7..9, z 2..8).
  const float h = 2.8f;
  add_face(m, {0, 0, 2}, {9, 0, 2}, {9, 0, 0}, {0, 0, 0}, warm_white);
  add_face(m, {7, 0, 8}, {9, 0, 8}, {9, 0, 2}, {7, 0, 2}, warm_white);
  add_face(m, {0, h, 0}, {9, h, 0}, {9, h, 2}, {0, h, 2}, white);
  add_face(m, {7, h, 2}, {9, h, 2}, {9, h, 8}, {7, h, 8}, white);
  add_face(m, {0, 0, 0}, {9, 0, 0}, {9, h, 0}, {0, h, 0}, terracotta);  // north wall of the long arm
  add_face(m, {7, 0, 2}, {0, 0, 2}, {0, h, 2}, {7, h, 2}, white);       // south wall of the long arm
  add_face(m, {9, 0, 0}, {9, 0, 8}, {9, h, 8}, {9, h, 0}, blue);        // east wall
  add_face(m, {7, 0, 8}, {7, 0, 2}, {7, h, 2}, {7, h, 8}, white);       // west wall of the short arm
  add_face(m, {0, 0, 2}, {0, 0, 0}, {0, h, 0}, {0, h, 2}, green);       // the long arm's end
  add_face(m, {9, 0, 8}, {7, 0, 8}, {7, h, 8}, {9, h, 8}, ochre);       // the short arm's end
  for (int i = 0; i < 3; ++i) add_box(m, {1.5f + 2.0f * static_cast<float>(i), 1.4f, 0.15f}, {0.3f, 2.8f, 0.3f}, 0.0f, white);  // pilasters
  add_box(m, {8.0f, 0.45f, 5.0f}, {0.8f, 0.9f, 0.5f}, 0.0f, wood);  // a cabinet
  sc.view.position = {0.8f, 1.6f, 1.0f};
  sc.view.target = {8.0f, 1.2f, 1.0f};
  sc.view.vertical_fov_degrees = 60.0f;
  sc.lights.emplace_back().kind = light_kind::spot;
  sc.lights[0].spot.position = {4.0f, 2.72f, 1.0f};
  sc.lights[0].spot.direction = {0.0f, -1.0f, 0.0f};
  sc.lights[0].spot.intensity = glm::vec3(7.0f);
  sc.lights[0].spot.cos_inner = std::cos(glm::radians(55.0f));
  sc.lights[0].spot.cos_outer = std::cos(glm::radians(75.0f));
  pose_space& p = s.space;
  p.camera_low = {0.5f, 0.8f, 0.5f};
  p.camera_high = {8.5f, 2.3f, 1.5f};
  p.look_low = {3.0f, 0.0f, 0.0f};
  p.look_high = {9.0f, 2.0f, 7.0f};
  p.ceiling = h;
  p.light_low = {1.0f, 0.0f, 0.4f};
  p.light_high = {8.6f, 0.0f, 1.6f};
  p.walls = {{{3.0f, 1.3f, 0.15f}, {0, 0, 1}}, {{2.0f, 1.3f, 1.85f}, {0, 0, -1}}, {{7.15f, 1.3f, 5.0f}, {1, 0, 0}}};
  p.kinds = {"grazing/spot-ceiling", "at-light/spot-ceiling", "overview/spot-wall", "up/spot-ceiling",
             "overview/spot-ceiling", "at-light/spot-wall", "grazing/spot-wall", "up/spot-wall"};
  return s;
}

study_scene loft() {
  study_scene s;
  scene& sc = s.content;
  sc.name = "loft";
  mesh& m = sc.geometry;
  const glm::vec3 walls[6] = {wood, white, white, ochre, blue, white};
  add_room(m, {-3.5f, 0, -3.0f}, {3.5f, 5.0f, 3.0f}, walls);
  add_box(m, {-1.75f, 2.55f, 0.0f}, {3.5f, 0.1f, 6.0f}, 0.0f, white);     // the mezzanine over the west half
  add_box(m, {0.0f, 3.05f, 0.0f}, {0.01f, 0.9f, 6.0f}, 0.0f, white);       // its thin railing panel
  for (int i = 0; i < 6; ++i)                                                // stairs up along the north wall
    add_box(m, {0.4f + 0.45f * static_cast<float>(i), 0.2f + 0.4f * static_cast<float>(i), -2.6f}, {0.45f, 0.4f, 0.8f}, 0.0f, wood);
  add_box(m, {2.2f, 0.5f, 1.6f}, {1.4f, 1.0f, 0.8f}, 0.0f, red);            // a block under the open half
  add_box(m, {-2.2f, 0.45f, 1.0f}, {1.2f, 0.9f, 1.8f}, 0.0f, green);        // a block under the mezzanine
  sc.view.position = {3.0f, 1.7f, 2.6f};
  sc.view.target = {-2.0f, 2.0f, -1.0f};
  sc.view.vertical_fov_degrees = 65.0f;
  sc.lights.emplace_back().kind = light_kind::spot;
  sc.lights[0].spot.position = {1.8f, 4.9f, 0.0f};
  sc.lights[0].spot.direction = glm::normalize(glm::vec3(-0.4f, -1.0f, 0.0f));
  sc.lights[0].spot.intensity = glm::vec3(16.0f);
  sc.lights[0].spot.cos_inner = std::cos(glm::radians(45.0f));
  sc.lights[0].spot.cos_outer = std::cos(glm::radians(65.0f));
  pose_space& p = s.space;
  p.camera_low = {0.4f, 0.6f, -2.0f};
  p.camera_high = {3.2f, 4.5f, 2.7f};
  p.look_low = {-3.3f, 0.0f, -2.8f};
  p.look_high = {3.3f, 4.0f, 2.8f};
  p.ceiling = 5.0f;
  p.light_low = {-3.0f, 0.0f, -2.5f};
  p.light_high = {3.0f, 0.0f, 2.5f};
  p.walls = {{{-3.3f, 1.2f, 0.0f}, {1, 0, 0}}, {{3.3f, 2.0f, 0.0f}, {-1, 0, 0}}, {{0.0f, 3.5f, 2.8f}, {0, 0, -1}}};
  p.thin_point = {0.0f, 3.05f, 0.0f};
  p.thin_normal = {1, 0, 0};
  p.kinds = {"overview/spot-ceiling", "thin-side/spot-corner", "at-light/spot-ceiling", "up/spot-wall",
             "grazing/spot-ceiling", "overview/spot-corner", "thin-side/spot-ceiling", "at-light/spot-wall"};
  return s;
}

study_scene street() {
  study_scene s;
  scene& sc = s.content;
  sc.name = "street";
  mesh& m = sc.geometry;
  add_quad(m, {-14, 0, 14}, {14, 0, 14}, {14, 0, -14}, {-14, 0, -14}, {0, 1, 0}, grey);
  // Two rows of houses along a street 4 wide (z in [-2, 2]), of varied heights and colours.
  const glm::vec3 colours[5] = {ochre, white, terracotta, blue, warm_white};
  const float heights[2][5] = {{5.0f, 3.5f, 7.0f, 4.0f, 6.0f}, {4.0f, 6.5f, 3.0f, 5.5f, 4.5f}};
  for (int side = 0; side < 2; ++side)
    for (int i = 0; i < 5; ++i) {
      const float h = heights[side][i];
      const float z = side == 0 ? -4.0f : 4.0f;
      add_box(m, {-8.0f + 4.0f * static_cast<float>(i), 0.5f * h, z}, {3.8f, h, 4.0f}, 0.0f, colours[(i + 2 * side) % 5]);
    }
  add_box(m, {-1.0f, 1.3f, 1.7f}, {2.5f, 0.02f, 0.6f}, 0.0f, red);  // an awning, a thin occluder
  sc.view.position = {-7.0f, 1.7f, 0.5f};
  sc.view.target = {4.0f, 2.5f, -0.5f};
  sc.view.vertical_fov_degrees = 60.0f;
  sc.view.far_plane = 80.0f;
  sc.lights.emplace_back().kind = light_kind::directional;
  sc.lights[0].directional.direction = glm::normalize(glm::vec3(0.5f, -1.0f, 0.4f));
  sc.lights[0].directional.irradiance = glm::vec3(3.0f);
  pose_space& p = s.space;
  p.camera_low = {-9.0f, 0.8f, -1.5f};
  p.camera_high = {9.0f, 4.0f, 1.5f};
  p.look_low = {-9.0f, 0.0f, -2.0f};
  p.look_high = {9.0f, 5.0f, 2.0f};
  p.walls = {{{0.0f, 1.6f, -1.8f}, {0, 0, 1}}, {{0.0f, 1.6f, 1.8f}, {0, 0, -1}}};
  p.kinds = {"grazing/sun-low", "overview/sun-high", "at-light/sun-low", "grazing/sun-high",
             "overview/sun-low", "overview/sun-high", "at-light/sun-high", "grazing/sun-low"};
  return s;
}

study_scene attic() {
  study_scene s;
  scene& sc = s.content;
  sc.name = "attic";
  mesh& m = sc.geometry;
  // 6 long (x), 5 wide (z); knee walls 1 high, the roof rising to a ridge at 3.5 over z = 0.
  const float knee = 1.0f, ridge = 3.5f, hw = 2.5f, hl = 3.0f;
  add_face(m, {-hl, 0, hw}, {hl, 0, hw}, {hl, 0, -hw}, {-hl, 0, -hw}, wood);                    // floor
  add_face(m, {-hl, 0, -hw}, {hl, 0, -hw}, {hl, knee, -hw}, {-hl, knee, -hw}, white);           // knee walls
  add_face(m, {hl, 0, hw}, {-hl, 0, hw}, {-hl, knee, hw}, {hl, knee, hw}, white);
  add_face(m, {-hl, knee, -hw}, {hl, knee, -hw}, {hl, ridge, 0}, {-hl, ridge, 0}, warm_white);  // roof slopes
  add_face(m, {hl, knee, hw}, {-hl, knee, hw}, {-hl, ridge, 0}, {hl, ridge, 0}, warm_white);
  for (float x : {-hl, hl}) {  // gable walls: a rectangle and a triangle each
    const float facing = x < 0.0f ? 1.0f : -1.0f;
    const glm::vec3 colour = x < 0.0f ? blue : red;
    if (facing > 0.0f) {
      add_face(m, {x, 0, hw}, {x, 0, -hw}, {x, knee, -hw}, {x, knee, hw}, colour);
      add_face(m, {x, knee, hw}, {x, knee, -hw}, {x, ridge, 0}, {x, ridge, 0.0001f}, colour);
    } else {
      add_face(m, {x, 0, -hw}, {x, 0, hw}, {x, knee, hw}, {x, knee, -hw}, colour);
      add_face(m, {x, knee, -hw}, {x, knee, hw}, {x, ridge, 0.0001f}, {x, ridge, 0}, colour);
    }
  }
  add_box(m, {0.0f, 2.3f, 0.0f}, {6.0f, 0.15f, 0.15f}, 0.0f, wood);       // a tie beam
  add_box(m, {-1.5f, 0.35f, 1.2f}, {1.0f, 0.7f, 1.6f}, 20.0f, green);     // a chest
  add_box(m, {1.8f, 0.9f, -1.2f}, {0.01f, 1.8f, 1.2f}, 0.0f, white);       // a thin partition
  sc.view.position = {2.5f, 1.5f, 1.5f};
  sc.view.target = {-2.5f, 1.2f, -0.5f};
  sc.view.vertical_fov_degrees = 65.0f;
  sc.lights.emplace_back().kind = light_kind::spot;
  sc.lights[0].spot.position = {0.0f, 3.3f, 0.0f};
  sc.lights[0].spot.direction = {0.0f, -1.0f, 0.0f};
  sc.lights[0].spot.intensity = glm::vec3(8.0f);
  sc.lights[0].spot.cos_inner = std::cos(glm::radians(50.0f));
  sc.lights[0].spot.cos_outer = std::cos(glm::radians(72.0f));
  pose_space& p = s.space;
  p.camera_low = {-2.7f, 0.6f, -1.0f};
  p.camera_high = {2.7f, 1.8f, 1.0f};
  p.look_low = {-2.8f, 0.0f, -2.2f};
  p.look_high = {2.8f, 2.5f, 2.2f};
  p.ceiling = 3.35f;
  p.light_low = {-2.5f, 0.0f, -0.3f};
  p.light_high = {2.5f, 0.0f, 0.3f};
  p.walls = {{{-2.8f, 0.8f, 0.0f}, {1, 0, 0}}, {{2.8f, 0.8f, 0.0f}, {-1, 0, 0}}, {{0.0f, 0.6f, -2.3f}, {0, 0, 1}}};
  p.thin_point = {1.8f, 0.9f, -1.2f};
  p.thin_normal = {1, 0, 0};
  p.kinds = {"up/spot-ceiling", "grazing/spot-ceiling", "at-light/spot-corner", "thin-side/spot-ceiling",
             "overview/spot-wall", "up/spot-corner", "at-light/spot-ceiling", "grazing/spot-wall"};
  return s;
}

std::vector<study_scene> study_scenes() { return {living_room(), courtyard(), thin_walls(), corridor(), loft(), street(), attic()}; }

// A light pose of `kind` in `space`: (position, target).
pose light_pose(const std::string& kind, const pose_space& space, random_stream& random) {
  if (kind == "sun-high" || kind == "sun-low") {
    const float elevation = glm::radians(kind == "sun-high" ? random.between(55.0f, 75.0f) : random.between(12.0f, 30.0f));
    const float azimuth = random.between(0.0f, 6.2831853f);
    const glm::vec3 towards_sun(std::cos(elevation) * std::cos(azimuth), std::sin(elevation), std::cos(elevation) * std::sin(azimuth));
    return {10.0f * towards_sun, glm::vec3(0.0f)};
  }
  const float y = space.ceiling - 0.08f;
  if (kind == "spot-ceiling") {
    glm::vec3 position = random.in_box(space.light_low, space.light_high);
    position.y = y;
    const float tilt = glm::radians(random.between(0.0f, 25.0f)), turn = random.between(0.0f, 6.2831853f);
    return {position, position + glm::vec3(std::sin(tilt) * std::cos(turn), -std::cos(tilt), std::sin(tilt) * std::sin(turn))};
  }
  if (kind == "spot-corner") {
    // Near one of the four upper corners of the light region, aimed at the far lower side of the room.
    const float sx = random.uniform() < 0.5f ? 0.0f : 1.0f, sz = random.uniform() < 0.5f ? 0.0f : 1.0f;
    const glm::vec3 corner(glm::mix(space.light_low.x, space.light_high.x, sx), y - random.between(0.0f, 0.4f),
                           glm::mix(space.light_low.z, space.light_high.z, sz));
    const glm::vec3 far(glm::mix(space.light_low.x, space.light_high.x, 1.0f - sx + random.between(-0.3f, 0.3f)), random.between(0.0f, 0.8f),
                        glm::mix(space.light_low.z, space.light_high.z, 1.0f - sz + random.between(-0.3f, 0.3f)));
    return {corner, far};
  }
  // spot-wall: close to a wall, high, shining down along it.
  const auto& [point, normal] = space.walls[static_cast<std::size_t>(random.index(static_cast<int>(space.walls.size())))];
  glm::vec3 position = point + normal * random.between(0.15f, 0.35f);
  position.y = y - random.between(0.0f, 0.3f);
  const glm::vec3 along = glm::normalize(glm::cross(normal, glm::vec3(0, 1, 0)));
  const glm::vec3 target = position + glm::vec3(0.0f, -2.0f, 0.0f) + along * random.between(-1.0f, 1.0f) + normal * random.between(0.1f, 0.5f);
  return {position, target};
}

// A camera pose of `kind`, given the light's pose.
pose camera_pose(const std::string& kind, const pose_space& space, const pose& light, bool sun, random_stream& random) {
  glm::vec3 position = random.in_box(space.camera_low, space.camera_high);
  if (kind == "overview") return {position, random.in_box(space.look_low, space.look_high)};
  if (kind == "at-light") {
    // Towards a spot light's position, or towards the sun but at most 10 degrees up (the walls
    // facing away from it, lit only indirectly, rather than the sky).
    const glm::vec3 towards_sun(light.position.x, 0.0f, light.position.z);
    const glm::vec3 target = sun ? position + glm::normalize(glm::normalize(towards_sun) + glm::vec3(0.0f, 0.18f, 0.0f)) * 5.0f : light.position;
    if (glm::length(target - position) < 1.0f) position = target - glm::vec3(1.2f, 0.4f, 1.2f) * (space.camera_high.z > target.z ? -1.0f : 1.0f);
    return {position, target + random.in_box(glm::vec3(-0.3f), glm::vec3(0.3f))};
  }
  if (kind == "up") {
    const glm::vec3 target = position + glm::vec3(random.between(-1.5f, 1.5f), random.between(1.5f, 2.5f), random.between(-1.5f, 1.5f));
    return {position, target + glm::vec3(0.6f, 0.0f, 0.0f)};
  }
  if (kind == "thin-side") {
    // In the occluder's plane, a few units off, looking at it edge-on.
    const glm::vec3 along = glm::normalize(glm::cross(space.thin_normal, glm::vec3(0, 1, 0)));
    const glm::vec3 side = glm::length(along) > 0.0f ? along : glm::vec3(1, 0, 0);
    const float sign = random.uniform() < 0.5f ? -1.0f : 1.0f;
    const glm::vec3 from = space.thin_point + side * sign * random.between(1.5f, 2.0f) + glm::vec3(0.0f, random.between(-0.2f, 0.6f), 0.0f) +
                           space.thin_normal * random.between(-0.15f, 0.15f);
    return {glm::clamp(from, space.camera_low - glm::vec3(0.0f, 0.0f, 3.0f), space.camera_high), space.thin_point};
  }
  // grazing: beside a wall, looking along it.
  const auto& [point, normal] = space.walls[static_cast<std::size_t>(random.index(static_cast<int>(space.walls.size())))];
  const glm::vec3 along = glm::normalize(glm::cross(normal, glm::vec3(0, 1, 0))) * (random.uniform() < 0.5f ? -1.0f : 1.0f);
  const glm::vec3 from = point + normal * random.between(0.25f, 0.6f) - along * random.between(1.0f, 2.0f) + glm::vec3(0.0f, random.between(-0.4f, 0.6f), 0.0f);
  return {from, point + along * random.between(2.0f, 3.5f) + normal * random.between(0.0f, 0.3f) + glm::vec3(0.0f, random.between(-0.6f, 0.3f), 0.0f)};
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"vplkit study set: the glTF scenes and random poses of the RSM pose study"};
  std::string out = "bench";
  int poses_per_scene = 8;
  app.add_option("--out", out, "folder for scenes/ and poses/")->capture_default_str();
  app.add_option("--poses", poses_per_scene, "poses per scene")->check(CLI::Range(1, 64))->capture_default_str();
  CLI11_PARSE(app, argc, argv);
  try {
    std::vector<output_file> files;
    std::ostringstream tune, holdout, all;
    const std::string header =
        "# RSM pose study (docs/rsm-study.md, \"Any frame\"), written by build/bench/vplkit_study_set: one frame per line, render's options.\n";
    tune << header << "# The tuning set: the first four poses of living-room, courtyard, thin-walls and corridor.\n";
    holdout << header << "# The held-out set: the other poses of those scenes and every pose of loft, street and attic (never tuned on).\n";
    all << header << "# Every frame: the tuning and the held-out set.\n";
    std::uint32_t scene_index = 0;
    for (study_scene& s : study_scenes()) {
      const std::string file = "bench/scenes/" + s.content.name + ".gltf";
      check_scene(s.content);
      files.push_back({fs::path(out) / "scenes" / (s.content.name + ".gltf"), [text = gltf_text(s.content)] {
                         return std::vector<std::uint8_t>(text.begin(), text.end());
                       }});
      random_stream random(hash_combine(0x5eed23u, scene_index++));
      for (int i = 0; i < poses_per_scene; ++i) {
        const std::string kinds = s.space.kinds[static_cast<std::size_t>(i) % s.space.kinds.size()];
        const std::string camera_kind = kinds.substr(0, kinds.find('/')), light_kind_name = kinds.substr(kinds.find('/') + 1);
        const bool sun = s.content.lights[0].kind == light_kind::directional;
        pose light, view;
        // Draw again (a bounded number of times) when the camera pose is one the scene cannot take.
        for (int attempt = 0;; ++attempt) {
          light = light_pose(light_kind_name, s.space, random);
          view = camera_pose(camera_kind, s.space, light, sun, random);
          scene moved = s.content;
          try {
            apply_pose(view, moved.view, "camera");
            apply_pose(light, moved.lights[0], "light");
            break;
          } catch (const error&) {
            if (attempt > 20) throw;
          }
        }
        std::ostringstream line;
        line << "--scene " << file << " --camera " << format_pose(view) << " --light " << format_pose(light) << "  # " << s.content.name << " "
             << i << " " << kinds << "\n";
        (s.tuning && i < 4 ? tune : holdout) << line.str();
        all << line.str();
      }
    }
    for (const auto& [name, text] : {std::pair{"tune.txt", tune.str()}, std::pair{"holdout.txt", holdout.str()}, std::pair{"all.txt", all.str()}})
      files.push_back({fs::path(out) / "poses" / name, [bytes = text] { return std::vector<std::uint8_t>(bytes.begin(), bytes.end()); }});
    write_all_or_nothing(files);
    for (const output_file& f : files) std::cout << "wrote " << f.path.string() << "\n";
  } catch (const std::exception& failure) {
    std::cerr << "vplkit_study_set: error: " << failure.what() << "\n";
    return 1;
  }
  return 0;
}
