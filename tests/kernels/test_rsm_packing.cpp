// The one-texel RSM encoding (vplkit/rsm_packing.hpp): depth exact, normals within the 16-bit
// octahedral grid, flux within 2^-13 relative, positions rebuilt on the texel's centre ray for a
// perspective and an orthographic light.
#include <doctest/doctest.h>

#include <cmath>
#include <random>

#include <glm/gtc/matrix_transform.hpp>

#include <vplkit/rsm_packing.hpp>

using namespace vplkit;

namespace {

glm::vec3 random_unit(std::mt19937& random) {
  std::normal_distribution<float> normal;
  return glm::normalize(glm::vec3(normal(random), normal(random), normal(random)));
}

}  // namespace

TEST_CASE("octahedral normals: every direction round-trips within the 16-bit grid, axes exactly") {
  std::mt19937 random(3);
  float worst = 0.0f;
  for (int i = 0; i < 100000; ++i) {
    const glm::vec3 n = random_unit(random);
    const rsm_texel<float> back = unpack_rsm_texel(pack_rsm_texel(-1.0f, n, glm::vec3(1.0f)), glm::ivec2(0), rsm_unprojection<float>{});
    // The angle from the chord, in double (acos of a float dot product near 1 resolves only 3e-4 rad).
    worst = std::max(worst, static_cast<float>(2.0 * std::asin(glm::length(glm::dvec3(n) - glm::dvec3(back.normal)) / 2.0)));
    REQUIRE(std::fabs(glm::length(back.normal) - 1.0f) < 1e-6f);
  }
  // Two 16-bit coordinates on the unfolded octahedron: 3e-5 of the square per step, at most a few
  // times that in angle where the octahedron is most stretched.
  MESSAGE("largest normal error: " << worst << " rad");
  CHECK(worst < 2e-4f);
  for (const glm::vec3 axis : {glm::vec3(1, 0, 0), glm::vec3(0, -1, 0), glm::vec3(0, 0, 1), glm::vec3(0, 0, -1)}) {
    const rsm_texel<float> back = unpack_rsm_texel(pack_rsm_texel(-1.0f, axis, glm::vec3(0.0f)), glm::ivec2(0), rsm_unprojection<float>{});
    CHECK(glm::dot(back.normal, axis) > 1.0f - 1e-6f);
  }
}

TEST_CASE("flux keeps 13 mantissa bits (relative error < 2^-13, never above the input); depth is exact") {
  std::mt19937 random(4);
  std::uniform_real_distribution<float> exponent(-20.0f, 20.0f);
  for (int i = 0; i < 100000; ++i) {
    const glm::vec3 flux(std::exp2(exponent(random)), std::exp2(exponent(random)), std::exp2(exponent(random)));
    const float depth = -std::exp2(exponent(random));
    const rsm_texel<float> back = unpack_rsm_texel(pack_rsm_texel(depth, glm::vec3(0, 0, 1), flux), glm::ivec2(0), rsm_unprojection<float>{});
    REQUIRE(back.eye_depth == depth);
    for (int c = 0; c < 3; ++c) {
      REQUIRE(back.flux[c] <= flux[c]);
      REQUIRE(back.flux[c] >= flux[c] * (1.0f - std::exp2(-13.0f)));
    }
  }
  const rsm_texel<float> empty = unpack_rsm_texel(glm::uvec4(0u), glm::ivec2(0), rsm_unprojection<float>{});
  CHECK(empty.eye_depth == 0.0f);  // an empty texel (the cleared target) stays empty
  CHECK(empty.flux == glm::vec3(0.0f));
}

TEST_CASE("positions are rebuilt on the texel's centre ray: a spot light's and a directional light's RSM") {
  const glm::vec3 eye(0.3f, 1.9f, -0.2f);
  const glm::mat4 view = glm::lookAt(eye, eye + glm::vec3(0.1f, -1.0f, 0.05f), glm::vec3(0, 0, -1));
  for (const int perspective : {1, 0}) {
    CAPTURE(perspective);
    const float tan_half = 1.2f, half_extent = 2.5f;
    const glm::mat4 projection = perspective ? glm::perspective(2.0f * std::atan(tan_half), 1.0f, 0.01f, 10.0f)
                                             : glm::ortho(-half_extent, half_extent, -half_extent, half_extent, 0.1f, 10.0f);
    rsm_unprojection<float> light;
    light.inverse_light_view = glm::inverse(view);
    light.scale = perspective ? tan_half : half_extent;
    light.perspective = perspective;
    light.size = glm::ivec2(64, 64);
    for (const glm::ivec2 texel : {glm::ivec2(0, 0), glm::ivec2(31, 40), glm::ivec2(63, 5)}) {
      const float depth = -1.7f;
      const rsm_texel<float> back = unpack_rsm_texel(pack_rsm_texel(depth, glm::vec3(0, 1, 0), glm::vec3(1.0f)), texel, light);
      // The rebuilt point projects onto the texel's centre at the stored depth.
      const glm::vec2 at = map_coordinate(projection * view, back.position, light.size);
      CHECK(at.x == doctest::Approx(static_cast<float>(texel.x) + 0.5f).epsilon(1e-4));
      CHECK(at.y == doctest::Approx(static_cast<float>(texel.y) + 0.5f).epsilon(1e-4));
      CHECK(transform_point(view, back.position).z == doctest::Approx(depth).epsilon(1e-5));
    }
  }
}
