// Final gathering with the scene's lights (issue 38): any mix of spots, point lights and suns,
// each with its own shadows, summed; none is black. The properties: two lights give the sum of
// the single-light images (linear: to float rounding in the pipeline, within 1 % for the sampled
// references) for the three techniques and both references of
// the object's indirect light; a point light's occluder darkens the wall behind it in the
// distance cube map (the point light's cube shadow map); a second light of zero power leaves the
// single-spot images bit for bit (the summing passes add exact zeros); a sun over the closed box
// lights nothing inside (its orthographic shadow map); no light is black.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include <vplkit/direct_light.hpp>
#include <vplkit/final_gather.hpp>

#include "frontend/reference/final_gather_reference.hpp"
#include "frontend/reference/monte_carlo.hpp"
#include "frontend/reference/ray_scene.hpp"
#include "tests/frontend/techniques/pass_parity.hpp"

using namespace vplkit;
using namespace vplkit::parity;

namespace {

final_gather_settings small_final_gather_settings(const char* technique) {
  final_gather_settings settings;
  settings.technique = technique;
  settings.width = settings.height = 48;
  settings.face_size = 32;
  settings.resolution = 4;
  settings.environment_resolution = 8;
  return settings;
}

scene_light bulb_at(glm::vec3 position, float intensity) {
  scene_light light;
  light.kind = light_kind::point;
  light.point.position = position;
  light.point.intensity = glm::vec3(intensity);
  return light;
}

// The built-in box with the given lights.
final_gather_scene box_lit_by(const std::vector<scene_light>& lights, glm::vec3 object = glm::vec3(0.3f, 0.7f, 0.1f)) {
  scene room = final_gather_box();
  room.lights = lights;
  return make_final_gather_scene(room, "sphere", object, 0.5f);
}

// |a - b| summed over the pixels and channels, against the sum of |b|: the relative L1 distance.
double relative_difference(const image& a, const image& b) {
  double difference = 0.0, total = 0.0;
  for (std::size_t i = 0; i < a.texels.size(); ++i)
    for (int c = 0; c < 3; ++c) {
      difference += std::abs(static_cast<double>(a.texels[i][c]) - b.texels[i][c]);
      total += std::abs(static_cast<double>(b.texels[i][c]));
    }
  return total > 0.0 ? difference / total : (difference > 0.0 ? 1.0 : 0.0);
}

image sum_of(const image& a, const image& b) {
  image out = a;
  for (std::size_t i = 0; i < out.texels.size(); ++i) out.texels[i] = glm::vec4(glm::vec3(a.texels[i]) + glm::vec3(b.texels[i]), 1.0f);
  return out;
}

}  // namespace

TEST_CASE("final gathering with two lights (a spot and a point light) is the sum of the single-light images (radiance, indirect and direct light) to float rounding: the three techniques") {
  const scene_light spot = final_gather_box().lights.at(0);
  const scene_light bulb = bulb_at(glm::vec3(-0.4f, 1.5f, -0.3f), 0.6f);
  for (const char* technique : {"finalgather-polygon", "finalgather-point", "envmap"}) {
    INFO(technique);
    final_gather_pipeline both(test_shaders(), box_lit_by({spot, bulb}), small_final_gather_settings(technique));
    final_gather_pipeline only_spot(test_shaders(), box_lit_by({spot}), small_final_gather_settings(technique));
    final_gather_pipeline only_bulb(test_shaders(), box_lit_by({bulb}), small_final_gather_settings(technique));
    const final_gather_frame f2 = both.render(), fs = only_spot.render(), fb = only_bulb.render();
    // Each light contributes a real share (else the sum would hold trivially).
    const double spot_share = relative_difference(fs.indirect, f2.indirect), bulb_share = relative_difference(fb.indirect, f2.indirect);
    MESSAGE(std::string(technique) << ": the spot's image differs from the two lights' by " << spot_share << " (the point light's share), the point light's by "
                                   << bulb_share);
    CHECK(spot_share > 0.1);
    CHECK(bulb_share > 0.1);
    const double radiance_error = relative_difference(f2.radiance, sum_of(fs.radiance, fb.radiance));
    const double indirect_error = relative_difference(f2.indirect, sum_of(fs.indirect, fb.indirect));
    // The direct light (render's -direct.pfm: the shading pass's third output, the per-light
    // final_gather_direct.frag passes summed).
    const double direct_error = relative_difference(both.direct_output().read_image(),
                                                    sum_of(only_spot.direct_output().read_image(), only_bulb.direct_output().read_image()));
    MESSAGE(std::string(technique) << ": two lights against the sum, radiance " << radiance_error << ", indirect " << indirect_error << ", direct "
                                   << direct_error);
    // Each light's passes are the same alone and in the pair; only the blends' float additions
    // differ (measured below 1.1e-7), so 1e-5 rather than the 1 % for half floats.
    CHECK(radiance_error < 1e-5);
    CHECK(indirect_error < 1e-5);
    CHECK(direct_error < 1e-5);
  }
}

TEST_CASE("final gathering's references sum the lights: the Monte Carlo one bounce and the exact patch gather, two lights = the sum within 1 %") {
  const scene_light spot = final_gather_box().lights.at(0);
  const scene_light bulb = bulb_at(glm::vec3(-0.4f, 1.5f, -0.3f), 0.6f);
  const final_gather_scene both = box_lit_by({spot, bulb}), only_spot = box_lit_by({spot}), only_bulb = box_lit_by({bulb});
  const ray_scene room(both.room);
  const irradiance_settings<float> irradiance;
  for (const glm::vec3 n : {glm::vec3(1, 0, 0), glm::vec3(0, 1, 0), glm::vec3(0, 0, -1)}) {
    const glm::vec3 x = both.reference_point + 0.25f * n;
    const glm::vec3 e2 = one_bounce_irradiance(room, both.lights, irradiance, x, n, 256, 7u, 1u);
    const glm::vec3 es = one_bounce_irradiance(room, only_spot.lights, irradiance, x, n, 256, 7u, 1u);
    const glm::vec3 eb = one_bounce_irradiance(room, only_bulb.lights, irradiance, x, n, 256, 7u, 1u);
    REQUIRE(es.r + es.g + es.b > 0.0f);
    REQUIRE(eb.r + eb.g + eb.b > 0.0f);
    for (int c = 0; c < 3; ++c) CHECK(e2[c] == doctest::Approx(es[c] + eb[c]).epsilon(0.01));
    const double r2 = final_gather_reference(both, glm::dvec3(x), glm::dvec3(n), 8);
    const double rs = final_gather_reference(only_spot, glm::dvec3(x), glm::dvec3(n), 8);
    const double rb = final_gather_reference(only_bulb, glm::dvec3(x), glm::dvec3(n), 8);
    REQUIRE(rs > 0.0);
    REQUIRE(rb > 0.0);
    CHECK(r2 == doctest::Approx(rs + rb).epsilon(0.01));
  }
}

TEST_CASE("final gathering: a second light of zero power leaves the single-spot images bit for bit") {
  const scene_light spot = final_gather_box().lights.at(0);
  for (const scene_light& dark : {bulb_at(glm::vec3(0.2f, 1.2f, 0.3f), 0.0f), [] {
         scene_light sun;
         sun.kind = light_kind::directional;
         sun.directional.direction = glm::normalize(glm::vec3(0.3f, -1.0f, 0.2f));
         sun.directional.irradiance = glm::vec3(0.0f);
         return sun;
       }()}) {
    for (const char* technique : {"finalgather-polygon", "envmap"}) {
      INFO(technique << ", a dark " << light_kind_name(dark.kind));
      final_gather_pipeline one(test_shaders(), box_lit_by({spot}), small_final_gather_settings(technique));
      final_gather_pipeline two(test_shaders(), box_lit_by({spot, dark}), small_final_gather_settings(technique));
      const final_gather_frame a = one.render(), b = two.render();
      std::size_t differing = 0, lit = 0;
      for (std::size_t i = 0; i < a.radiance.texels.size(); ++i) {
        lit += a.radiance.texels[i].r > 0.0f;
        differing += a.radiance.texels[i] != b.radiance.texels[i] || a.indirect.texels[i] != b.indirect.texels[i];
      }
      CHECK(lit > 500);
      CHECK(differing == 0);
    }
  }
}

TEST_CASE("final gathering: a point light's occluder darkens the wall behind it in the distance cube map, as a shadow ray finds") {
  // The box lit by a point light near the red wall (x = -1); a panel between them (x = -0.7,
  // facing the light) hides part of the wall. The cube map around an object on the other side
  // (M = the face size, so each texel is one face texel) sees that wall past the panel.
  scene room = final_gather_box();
  room.lights = {bulb_at(glm::vec3(-0.3f, 1.0f, 0.0f), 1.0f)};
  add_quad(room.geometry, {-0.7f, 0.8f, 0.25f}, {-0.7f, 0.8f, -0.25f}, {-0.7f, 1.2f, -0.25f}, {-0.7f, 1.2f, 0.25f}, {1, 0, 0}, glm::vec3(0.5f));
  const final_gather_scene s = make_final_gather_scene(room, "sphere", glm::vec3(0.5f, 1.0f, 0.6f), 0.2f);
  final_gather_settings settings = small_final_gather_settings("finalgather-polygon");
  settings.face_size = settings.resolution = 32;
  final_gather_pipeline pipeline(test_shaders(), s, settings);
  pipeline.render();
  const image cube = pipeline.read_buffers().small_cube;
  const ray_scene rays(s.room);
  const glm::vec3 light = s.lights[0].point.position;
  const int m = settings.resolution;
  std::size_t shadowed = 0, lit = 0, dark_in_shadow = 0, bright_in_light = 0;
  for (int face = 0; face < 6; ++face)
    for (int j = 0; j < m; ++j)
      for (int i = 0; i < m; ++i) {
        const glm::vec4 texel = cube.at(glm::ivec2(face * m + i, j));
        const glm::vec3 p = s.reference_point + glm::normalize(cube_texel_direction<float>(face, i, j, m)) * texel.w;
        if (!(p.x < -0.99f) || std::abs(p.y - 1.0f) > 0.6f || std::abs(p.z) > 0.6f) continue;  // the red wall around the panel's shadow
        // Clear of the shadow's edge: all four points a little around p agree.
        int occluded = 0;
        for (const glm::vec2 d : {glm::vec2(0.03f, 0.0f), glm::vec2(-0.03f, 0.0f), glm::vec2(0.0f, 0.03f), glm::vec2(0.0f, -0.03f)})
          occluded += rays.occluded(p + glm::vec3(1e-3f, d.x, d.y), light);
        if (occluded == 4) {
          ++shadowed;
          dark_in_shadow += glm::length(glm::vec3(texel)) == 0.0f;
        } else if (occluded == 0) {
          ++lit;
          bright_in_light += texel.r > 0.0f;
        }
      }
  MESSAGE("red-wall texels in the panel's shadow " << shadowed << " (black: " << dark_in_shadow << "), lit " << lit << " (red: " << bright_in_light << ")");
  REQUIRE(shadowed >= 10);
  REQUIRE(lit >= 10);
  CHECK(dark_in_shadow == shadowed);
  CHECK(bright_in_light == lit);
}

TEST_CASE("final gathering with no light is black: the view, the object's indirect light, every technique") {
  for (const char* technique : {"finalgather-polygon", "finalgather-point", "envmap"}) {
    INFO(technique);
    final_gather_pipeline pipeline(test_shaders(), box_lit_by({}), small_final_gather_settings(technique));
    const final_gather_frame frame = pipeline.render();
    const final_gather_buffers buffers = pipeline.read_buffers();
    std::size_t surfaces = 0, nonzero = 0;
    for (std::size_t i = 0; i < frame.radiance.texels.size(); ++i) {
      surfaces += buffers.gbuffer[0].texels[i].w > 0.5f;
      nonzero += glm::vec3(frame.radiance.texels[i]) != glm::vec3(0.0f) || glm::vec3(frame.indirect.texels[i]) != glm::vec3(0.0f);
    }
    CHECK(surfaces > 1000);  // the room and the object are there, drawn black
    CHECK(nonzero == 0);
    CHECK(pipeline.current_lights().empty());
    CHECK_THROWS_WITH_AS(pipeline.set_light(0, final_gather_box().lights[0]), doctest::Contains("no light 0 (it has 0)"), vplkit::error);
  }
}

TEST_CASE("final gathering: a sun over the closed box lights nothing inside it (its orthographic shadow map: the ceiling and walls hide it)") {
  scene_light sun;
  sun.kind = light_kind::directional;
  sun.directional.direction = glm::normalize(glm::vec3(0.3f, -1.0f, 0.2f));
  sun.directional.irradiance = glm::vec3(2.0f);
  final_gather_pipeline pipeline(test_shaders(), box_lit_by({sun}), small_final_gather_settings("finalgather-polygon"));
  const final_gather_frame frame = pipeline.render();
  const final_gather_buffers buffers = pipeline.read_buffers();
  // Receivers the sun faces (unshadowed irradiance > 0) must all be dark, except on the room's
  // edges: a pixel whose surface point lies exactly where a wall meets the floor or the ceiling
  // touches its occluder, which any depth bias lets through (and a shadow ray starting on the
  // wall's plane misses it too).
  std::size_t facing = 0, lit = 0, edge = 0;
  double unshadowed = 0.0, indirect = 0.0;
  for (std::size_t i = 0; i < buffers.gbuffer[0].texels.size(); ++i) {
    const glm::vec4 position_kind = buffers.gbuffer[0].texels[i];
    if (position_kind.w < 0.5f) continue;
    const glm::vec3 p(position_kind), n(buffers.gbuffer[1].texels[i]);
    const float e = directional_light_irradiance(n, sun.directional).r;
    unshadowed += e;
    indirect += frame.indirect.texels[i].r;
    if (e <= 0.0f) continue;
    const int at_bounds = (1.0f - std::abs(p.x) < 0.004f) + (std::min(p.y, 2.0f - p.y) < 0.004f) + (1.0f - std::abs(p.z) < 0.004f);
    if (at_bounds >= 2) {
      ++edge;
      continue;
    }
    ++facing;
    lit += buffers.direct.texels[i].r > 0.0f;
  }
  MESSAGE("receivers facing the sun " << facing << " (lit: " << lit << "), on the room's edges " << edge << "; indirect " << indirect
                                      << " against the unshadowed irradiance " << unshadowed);
  REQUIRE(facing > 500);
  CHECK(lit == 0);
  CHECK(indirect < 0.01 * unshadowed);
}
