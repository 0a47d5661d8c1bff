// Properties of the Light Wave kernels (include/vplkit/lightwave.hpp), against the numbers the
// thesis prints ([LW], Tables 5.1, 5.2 and 5.10, Eq. 4.2, 4.8).
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include <vplkit/lightwave.hpp>

using namespace vplkit;

TEST_CASE("Eq. 5.1 gives the VPL counts of Tables 5.1 and 5.2") {
  // Table 5.1: 5 VPLs per ray, angle 5, 10, 30, 45, 90.
  CHECK(lightwave_vpl_count(5, 5) == 6485);
  CHECK(lightwave_vpl_count(10, 5) == 1625);
  CHECK(lightwave_vpl_count(30, 5) == 185);
  CHECK(lightwave_vpl_count(45, 5) == 85);
  CHECK(lightwave_vpl_count(90, 5) == 25);
  // Table 5.2: 5 degrees, 1 .. 6 per ray.
  const int per_ray_counts[] = {1297, 2594, 3891, 5188, 6485, 7782};
  for (int per_ray = 1; per_ray <= 6; ++per_ray) CHECK(lightwave_vpl_count(5, per_ray) == per_ray_counts[per_ray - 1]);
}

TEST_CASE("Eq. 4.8: 40, 60, 80 and 120 integrated shadows for 2, 4, 6 and 10 steps over 5 maps") {
  CHECK(lightwave_integrated_shadow_count(2, 5) == 40);
  CHECK(lightwave_integrated_shadow_count(4, 5) == 60);
  CHECK(lightwave_integrated_shadow_count(6, 5) == 80);
  CHECK(lightwave_integrated_shadow_count(10, 5) == 120);
  CHECK(lightwave_integrated_shadow_count(10, 2) == 12);  // one pair
  CHECK(lightwave_integrated_shadow_count(3, 1) == 0);    // no pair
}

TEST_CASE("Eq. 4.2: attenuation 5%, 10%, 20%, 40%, 80% (and 160% at the sixth hemisphere); the 240-degree lobe") {
  const double expected[] = {0.05, 0.1, 0.2, 0.4, 0.8, 1.6};
  for (int h = 0; h < 6; ++h) CHECK(lightwave_attenuation<double>(h) == doctest::Approx(expected[h]).epsilon(1e-15));
  CHECK(lightwave_lobe(1.0) == 1.0);
  CHECK(lightwave_lobe(-0.5) == 0.0);
  CHECK(lightwave_lobe(-0.9) == 0.0);  // beyond 120 degrees off the normal
  CHECK(lightwave_lobe(0.0) == doctest::Approx(1.0 / 3.0));
  CHECK(lightwave_lobe(std::cos(2.0 * 3.14159265358979 / 3.0) + 1e-9) > 0.0);  // 120 degrees: the edge
}

TEST_CASE("the layout: hemisphere distances, unit normals pointing away, no duplicate at the pole, symmetry about the axis") {
  for (int angle : {5, 10, 30, 45, 90}) {
    lightwave_layout_settings<double> settings;
    settings.light_position = {0.3, 2.0, -0.4};
    settings.light_direction = glm::normalize(glm::dvec3(0.2, -1.0, 0.1));
    settings.angle_deg = angle;
    settings.per_ray = 5;
    settings.max_distance = 3.0;
    std::vector<lightwave_vpl<double>> vpls;
    lightwave_layout(settings, std::back_inserter(vpls));
    REQUIRE(vpls.size() == static_cast<std::size_t>(lightwave_vpl_count(angle, 5)));
    const int rays = lightwave_ray_count(angle);
    for (std::size_t i = 0; i < vpls.size(); ++i) {
      const int h = static_cast<int>(i) / rays;
      const glm::dvec3 offset = vpls[i].position - settings.light_position;
      REQUIRE(glm::length(offset) == doctest::Approx(3.0 * (1.0 - std::pow(0.5, h + 1))).epsilon(1e-9));
      REQUIRE(glm::length(vpls[i].normal) == doctest::Approx(1.0).epsilon(1e-9));
      REQUIRE(glm::dot(vpls[i].normal, glm::normalize(offset)) == doctest::Approx(1.0).epsilon(1e-9));  // away from the light
      REQUIRE(glm::dot(vpls[i].normal, settings.light_direction) >= -1e-9);  // in the lit hemisphere
      REQUIRE(vpls[i].attenuation == lightwave_attenuation<double>(h));
    }
    // No two VPLs at the same place (one axis ray, distinct azimuths on every ring).
    double closest = 1e30;
    for (std::size_t i = 0; i < static_cast<std::size_t>(rays); ++i)
      for (std::size_t j = i + 1; j < static_cast<std::size_t>(rays); ++j)
        closest = std::min(closest, glm::length(vpls[i].position - vpls[j].position));
    CAPTURE(angle);
    CHECK(closest > 1e-3);
    // Rotating the layout by `angle` about the light's axis maps it onto itself.
    const glm::dvec3 w = settings.light_direction;
    const double a = angle * 3.14159265358979323846 / 180.0;
    const auto rotate = [&](const glm::dvec3& p) {  // Rodrigues' formula about w
      return p * std::cos(a) + glm::cross(w, p) * std::sin(a) + w * glm::dot(w, p) * (1.0 - std::cos(a));
    };
    for (std::size_t i = 0; i < static_cast<std::size_t>(rays); ++i) {
      const glm::dvec3 rotated = rotate(vpls[i].position - settings.light_position) + settings.light_position;
      double nearest = 1e30;
      for (std::size_t j = 0; j < static_cast<std::size_t>(rays); ++j) nearest = std::min(nearest, glm::length(vpls[j].position - rotated));
      REQUIRE(nearest < 1e-8);  // the polynomial sin/cos is exact to 2e-9
    }
    // The outermost ring is horizontal: 90 degrees from the axis.
    CHECK(glm::dot(vpls[static_cast<std::size_t>(rays - 1)].normal, w) == doctest::Approx(0.0).scale(1.0).epsilon(1e-9));
  }
  CHECK(static_cast<bool>(validate_lightwave_layout(7, 5)));   // 7 does not divide 90
  CHECK(static_cast<bool>(validate_lightwave_layout(5, 0)));
  CHECK(static_cast<bool>(validate_lightwave_layout(0, 5)));
  CHECK_FALSE(static_cast<bool>(validate_lightwave_layout(5, 5)));
}

TEST_CASE("Eq. 4.5: one VPL facing a vertex, and the normalised sum over identical VPLs") {
  const glm::dvec3 x(0.0), n(0, 1, 0), albedo(0.5, 0.25, 1.0), eye(0, 5, 5);
  const lightwave_vpl<double> above{glm::dvec3(0, 2, 0), glm::dvec3(0, -1, 0), 0.2};
  lightwave_shading_settings<double> diffuse_only;
  diffuse_only.specular_strength = 0.0;
  // obj = 1, light = lobe(1) = 1, strength 0.8.
  const glm::dvec3 e = lightwave_vpl_contribution(x, n, albedo, eye, above, diffuse_only);
  CHECK(e.x == doctest::Approx(0.4));
  CHECK(e.z == doctest::Approx(0.8));
  // No distance falloff: twice as far, the same.
  const lightwave_vpl<double> farther{glm::dvec3(0, 4, 0), glm::dvec3(0, -1, 0), 0.2};
  CHECK(lightwave_vpl_contribution(x, n, albedo, eye, farther, diffuse_only).x == doctest::Approx(0.4));
  // Below the surface: nothing, specular included.
  const lightwave_vpl<double> below{glm::dvec3(0, -2, 0), glm::dvec3(0, 1, 0), 0.05};
  CHECK(lightwave_vpl_contribution(x, n, albedo, eye, below, lightwave_shading_settings<double>{}) == glm::dvec3(0.0));
  // Attenuation over 100% (sixth hemisphere) is clamped: no negative light.
  const lightwave_vpl<double> sixth{glm::dvec3(0, 2, 0), glm::dvec3(0, -1, 0), 1.6};
  CHECK(lightwave_vpl_contribution(x, n, albedo, eye, sixth, diffuse_only) == glm::dvec3(0.0));
  // The specular term: the mirror direction of a VPL straight above is straight up; an eye there
  // sees specular_strength * 1^k.
  lightwave_shading_settings<double> shiny;
  shiny.specular_strength = 0.3;
  const glm::dvec3 s = lightwave_vpl_contribution(x, n, glm::dvec3(0.0), glm::dvec3(0, 10, 0), above, shiny);
  CHECK(s.y == doctest::Approx(0.3));
  // Normalised sum: N copies of one VPL give that VPL's term.
  const auto fetch = [&](int) { return above; };
  CHECK(lightwave_vertex_indirect(x, n, albedo, eye, fetch, 37, diffuse_only).y == doctest::Approx(e.y));
}

TEST_CASE("integrated shadows: the lookups step from map a's coordinate to map b's, the first half in a") {
  const glm::dvec3 a(0.1, 0.2, 0.3), b(0.5, 0.6, 0.7);
  const int steps = 10;
  CHECK(glm::dvec3(lightwave_integrated_step(a, b, 0, steps)) == a);
  CHECK(glm::dvec3(lightwave_integrated_step(a, b, steps + 1, steps)) == b);
  int in_a = 0;
  for (int lookup = 1; lookup <= steps; ++lookup) {
    const glm::dvec4 step = lightwave_integrated_step(a, b, lookup, steps);
    in_a += step.w == 0.0;
    CHECK(step.x == doctest::Approx(0.1 + 0.4 * lookup / 11.0));
  }
  CHECK(in_a == 5);  // "the first 5 coordinates use i = 1, the last 5 i = 2"
  CHECK(lightwave_integrated_step(a, b, 0, steps).w == 0.0);
  CHECK(lightwave_integrated_step(a, b, 11, steps).w == 1.0);
}

TEST_CASE("Eq. 5.2, Alg. 1 as fixed, and Eq. 5.3 reproduce the thesis's numbers") {
  // Eq. 5.2 with m = 1.1: direct * 0.5 * shadow + direct * 0.6.
  CHECK(lightwave_faked_indirect(glm::dvec3(1.0), 0.0, 1.1).x == doctest::Approx(0.6));
  CHECK(lightwave_faked_indirect(glm::dvec3(2.0), 1.0, 1.5).y == doctest::Approx(3.0));
  // Alg. 1: identical images are 100% similar; 200 against 100 is about 50% different.
  const std::uint8_t a[] = {200, 0, 255}, b[] = {100, 0, 255};
  CHECK(lightwave_similarity(a, a, 3) == 100.0);
  const std::uint8_t x[] = {200}, y[] = {100};
  CHECK(lightwave_similarity(x, y, 1) == doctest::Approx(100.0 * 101.0 / 201.0));
  CHECK(lightwave_similarity(x, y, 1) == lightwave_similarity(y, x, 1));
  CHECK(lightwave_similarity(a, b, 3) == doctest::Approx(100.0 * (101.0 / 201.0 + 1.0 + 1.0) / 3.0));
  // Table 5.10: rank = (FPS - 55) / (100 - % similar), printed to 4 decimals.
  struct row {
    double fps, similar, rank;
  };
  const row table[] = {{681, 91.847, 76.7816}, {161, 98.563, 73.7648}, {87, 99.475, 60.9524}, {106, 98.853, 44.4638},
                       {681, 84.426, 40.1952}, {84, 97.956, 14.1879},  {78, 91.591, 2.7352},  {133, 99.483, 150.8704}};
  for (const row& r : table) {
    CAPTURE(r.rank);
    CHECK(lightwave_rank(r.fps - 55.0, r.similar) == doctest::Approx(r.rank).epsilon(1e-5));
  }
}
