// The shadow density of Alg. 4 (include/vplkit/shadow.hpp) on a synthetic RSM: lit, shadowed and
// softened edges, the receiver-plane gradient against self-shadowing, and the slope-scaled,
// normal-offset bias in the receiver's texel footprint (closed forms, a grazing plane, a contact).
#include <doctest/doctest.h>

#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

#include <vplkit/shadow.hpp>

#include "tests/kernels/synthetic_rsm.hpp"

using namespace vplkit;
// The synthetic scene's names one by one: a using-directive would reach into the files compiled
// after this one in its unity batch (tests/CMakeLists.txt).
using vplkit::testing::light_height;
using vplkit::testing::light_view_projection;
using vplkit::testing::rsm_size;
using vplkit::testing::synthetic_rsm;

TEST_CASE("Alg. 4: a flat lit floor is lit, an occluder's shadow is dark, the window softens the edge") {
  // Depths of the synthetic scene: floor at y = 0 (eye depth -10), block top at eye depth -9.2.
  synthetic_rsm scene;
  scene.block_x0 = 0.3;
  scene.block_x1 = 0.8;
  scene.block_height = 0.8;
  const auto depth = [&](glm::ivec2 t) { return scene(t).position.z; };
  const shadow_density_settings<double> settings;  // kernel 4, bias 0.02
  const auto density_at = [&](double x) {
    const glm::dvec3 floor_point(x, 0.0, 0.1);
    return shadow_density(map_coordinate(light_view_projection(), floor_point, glm::ivec2(rsm_size)), floor_point.y - light_height,
                          glm::dvec2(0.0), depth, glm::ivec2(rsm_size), settings);
  };
  CHECK(density_at(-1.0) == 1.0);  // open floor
  CHECK(density_at(0.5) == 0.0);   // under the block (the light looks straight down)
  const double edge = density_at(0.3);  // straddling the block's edge: partly shadowed
  CHECK(edge > 0.0);
  CHECK(edge < 1.0);
  // The block's own top is lit: its window sees only itself (and the lower floor beyond it).
  const glm::dvec3 top(0.55, 0.8, 0.1);
  CHECK(shadow_density(map_coordinate(light_view_projection(), top, glm::ivec2(rsm_size)), top.y - light_height, glm::dvec2(0.0), depth,
                       glm::ivec2(rsm_size), settings) == 1.0);
  // Outside the RSM counts as not lit (Alg. 4, line 5).
  CHECK(shadow_density(glm::dvec2(-10.0), -10.0, glm::dvec2(0.0), depth, glm::ivec2(rsm_size), settings) == 0.0);
}

TEST_CASE("Alg. 4: the receiver-plane gradient removes self-shadowing of a slope; without it the slope shadows itself") {
  // A slope whose depth falls 0.05 per RSM texel in x: a 4 x 4 window spans 0.2 of depth.
  const auto slope_depth = [](glm::ivec2 t) { return -10.0 - 0.05 * (t.x + 0.5 - 128.0); };
  const shadow_density_settings<double> settings;
  const glm::dvec2 centre(128.3, 100.6);
  const double receiver = -10.0 - 0.05 * (centre.x - 128.0);
  CHECK(shadow_density(centre, receiver, glm::dvec2(-0.05, 0.0), slope_depth, glm::ivec2(256), settings) == 1.0);
  CHECK(shadow_density(centre, receiver, glm::dvec2(0.0), slope_depth, glm::ivec2(256), settings) < 1.0);
}


TEST_CASE("shadow bias: the texel footprint is the map's width over its texels at the receiver") {
  const double half_fov = 0.4;
  const glm::dmat4 spot = glm::perspective(2.0 * half_fov, 1.0, 0.1, 100.0);
  CHECK(shadow_texel_footprint(spot, -7.0, 512) == doctest::Approx(2.0 * 7.0 * std::tan(half_fov) / 512.0).epsilon(1e-12));
  const glm::dmat4 sun = glm::ortho(-3.0, 3.0, -3.0, 3.0, 0.5, 20.0);
  CHECK(shadow_texel_footprint(sun, -7.0, 256) == doctest::Approx(6.0 / 256.0).epsilon(1e-12));
  CHECK(shadow_texel_footprint(sun, -1.0, 256) == doctest::Approx(6.0 / 256.0).epsilon(1e-12));  // a sun's does not grow with depth
}

TEST_CASE("shadow bias: the normal offset is normal_offset footprints times sin(theta), none facing the light") {
  shadow_density_settings<double> settings;
  settings.normal_offset = 1.5;
  const glm::dvec3 p(1.0, 2.0, 3.0), n(0.0, 1.0, 0.0);
  CHECK(shadow_normal_offset(p, n, n, 0.1, settings) == p);  // facing the light
  const double theta = 1.2;
  const glm::dvec3 to_light(std::sin(theta), std::cos(theta), 0.0);
  const glm::dvec3 moved = shadow_normal_offset(p, n, to_light, 0.1, settings);
  CHECK(moved.y - p.y == doctest::Approx(1.5 * 0.1 * std::sin(theta)).epsilon(1e-12));
  CHECK(moved.x == p.x);
  CHECK(moved.z == p.z);
}

TEST_CASE("shadow bias: the slope-scaled bias is depth_bias + slope_scale footprint tan(theta), clamped at max_slope") {
  shadow_density_settings<double> settings;
  settings.depth_bias = 0.01;
  settings.slope_scale = 2.0;
  settings.max_slope = 10.0;
  CHECK(shadow_slope_bias(1.0, 0.05, settings) == doctest::Approx(0.01).epsilon(1e-12));
  CHECK(shadow_slope_bias(std::cos(0.7), 0.05, settings) == doctest::Approx(0.01 + 2.0 * 0.05 * std::tan(0.7)).epsilon(1e-12));
  CHECK(shadow_slope_bias(std::cos(1.5), 0.05, settings) == doctest::Approx(0.01 + 2.0 * 0.05 * 10.0).epsilon(1e-12));  // tan 1.5 = 14 > 10
  CHECK(shadow_slope_bias(-0.5, 0.05, settings) == doctest::Approx(0.01 + 2.0 * 0.05 * 10.0).epsilon(1e-12));  // facing away
  CHECK_FALSE(validate(settings));
  settings.max_slope = 0.0;
  CHECK(static_cast<bool>(validate(settings)));
}

TEST_CASE("shadow bias: a plane grazing the light at 80 degrees, its gradient a quarter off, shadows itself without the slope bias, not with it") {
  // The plane's depth falls footprint tan(theta) per texel; the receiver-plane gradient from
  // screen-space derivatives is off by a quarter (it is clamped or straddles a silhouette).
  const double footprint = 0.02, theta = glm::radians(80.0), per_texel = footprint * std::tan(theta);
  const auto plane_depth = [&](glm::ivec2 t) { return -10.0 - per_texel * (t.x + 0.5 - 128.0); };
  const glm::dvec2 centre(128.3, 100.6);
  const double receiver = -10.0 - per_texel * (centre.x - 128.0);
  const glm::dvec2 gradient(-0.75 * per_texel, 0.0);
  shadow_density_settings<double> settings;
  settings.depth_bias = 0.0;
  settings.slope_scale = 0.0;
  CHECK(shadow_density(centre, receiver, gradient, plane_depth, glm::ivec2(256), settings) < 1.0);
  settings.slope_scale = 1.0;
  settings.depth_bias = shadow_slope_bias(std::cos(theta), footprint, settings);
  CHECK(shadow_density(centre, receiver, gradient, plane_depth, glm::ivec2(256), settings) == 1.0);
  // An occluder a texel's slope bias nearer than the plane (a box's base standing on it) still
  // shadows it: the bias is one texel's depth change, not more.
  const auto occluded = [&](glm::ivec2 t) { return plane_depth(t) + 2.0 * per_texel + 0.05; };
  CHECK(shadow_density(centre, receiver, gradient, occluded, glm::ivec2(256), settings) == 0.0);
}
