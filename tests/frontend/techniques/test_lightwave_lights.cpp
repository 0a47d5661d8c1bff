// Light Wave with every kind of light (frontend/techniques/lightwave/lightwave_pipeline.hpp): a
// point light's and a sun's direct light against the closed form at the surface each pixel sees
// (found here by tracing the camera's ray through the scene's few triangles), a point light's cube
// of shadow maps with no face missing and no dark seam, its VPLs carrying the whole sphere's flux,
// a light split into parts summing to the whole, mixed lights summing to their single-light
// images, and the further lights drawing from the first one's shared scene resources.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include <glm/gtc/constants.hpp>

#include <vplkit/cube_map.hpp>
#include <vplkit/direct_light.hpp>
#include <vplkit/parity/doctest.hpp>

#include "frontend/core/error.hpp"
#include "frontend/scene/camera.hpp"
#include "frontend/techniques/lightwave/lightwave_pipeline.hpp"

using namespace vplkit;
using namespace vplkit::parity;

namespace {

lightwave_settings lightwave_settings_of_side(const char* technique, int side = 64) {
  lightwave_settings settings;
  settings.technique = technique;
  settings.width = side;
  settings.height = side;
  settings.shadow_map_scale = 4.0f;
  settings.format = texel_format::rgba32f;
  return settings;
}

// A quad of half-sides |u| and |v| around `centre`, facing n = u x v (counter-clockwise seen from n).
void add_facing_quad(mesh& target, glm::vec3 centre, glm::vec3 u, glm::vec3 v, glm::vec3 albedo) {
  add_quad(target, centre - u - v, centre + u - v, centre + u + v, centre - u + v, glm::normalize(glm::cross(u, v)), albedo);
}

scene_light point_at(glm::vec3 position, glm::vec3 intensity) {
  scene_light light;
  light.kind = light_kind::point;
  light.point.position = position;
  light.point.intensity = intensity;
  return light;
}

scene_light sun_along(glm::vec3 direction, glm::vec3 irradiance) {
  scene_light light;
  light.kind = light_kind::directional;
  light.directional.direction = glm::normalize(direction);
  light.directional.irradiance = irradiance;
  return light;
}

// An 8 x 8 floor (albedo 0.5) seen from above at an angle; with `wall`, a 2-high wall at x = 1.
scene open_floor(const scene_light& light, bool wall = false) {
  scene s;
  s.name = "open-floor";
  add_facing_quad(s.geometry, {0, 0, 0}, {0, 0, 4}, {4, 0, 0}, glm::vec3(0.5f));
  if (wall) add_box(s.geometry, {1.05f, 1.0f, 0.0f}, {0.1f, 2.0f, 8.0f}, 0.0f, glm::vec3(0.5f));
  s.view.position = {0.0f, 5.5f, 4.5f};
  s.view.target = {0.0f, 0.0f, -0.3f};
  s.view.vertical_fov_degrees = 70.0f;
  s.lights = {light};
  return s;
}

// A closed 2 x 2 x 2 box, every wall facing in (albedo 0.6), a point light near its centre: off
// it by a little, so that the cube's face seams cross the walls instead of running along the
// box's edges.
const glm::vec3 box_light_position(0.12f, -0.1f, 0.07f);

scene closed_box() {
  scene s;
  s.name = "closed-box";
  const glm::vec3 albedo(0.6f);
  for (int axis = 0; axis < 3; ++axis)
    for (float side : {-1.0f, 1.0f}) {
      glm::vec3 n(0.0f), u(0.0f), v(0.0f);
      n[axis] = -side;  // facing the inside
      u[(axis + 1) % 3] = 1.0f;
      v = glm::cross(n, u);
      glm::vec3 centre(0.0f);
      centre[axis] = side;
      add_facing_quad(s.geometry, centre, u, v, albedo);
    }
  s.lights = {point_at(box_light_position, glm::vec3(1.5f))};
  return s;
}

// The camera at the box's centre looking at the wall across `axis`, `side` (90 degrees: the whole wall).
camera facing_wall(int axis, float side) {
  camera view;
  view.position = glm::vec3(0.0f);
  view.target = glm::vec3(0.0f);
  view.target[axis] = side;
  view.up = axis == 1 ? glm::vec3(0.0f, 0.0f, 1.0f) : glm::vec3(0.0f, 1.0f, 0.0f);
  view.vertical_fov_degrees = 90.0f;
  view.near_plane = 0.01f;
  return view;
}

struct hit {
  glm::vec3 position{0.0f}, normal{0.0f}, albedo{0.0f};
  float distance = 0.0f;
};

// The nearest triangle of `geometry` the ray meets (Moller-Trumbore), with its first vertex's
// normal and albedo (the test scenes' triangles are flat and of one colour).
std::optional<hit> trace(const mesh& geometry, glm::vec3 origin, glm::vec3 direction, float max_distance = 1e30f) {
  std::optional<hit> nearest;
  for (std::size_t i = 0; i + 2 < geometry.indices.size(); i += 3) {
    const vertex &a = geometry.vertices[geometry.indices[i]], &b = geometry.vertices[geometry.indices[i + 1]], &c = geometry.vertices[geometry.indices[i + 2]];
    const glm::vec3 e1 = b.position - a.position, e2 = c.position - a.position, p = glm::cross(direction, e2);
    const float det = glm::dot(e1, p);
    if (std::abs(det) < 1e-12f) continue;
    const glm::vec3 s = origin - a.position;
    const float u = glm::dot(s, p) / det;
    if (u < 0.0f || u > 1.0f) continue;
    const glm::vec3 q = glm::cross(s, e1);
    const float v = glm::dot(direction, q) / det;
    if (v < 0.0f || u + v > 1.0f) continue;
    const float t = glm::dot(e2, q) / det;
    if (!(t > 1e-5f && t < max_distance) || (nearest && t >= nearest->distance)) continue;
    nearest = hit{origin + t * direction, glm::normalize(a.normal), a.albedo, t};
  }
  return nearest;
}

// The direct radiance albedo / pi * E at a traced point, with a shadow ray (the closed form where
// nothing is in the way).
glm::vec3 traced_direct(const scene& s, const hit& h) {
  const scene_light& light = s.lights.front();
  glm::vec3 irradiance(0.0f), to_light(0.0f);
  float distance = 1e30f;
  if (light.kind == light_kind::point) {
    irradiance = point_light_irradiance(h.position, h.normal, light.point, irradiance_settings<float>{});
    to_light = light.point.position - h.position;
    distance = glm::length(to_light);
    to_light /= distance;
  } else if (light.kind == light_kind::directional) {
    irradiance = directional_light_irradiance(h.normal, light.directional);
    to_light = -light.directional.direction;
  } else {
    irradiance = spot_light_irradiance(h.position, h.normal, light.spot, irradiance_settings<float>{});
    to_light = glm::normalize(light.spot.position - h.position);
    distance = glm::length(light.spot.position - h.position);
  }
  if (glm::dot(irradiance, irradiance) > 0.0f && trace(s.geometry, h.position + 1e-4f * h.normal, to_light, distance)) return glm::vec3(0.0f);
  return h.albedo / glm::pi<float>() * irradiance;
}

struct direct_check {
  std::size_t lit = 0, within = 0, dark = 0;
  double drawn = 0.0, expected = 0.0;
  double mean_ratio() const { return expected > 0.0 ? drawn / expected : 0.0; }
};

// The red channel of `radiance` (drawn from `view`) against traced_direct at each pixel's centre
// where that is above ~0, for the pixels whose surface point `region` accepts: how many within
// +-7 %, how many darker than half (acne, a missing face, a dark seam).
template <typename Region>
direct_check compare_direct(const scene& s, const camera& view, const image& radiance, Region&& region) {
  const float aspect = static_cast<float>(radiance.width) / static_cast<float>(radiance.height);
  const glm::mat4 inverse = glm::inverse(camera_projection_matrix(view, aspect) * camera_view_matrix(view));
  direct_check result;
  for (int y = 0; y < radiance.height; ++y)
    for (int x = 0; x < radiance.width; ++x) {
      // The GL's rows: y = 0 at the bottom.
      const glm::vec2 ndc = (glm::vec2(x, y) + 0.5f) / glm::vec2(radiance.width, radiance.height) * 2.0f - 1.0f;
      const glm::vec4 far_point = inverse * glm::vec4(ndc, 1.0f, 1.0f);
      const glm::vec3 direction = glm::normalize(glm::vec3(far_point) / far_point.w - view.position);
      const std::optional<hit> h = trace(s.geometry, view.position, direction);
      if (!h || !region(*h)) continue;
      const float expected = traced_direct(s, *h).r;
      if (!(expected > 1e-4f)) continue;
      const float drawn = radiance.at(x, y).r;
      REQUIRE(std::isfinite(drawn));
      ++result.lit;
      result.within += std::abs(drawn / expected - 1.0f) <= 0.07f;
      result.dark += drawn < 0.5f * expected;
      result.drawn += drawn;
      result.expected += expected;
    }
  return result;
}

const auto anywhere = [](const hit&) { return true; };

scene with_lights(scene s, std::vector<scene_light> lights) {
  s.lights = std::move(lights);
  return s;
}

// The largest |whole - sum of parts| over the image's channels, relative to the largest value of the sum.
double sum_error(const image& whole, const std::vector<const image*>& parts) {
  double worst = 0.0, largest = 0.0;
  for (std::size_t i = 0; i < whole.texels.size(); ++i)
    for (int c = 0; c < 3; ++c) {
      double sum = 0.0;
      for (const image* part : parts) sum += static_cast<double>(part->texels[i][c]);
      REQUIRE(std::isfinite(whole.texels[i][c]));
      worst = std::max(worst, std::abs(static_cast<double>(whole.texels[i][c]) - sum));
      largest = std::max(largest, std::abs(sum));
    }
  REQUIRE(largest > 0.0);
  return worst / largest;
}

}  // namespace

TEST_CASE("Light Wave, a point light in the open: its direct light is the closed form within 7 %, no acne, over the cube's faces") {
  const scene source = open_floor(point_at({0.3f, 1.0f, -0.2f}, glm::vec3(2.0f)));
  lightwave_pipeline pipeline(test_shaders(), source, lightwave_settings_of_side("lightwave-direct", 96));
  REQUIRE(pipeline.light_layers() == 6);
  const lightwave_frame frame = pipeline.render();
  std::size_t side_faces = 0;
  const direct_check open = compare_direct(source, source.view, frame.radiance, [&](const hit& h) {
    side_faces += cube_face_of(h.position - source.lights[0].point.position) != 3;
    return true;
  });
  CAPTURE(open.lit);
  CAPTURE(open.within);
  CAPTURE(open.dark);
  CAPTURE(open.mean_ratio());
  REQUIRE(open.lit > 96 * 96 / 2);
  CHECK(side_faces > open.lit / 4);  // the floor far from the light lies in the four side faces: the seams are crossed
  CHECK(std::abs(open.mean_ratio() - 1.0) <= 0.02);
  CHECK(static_cast<double>(open.dark) <= 0.01 * static_cast<double>(open.lit));
  CHECK(static_cast<double>(open.within) >= 0.97 * static_cast<double>(open.lit));
}

TEST_CASE("Light Wave, a point light behind a wall: its cube shadow map darkens the floor beyond the wall, not the floor before it") {
  const scene source = open_floor(point_at({0.3f, 1.0f, -0.2f}, glm::vec3(2.0f)), true);
  const lightwave_frame frame = lightwave_pipeline(test_shaders(), source, lightwave_settings_of_side("lightwave-direct", 96)).render();
  const direct_check before = compare_direct(source, source.view, frame.radiance, [](const hit& h) { return h.position.y < 0.01f && h.position.x < 0.8f; });
  // Beyond the wall the traced light is 0: count the pixels there that the pipeline lit.
  const float aspect = 1.0f;
  const glm::mat4 inverse = glm::inverse(camera_projection_matrix(source.view, aspect) * camera_view_matrix(source.view));
  std::size_t beyond = 0, leaking = 0;
  for (int y = 0; y < frame.radiance.height; ++y)
    for (int x = 0; x < frame.radiance.width; ++x) {
      const glm::vec2 ndc = (glm::vec2(x, y) + 0.5f) / glm::vec2(frame.radiance.width, frame.radiance.height) * 2.0f - 1.0f;
      const glm::vec4 far_point = inverse * glm::vec4(ndc, 1.0f, 1.0f);
      const std::optional<hit> h = trace(source.geometry, source.view.position, glm::normalize(glm::vec3(far_point) / far_point.w - source.view.position));
      if (!h || !(h->position.y < 0.01f && h->position.x > 1.3f)) continue;
      ++beyond;
      leaking += frame.radiance.at(x, y).r > 1e-3f;
    }
  CAPTURE(before.lit);
  CAPTURE(beyond);
  REQUIRE(before.lit > 500);
  REQUIRE(beyond > 300);
  CHECK(std::abs(before.mean_ratio() - 1.0) <= 0.03);
  CHECK(static_cast<double>(before.dark) <= 0.01 * static_cast<double>(before.lit));
  CHECK(static_cast<double>(leaking) <= 0.01 * static_cast<double>(beyond));
}

TEST_CASE("Light Wave, a point light in a closed box: all six walls lit at the closed form, no face missing, no dark seam") {
  const scene box = closed_box();
  lightwave_pipeline pipeline(test_shaders(), box, lightwave_settings_of_side("lightwave-direct", 64));
  for (int axis = 0; axis < 3; ++axis)
    for (float side : {-1.0f, 1.0f}) {
      CAPTURE(axis);
      CAPTURE(side);
      const camera view = facing_wall(axis, side);
      pipeline.set_camera(view);
      const lightwave_frame frame = pipeline.render();
      // The wall ahead only (the camera's 90 degrees see it whole, up to its edges).
      const direct_check wall = compare_direct(box, view, frame.radiance, [&](const hit& h) { return std::abs(h.position[axis] - side) < 1e-4f; });
      CAPTURE(wall.lit);
      CAPTURE(wall.within);
      CAPTURE(wall.dark);
      CAPTURE(wall.mean_ratio());
      REQUIRE(wall.lit > 64 * 64 * 9 / 10);
      // The wall's mean within 2 % of the closed form; no pixel darker than half of it (a face
      // missing or a seam's dark line would be).
      CHECK(std::abs(wall.mean_ratio() - 1.0) <= 0.02);
      CHECK(wall.dark == 0);
      CHECK(static_cast<double>(wall.within) >= 0.98 * static_cast<double>(wall.lit));
    }
}

TEST_CASE("Light Wave, a point light's flux VPLs in a closed box carry the whole sphere's flux, 4 pi I x albedo; every wall gets indirect light") {
  const scene box = closed_box();
  for (const char* technique : {"lightwave-unshadowed", "lightwave-accurate"}) {
    CAPTURE(technique);
    lightwave_pipeline pipeline(test_shaders(), box, lightwave_settings_of_side(technique, 32));
    pipeline.set_camera(facing_wall(1, -1.0f));
    pipeline.render();
    REQUIRE(pipeline.vpl_count() == lightwave_sphere_sample_count(5, 5));
    // Every sample's ray meets a wall that faces the light: all of them carry light.
    CHECK(pipeline.lit_vpl_count() == pipeline.vpl_count());
    glm::dvec3 total(0.0);
    for (const lightwave_flux_vpl<float>& vpl : pipeline.flux_vpls()) total += glm::dvec3(vpl.flux);
    const double expected = 4.0 * glm::pi<double>() * 1.5 * 0.6;
    CHECK(total.r == doctest::Approx(expected).epsilon(1e-4));
    // The merged VPLs the receivers sum keep it.
    glm::dvec3 merged(0.0);
    for (const lightwave_flux_vpl<float>& vpl : pipeline.receiver_vpls()) merged += glm::dvec3(vpl.flux);
    CHECK(merged.r == doctest::Approx(expected).epsilon(1e-4));
    CHECK(pipeline.receiver_vpls().size() < pipeline.flux_vpls().size());
  }
  // The indirect light on each wall: positive everywhere the camera sees it.
  lightwave_pipeline unshadowed(test_shaders(), box, lightwave_settings_of_side("lightwave-unshadowed", 32));
  for (int axis = 0; axis < 3; ++axis)
    for (float side : {-1.0f, 1.0f}) {
      unshadowed.set_camera(facing_wall(axis, side));
      const lightwave_frame frame = unshadowed.render();
      std::size_t dark = 0;
      for (const glm::vec4& t : frame.indirect.texels) dark += !(t.r > 0.0f);
      CAPTURE(axis);
      CAPTURE(side);
      CHECK(dark == 0);
    }
}

namespace {

// The image's indirect light (red, summed) and its lowest indirect shadow factor.
struct indirect_summary {
  double indirect = 0.0;
  float lowest_factor = 1.0f;
};
indirect_summary summarise(const lightwave_frame& frame) {
  indirect_summary s;
  for (const glm::vec4& t : frame.indirect.texels) s.indirect += t.r;
  for (const glm::vec4& t : frame.indirect_shadow.texels) s.lowest_factor = std::min(s.lowest_factor, t.r);
  return s;
}

}  // namespace

TEST_CASE("Light Wave, a point light's integrated shadows: in a closed box nothing occludes, every wall gets the unshadowed indirect light; a block still shadows the floor") {
  // The old failure: the thesis's integrated maps (the axis VPL under the bulb and a ring 45
  // degrees off it, all in the sphere's first hemisphere) all faced one way, and their lookups,
  // stepped between maps that see the other walls edge-on, darkened an empty box: 0.82 to 0.92
  // of the unshadowed light on five walls, lowest factors 0.52 to 0.60 (the kitchen measured 0.41
  // of the Monte Carlo reference, docs/scenes.md). Placed by importance they keep 0.91 to 0.98,
  // lowest factors 0.77 to 0.82: what remains is the stepping's own error (coordinates
  // interpolated between two views of a wall seen at a grazing angle), which the thesis has too.
  const scene box = closed_box();
  lightwave_pipeline integrated(test_shaders(), box, lightwave_settings_of_side("lightwave-integrated", 32));
  lightwave_pipeline unshadowed(test_shaders(), box, lightwave_settings_of_side("lightwave-unshadowed", 32));
  for (int axis = 0; axis < 3; ++axis)
    for (float side : {-1.0f, 1.0f}) {
      integrated.set_camera(facing_wall(axis, side));
      unshadowed.set_camera(facing_wall(axis, side));
      const indirect_summary shadowed = summarise(integrated.render()), open = summarise(unshadowed.render());
      CAPTURE(axis);
      CAPTURE(side);
      REQUIRE(open.indirect > 0.0);
      CHECK(shadowed.indirect / open.indirect >= 0.9);
      CHECK(shadowed.lowest_factor >= 0.7f);
    }
  // The maps spread over the room: not all on one surface.
  const std::vector<lightwave_shadow_caster>& casters = integrated.shadow_casters();
  REQUIRE(casters.size() == 5);
  int facings = 0;
  for (std::size_t i = 0; i < casters.size(); ++i) {
    bool new_facing = true;
    for (std::size_t k = 0; k < i; ++k)
      new_facing = new_facing && glm::dot(integrated.flux_vpls()[static_cast<std::size_t>(casters[i].vpl)].normal,
                                          integrated.flux_vpls()[static_cast<std::size_t>(casters[k].vpl)].normal) < 0.9f;
    facings += new_facing;
  }
  CHECK(facings >= 3);

  // A block on the floor under the light: the floor at its foot loses the light of the VPLs the
  // block hides (the walls' and the floor's beyond it), so the shadows must still darken there.
  scene blocked = box;
  add_box(blocked.geometry, {0.0f, -0.75f, 0.0f}, {0.5f, 0.5f, 0.5f}, 0.0f, glm::vec3(0.6f));
  lightwave_pipeline blocked_integrated(test_shaders(), blocked, lightwave_settings_of_side("lightwave-integrated", 32));
  lightwave_pipeline blocked_unshadowed(test_shaders(), blocked, lightwave_settings_of_side("lightwave-unshadowed", 32));
  blocked_integrated.set_camera(facing_wall(1, -1.0f));
  blocked_unshadowed.set_camera(facing_wall(1, -1.0f));
  const indirect_summary shadowed = summarise(blocked_integrated.render()), open = summarise(blocked_unshadowed.render());
  MESSAGE("a block on the floor: integrated / unshadowed indirect " << shadowed.indirect / open.indirect << ", lowest factor " << shadowed.lowest_factor);
  CHECK(shadowed.lowest_factor < 0.8f);
  CHECK(shadowed.indirect < 0.99 * open.indirect);
}

TEST_CASE("Light Wave, a sun on an open floor: its direct light is the closed form; its flux VPLs carry E x albedo x the floor's area across the light") {
  const glm::vec3 direction = glm::normalize(glm::vec3(0.3f, -1.0f, 0.2f));
  const scene source = open_floor(sun_along(direction, glm::vec3(1.2f)));
  lightwave_pipeline pipeline(test_shaders(), source, lightwave_settings_of_side("lightwave-direct", 96));
  REQUIRE(pipeline.light_layers() == 1);
  const lightwave_frame frame = pipeline.render();
  const direct_check open = compare_direct(source, source.view, frame.radiance, anywhere);
  CAPTURE(open.lit);
  CAPTURE(open.within);
  CAPTURE(open.dark);
  CAPTURE(open.mean_ratio());
  REQUIRE(open.lit > 96 * 96 / 2);
  CHECK(std::abs(open.mean_ratio() - 1.0) <= 0.02);
  CHECK(static_cast<double>(open.dark) <= 0.01 * static_cast<double>(open.lit));
  CHECK(static_cast<double>(open.within) >= 0.97 * static_cast<double>(open.lit));

  lightwave_pipeline flux(test_shaders(), source, lightwave_settings_of_side("lightwave-unshadowed", 32));
  flux.render();
  REQUIRE(flux.vpl_count() == lightwave_parallel_sample_count(5, 5));
  glm::dvec3 total(0.0);
  for (const lightwave_flux_vpl<float>& vpl : flux.flux_vpls()) {
    total += glm::dvec3(vpl.flux);
    REQUIRE(std::abs(vpl.position.y) < 1e-3f);  // on the floor
  }
  // The floor's 64 m^2 seen across the light: 64 |cos|; the grid's cells (37 across the window of
  // the scene's bounding diameter) cut the floor's border: 2 % covers a cell's width along it.
  const double expected = 1.2 * 0.5 * 64.0 * std::abs(static_cast<double>(direction.y));
  CHECK(total.r == doctest::Approx(expected).epsilon(0.02));
}

TEST_CASE("Light Wave, a point light split into two at its place: every technique's image is the sum of the parts' where the light is linear") {
  const scene box = [] {
    scene s = make_boxes_scene();
    s.lights = {point_at(s.lights.at(0).spot.position, glm::vec3(1.0f, 0.8f, 0.6f))};
    return s;
  }();
  const scene_light whole = box.lights[0];
  scene_light part_a = whole, part_b = whole;
  part_a.point.intensity = whole.point.intensity * 0.3f;
  part_b.point.intensity = whole.point.intensity * 0.7f;
  for (lightwave_energy energy : {lightwave_energy::flux, lightwave_energy::thesis})
    for (const lightwave_technique& technique : lightwave_techniques()) {
      // The thesis energy's VPLs ignore the light's intensity (docs/errata.md, LW-8): its indirect
      // light is not linear in the light, and two halves of a light bring twice the whole's.
      if (energy == lightwave_energy::thesis && technique.mode >= lightwave_mode::unshadowed) continue;
      CAPTURE(technique.name);
      CAPTURE(static_cast<int>(energy));
      lightwave_settings settings = lightwave_settings_of_side(technique.name, 48);
      settings.energy = energy;
      const lightwave_frame one = lightwave_pipeline(test_shaders(), box, settings).render();
      const lightwave_frame parts = lightwave_pipeline(test_shaders(), with_lights(box, {part_a, part_b}), settings).render();
      // The same VPLs, maps and casters for both parts: only the float sums differ.
      CHECK(sum_error(one.radiance, {&parts.radiance}) < 1e-5);
      if (technique.mode >= lightwave_mode::unshadowed) CHECK(sum_error(one.indirect, {&parts.indirect}) < 1e-5);
    }
}

namespace {

// A spot, a point light and a sun in the boxes scene: each technique's image and indirect light
// with all three against the sum of the three single-light images.
void check_mixed_lights(lightwave_energy energy) {
  scene mixed = make_boxes_scene();
  REQUIRE(mixed.lights.size() == 1);
  mixed.lights.push_back(point_at({0.5f, 1.2f, 0.3f}, {0.6f, 0.5f, 0.9f}));
  mixed.lights.push_back(sun_along({-0.4f, -1.0f, 0.3f}, {0.5f, 0.45f, 0.3f}));
  for (const lightwave_technique& technique : lightwave_techniques()) {
    CAPTURE(technique.name);
    CAPTURE(static_cast<int>(energy));
    lightwave_settings settings = lightwave_settings_of_side(technique.name, 32);
    settings.energy = energy;
    std::vector<lightwave_frame> single;
    std::vector<image> single_direct;  // render's -direct.pfm, the main pass's fifth output
    for (std::size_t k = 0; k < 3; ++k) {
      lightwave_pipeline alone(test_shaders(), with_lights(mixed, {mixed.lights[k]}), settings);
      single.push_back(alone.render());
      single_direct.push_back(alone.direct_output().read_image());
    }
    lightwave_pipeline all(test_shaders(), mixed, settings);
    REQUIRE(all.light_count() == 3);
    const lightwave_frame sum = all.render();
    // rgba32f targets, and each light runs the same passes alone as in the group (its own VPLs,
    // maps and casters): only the blend's float addition differs, as for the split light above
    // (measured 6e-8 to 8e-8 of the brightest pixel), so 1e-5, not the 1 % for half floats.
    const double radiance_error = sum_error(sum.radiance, {&single[0].radiance, &single[1].radiance, &single[2].radiance});
    const double direct_error = sum_error(all.direct_output().read_image(), {&single_direct[0], &single_direct[1], &single_direct[2]});
    const double indirect_error = technique.mode >= lightwave_mode::unshadowed
                                      ? sum_error(sum.indirect, {&single[0].indirect, &single[1].indirect, &single[2].indirect})
                                      : 0.0;
    MESSAGE(std::string(technique.name) << ": the three lights against the sum, radiance " << radiance_error << ", direct irradiance " << direct_error
                                        << ", indirect " << indirect_error);
    CHECK(radiance_error < 1e-5);
    CHECK(direct_error < 1e-5);
    CHECK(indirect_error < 1e-5);
    // The shadow factor, a ratio, is the first light's.
    for (std::size_t i = 0; i < sum.indirect_shadow.texels.size(); ++i) REQUIRE(sum.indirect_shadow.texels[i].r == single[0].indirect_shadow.texels[i].r);
    // Each light brings light of its own (a sum with one dropped would fail above).
    for (std::size_t k = 0; k < 3; ++k) {
      double lit = 0.0;
      for (const glm::vec4& t : single[k].radiance.texels) lit += t.r + t.g + t.b;
      CAPTURE(k);
      CHECK(lit > 0.0);
    }
  }
}

}  // namespace

TEST_CASE("Light Wave, a spot, a point light and a sun, flux energy: every technique's image, direct and indirect light are the sums of the single-light images to float rounding") {
  check_mixed_lights(lightwave_energy::flux);
}

TEST_CASE("Light Wave, a spot, a point light and a sun, thesis energy: every technique's image, direct and indirect light are the sums of the single-light images to float rounding" *
          doctest::test_suite("slow")) {
  check_mixed_lights(lightwave_energy::thesis);
}

TEST_CASE("Light Wave, several lights share the scene's mesh, receivers and screen buffers; a light keeps its kind when it moves") {
  scene mixed = make_boxes_scene();
  mixed.lights.push_back(point_at({0.5f, 1.2f, 0.3f}, glm::vec3(0.6f)));
  lightwave_pipeline pipeline(test_shaders(), mixed, lightwave_settings_of_side("lightwave-accurate", 32));
  REQUIRE(pipeline.light_count() == 2);
  CHECK(pipeline.light_pipeline(1).shares_resources_with(pipeline));
  CHECK(pipeline.light_pipeline(1).light_layers() == 6);
  // The receivers' textures and sum targets at least, which a further light no longer makes again.
  CHECK(pipeline.shared_bytes() > static_cast<std::uint64_t>(pipeline.drawn_mesh().vertices.size()) * 16u * 3u);
  const lightwave_pipeline alone(test_shaders(), with_lights(mixed, {mixed.lights[1]}), lightwave_settings_of_side("lightwave-accurate", 32));
  CHECK_FALSE(alone.shares_resources_with(pipeline));
  // A move that keeps the kind is drawn; one that changes it is refused, naming both kinds.
  scene_light moved = mixed.lights[1];
  moved.point.position.x -= 0.3f;
  CHECK_NOTHROW(pipeline.set_light(1, moved));
  CHECK_NOTHROW(pipeline.render());
  CHECK_THROWS_WITH_AS(pipeline.set_light(1, mixed.lights[0]), doctest::Contains("is a point light and cannot become a spot one"), error);
}
