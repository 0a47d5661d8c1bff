// The shadow density of Alg. 4 (include/vplkit/shadow.hpp) on a synthetic RSM: lit, shadowed and
// softened edges, and the receiver-plane gradient against self-shadowing.
#include <doctest/doctest.h>

#include <cmath>

#include <vplkit/shadow.hpp>

#include "tests/kernels/synthetic_rsm.hpp"

using namespace vplkit;
using namespace vplkit::testing;

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

