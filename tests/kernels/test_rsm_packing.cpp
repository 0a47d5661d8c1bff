// The one-texel RSM encoding (vplkit/rsm_packing.hpp): depth exact, normals within 2^-16 per
// coordinate, flux within 2^-9 relative and unbiased, the empty texel empty, positions rebuilt
// on the texel's centre ray for a perspective and an orthographic light.
#include <doctest/doctest.h>

#include <cmath>
#include <random>

#include <glm/gtc/matrix_transform.hpp>

#include <vplkit/rsm_packing.hpp>
#include "tests/kernels/random_vectors.hpp"

using namespace vplkit;

namespace {

rsm_texel<float> round_trip(float depth, const glm::vec3& normal, const glm::vec3& flux) {
  return unpack_rsm_texel(pack_rsm_texel(depth, normal, flux), glm::ivec2(0), make_rsm_unprojection(1.0f, true, glm::ivec2(1)));
}

}  // namespace

TEST_CASE("normals: every coordinate round-trips within 2^-16, the axes and their signs exactly") {
  std::mt19937 random(3);
  float worst = 0.0f;
  for (int i = 0; i < 100000; ++i) {
    const glm::vec3 n = vplkit::testing::random_unit_vector<float>(random);
    const rsm_texel<float> back = round_trip(-1.0f, n, glm::vec3(1.0f));
    for (int k = 0; k < 3; ++k) {
      worst = std::max(worst, std::fabs(back.normal[k] - n[k]));
      REQUIRE((std::signbit(back.normal[k]) == std::signbit(n[k]) || back.normal[k] == 0.0f));
    }
  }
  MESSAGE("largest coordinate error: " << worst);
  // Half a step of 1/32767, and the float rounding of the product.
  CHECK(worst <= 0.5f / 32767.0f + 1e-7f);
  for (const glm::vec3 axis : {glm::vec3(1, 0, 0), glm::vec3(0, -1, 0), glm::vec3(0, 0, 1), glm::vec3(0, 0, -1)})
    CHECK(round_trip(-1.0f, axis, glm::vec3(0.0f)).normal == axis);
}

TEST_CASE("flux keeps 8 mantissa bits rounded to nearest (relative error <= 2^-9, mean error ~0); depth is exact") {
  std::mt19937 random(4);
  std::uniform_real_distribution<float> exponent(-40.0f, 40.0f);
  double signed_error = 0.0;
  const int count = 100000;
  for (int i = 0; i < count; ++i) {
    const glm::vec3 flux(std::exp2(exponent(random)), std::exp2(exponent(random)), std::exp2(exponent(random)));
    const float depth = -std::exp2(exponent(random));
    const rsm_texel<float> back = round_trip(depth, glm::vec3(0, 0, 1), flux);
    REQUIRE(back.position.z == depth);
    for (int c = 0; c < 3; ++c) {
      REQUIRE(std::fabs(back.flux[c] - flux[c]) <= flux[c] * std::exp2(-9.0f));
      signed_error += (static_cast<double>(back.flux[c]) - flux[c]) / flux[c];
    }
  }
  // Truncation would bias every texel down by ~2^-9 on average: rounding leaves no bias.
  CHECK(std::fabs(signed_error / (3.0 * count)) < 2e-5);
  const rsm_texel<float> empty = unpack_rsm_texel(glm::uvec4(0u), glm::ivec2(5, 7), make_rsm_unprojection(1.0f, true, glm::ivec2(8)));
  CHECK(empty.position.z == 0.0f);  // an empty texel (the cleared target) stays empty
  CHECK(empty.flux == glm::vec3(0.0f));
  // Out of the domain: no NaN and no infinity come back.
  for (const float bad : {-1.0f, -0.0f, std::nanf(""), INFINITY, 3.4e38f}) {
    const float back = round_trip(-1.0f, glm::vec3(0, 0, 1), glm::vec3(bad)).flux.r;
    CAPTURE(bad);
    CHECK(std::isfinite(back));
    CHECK(back >= 0.0f);
  }
}

TEST_CASE("positions are rebuilt on the texel's centre ray: a spot light's and a directional light's RSM") {
  const glm::vec3 eye(0.3f, 1.9f, -0.2f);
  const glm::mat4 view = glm::lookAt(eye, eye + glm::vec3(0.1f, -1.0f, 0.05f), glm::vec3(0, 0, -1));
  for (const bool perspective : {true, false}) {
    CAPTURE(perspective);
    const float tan_half = 1.2f, half_extent = 2.5f;
    const glm::mat4 projection = perspective ? glm::perspective(2.0f * std::atan(tan_half), 1.0f, 0.01f, 10.0f)
                                             : glm::ortho(-half_extent, half_extent, -half_extent, half_extent, 0.1f, 10.0f);
    const glm::ivec2 size(64, 48);
    const rsm_unprojection<float> light = make_rsm_unprojection(perspective ? tan_half : half_extent, perspective, size);
    const glm::mat4 to_world = glm::inverse(view);
    for (const glm::ivec2 texel : {glm::ivec2(0, 0), glm::ivec2(31, 40), glm::ivec2(63, 5), glm::ivec2(63, 47)}) {
      const float depth = -1.7f;
      const rsm_texel<float> back = unpack_rsm_texel(pack_rsm_texel(depth, glm::vec3(0, 1, 0), glm::vec3(1.0f)), texel, light);
      // The rebuilt point, in the world, projects onto the texel's centre at the stored depth.
      const glm::vec2 at = map_coordinate(projection * view, transform_point(to_world, back.position), size);
      CHECK(at.x == doctest::Approx(static_cast<float>(texel.x) + 0.5f).epsilon(1e-4));
      CHECK(at.y == doctest::Approx(static_cast<float>(texel.y) + 0.5f).epsilon(1e-4));
      CHECK(back.position.z == depth);
    }
  }
}
