// Properties of the Light Wave kernels (include/vplkit/lightwave.hpp), against the numbers the
// thesis prints ([LW], Tables 5.1, 5.2 and 5.10, Eq. 4.2, 4.8).
#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <vector>

#include <vplkit/lightwave.hpp>

#include "tests/closed_forms.hpp"

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

// ---- The flux energy: the cone layout, the flux a ray's patch carries, and the VPLs' light ----

namespace {

lightwave_cone_settings<double> cone_settings(int angle, int per_ray, double half_angle_deg) {
  lightwave_cone_settings<double> settings;
  settings.light_direction = glm::normalize(glm::dvec3(0.3, -1.0, 0.2));
  settings.angle_deg = angle;
  settings.per_ray = per_ray;
  settings.half_angle_deg = half_angle_deg;
  return settings;
}

using closed_forms::pi;

}  // namespace

TEST_CASE("the cone layout: unit directions inside the cone, patches that tile it exactly, equal within a ring") {
  for (int angle : {5, 10, 30, 90})
    for (int per_ray : {1, 3, 5})
      for (double half_angle : {10.0, 50.0, 83.0}) {
        const lightwave_cone_settings<double> settings = cone_settings(angle, per_ray, half_angle);
        const int count = lightwave_vpl_count(angle, per_ray), rays = lightwave_ray_count(angle);
        double total = 0.0, smallest_cos = 1.0;
        for (int index = 0; index < count; ++index) {
          const glm::dvec4 sample = lightwave_cone_sample(index, settings);
          const glm::dvec3 direction(sample);
          REQUIRE(glm::length(direction) == doctest::Approx(1.0).epsilon(1e-8));  // the polynomial sin/cos: 1e-9
          REQUIRE(sample.w > 0.0);
          smallest_cos = std::min(smallest_cos, glm::dot(direction, settings.light_direction));
          total += sample.w;
          // Every sample of a ring (not the axis) has the same solid angle: equal sectors split equally.
          if (index % rays > 0) REQUIRE(sample.w == doctest::Approx(lightwave_cone_sample((index / rays) * rays + 1 + ((index % rays) - 1) / (360 / angle) * (360 / angle), settings).w));
        }
        CAPTURE(angle);
        CAPTURE(per_ray);
        CAPTURE(half_angle);
        // The patches tile the cone: their solid angles sum to 2 pi (1 - cos half_angle) (the
        // polynomial cosine is exact to 1e-9).
        CHECK(total == doctest::Approx(2.0 * pi * (1.0 - std::cos(half_angle * pi / 180.0))).epsilon(1e-7));
        CHECK(smallest_cos >= std::cos(half_angle * pi / 180.0) - 1e-9);  // nothing outside the cone
      }
}

TEST_CASE("the cone layout: a sample lies in its ray's patch; one sample per ray sits at the patch's solid-angle median; symmetric about the axis") {
  const lightwave_cone_settings<double> settings = cone_settings(5, 5, 45.0);
  const int rays = lightwave_ray_count(5), rings = 18;
  const double band = 45.0 / (rings + 0.5);  // degrees
  for (int index = 0; index < lightwave_vpl_count(5, 5); ++index) {
    const int ray = index % rays, ring = ray == 0 ? 0 : (ray - 1) / 72 + 1;
    const double polar = std::acos(std::min(1.0, glm::dot(glm::dvec3(lightwave_cone_sample(index, settings)), settings.light_direction))) * 180.0 / pi;
    REQUIRE(polar >= (ring == 0 ? 0.0 : (ring - 0.5) * band) - 1e-6);
    REQUIRE(polar <= (ring + 0.5) * band + 1e-6);
  }
  // One sample per ray: at the median of its patch's solid angle (the mean of the cosines of its
  // polar bounds), for the axis's cap and for ring e's band.
  const lightwave_cone_settings<double> one = cone_settings(5, 1, 45.0);
  CHECK(glm::dot(glm::dvec3(lightwave_cone_sample(0, one)), one.light_direction) == doctest::Approx(0.5 * (1.0 + std::cos(0.5 * band * pi / 180.0))).epsilon(1e-9));
  for (int ring : {1, 9, 18}) {
    const double low = std::cos((ring - 0.5) * band * pi / 180.0), high = std::cos((ring + 0.5) * band * pi / 180.0);
    const glm::dvec3 direction(lightwave_cone_sample(1 + (ring - 1) * 72 + 7, one));
    CHECK(glm::dot(direction, one.light_direction) == doctest::Approx(0.5 * (low + high)).epsilon(1e-9));
  }
  // Rotating by the ray angle about the axis maps the layout onto itself (one sample per ray).
  const glm::dvec3 w = one.light_direction;
  const double a = 5.0 * pi / 180.0;
  for (int ray = 1; ray < rays; ++ray) {
    const glm::dvec3 p(lightwave_cone_sample(ray, one));
    const glm::dvec3 rotated = p * std::cos(a) + glm::cross(w, p) * std::sin(a) + w * glm::dot(w, p) * (1.0 - std::cos(a));
    double nearest = 1e30;
    for (int other = 1; other < rays; ++other) nearest = std::min(nearest, glm::length(glm::dvec3(lightwave_cone_sample(other, one)) - rotated));
    REQUIRE(nearest < 1e-8);
  }
}

TEST_CASE("the flux of a ray's patch: the spot's intensity, cone and solid angle times the albedo; nothing on a back face") {
  spot_light<double> light;
  light.direction = glm::dvec3(0, -1, 0);
  light.intensity = glm::dvec3(2.0, 1.0, 0.5);
  light.cos_inner = std::cos(30.0 * pi / 180.0);
  light.cos_outer = std::cos(50.0 * pi / 180.0);
  const glm::dvec3 albedo(0.5, 0.25, 1.0), up(0, 1, 0);
  const glm::dvec3 on_axis(0, -1, 0);
  CHECK(lightwave_ray_flux(light, on_axis, 0.01, albedo, up) == glm::dvec3(0.01, 0.0025, 0.005));
  CHECK(lightwave_ray_flux(light, on_axis, 0.01, albedo, -up) == glm::dvec3(0.0));  // the back of a surface
  const glm::dvec3 outside(std::sin(60.0 * pi / 180.0), -std::cos(60.0 * pi / 180.0), 0.0);
  CHECK(lightwave_ray_flux(light, outside, 0.01, albedo, up) == glm::dvec3(0.0));  // beyond the cone
  // Summed over the cone layout, the flux the spot sends: I * integral of the smoothstep cone over
  // the sphere = 2 pi I ((1 - cos_inner) + (cos_inner - cos_outer) / 2), times the albedo.
  lightwave_cone_settings<double> settings = cone_settings(5, 5, 50.0);
  settings.light_direction = light.direction;
  glm::dvec3 total(0.0);
  for (int index = 0; index < lightwave_vpl_count(5, 5); ++index) {
    const glm::dvec4 sample = lightwave_cone_sample(index, settings);
    total += lightwave_ray_flux(light, glm::dvec3(sample), sample.w, albedo, up);
  }
  const double exact = 2.0 * pi * ((1.0 - light.cos_inner) + 0.5 * (light.cos_inner - light.cos_outer));
  CHECK(total.x == doctest::Approx(exact * 2.0 * 0.5).epsilon(2e-3));
  CHECK(total.z == doctest::Approx(exact * 0.5 * 1.0).epsilon(2e-3));
}

TEST_CASE("a flux VPL's light: Eq. 3.2 / pi, clamped at its patch's radius; over a plane it faces it delivers its flux") {
  const lightwave_flux_vpl<double> vpl{glm::dvec3(0, 2, 0), glm::dvec3(0, -1, 0), glm::dvec3(3.0, 1.5, 0.0), 0.1};
  // Straight below at distance 2, facing it: flux / (pi d^2).
  const glm::dvec3 e = lightwave_bounce_irradiance(glm::dvec3(0.0), glm::dvec3(0, 1, 0), vpl, 0.01);
  CHECK(e.x == doctest::Approx(3.0 / (pi * 4.0)));
  CHECK(lightwave_bounce_weight(glm::dvec3(0.0), glm::dvec3(0, 1, 0), vpl, 0.01) == doctest::Approx(4.5 / (pi * 4.0)));
  // Twice as far: a quarter (a diffuse bounce's falloff, which Eq. 4.5 lacks).
  const lightwave_flux_vpl<double> farther{glm::dvec3(0, 4, 0), glm::dvec3(0, -1, 0), glm::dvec3(3.0, 1.5, 0.0), 0.1};
  CHECK(lightwave_bounce_irradiance(glm::dvec3(0.0), glm::dvec3(0, 1, 0), farther, 0.01).x == doctest::Approx(e.x / 4.0));
  // Nearer than its radius: clamped there (the disk the patch covers, not a point), and the
  // larger of radius and min_distance.
  const glm::dvec3 near_point(0, 1.95, 0);
  CHECK(lightwave_bounce_irradiance(near_point, glm::dvec3(0, 1, 0), vpl, 0.01).x == doctest::Approx(3.0 * 0.05 * 0.05 / (pi * 0.01 * 0.01)));
  CHECK(lightwave_bounce_irradiance(near_point, glm::dvec3(0, 1, 0), vpl, 0.2).x == doctest::Approx(3.0 * 0.05 * 0.05 / (pi * 0.04 * 0.04)));
  // Behind it, or a receiver turned away: nothing.
  CHECK(lightwave_bounce_irradiance(glm::dvec3(0, 3, 0), glm::dvec3(0, -1, 0), vpl, 0.01) == glm::dvec3(0.0));
  CHECK(lightwave_bounce_irradiance(glm::dvec3(0.0), glm::dvec3(0, -1, 0), vpl, 0.01) == glm::dvec3(0.0));
  // Energy: summed over a plane the VPL faces, irradiance times area is the flux it sends there:
  // out to radius R at height h, flux (1 - h^2 / (R^2 + h^2)) (a cosine lobe). Rings of the plane
  // at height 0 (the light is the same all around a ring), R = 200; the clamp does not act at h = 2.
  double caught = 0.0;
  for (double rho = 0.0005, step = 0.001; rho < 200.0; rho += step, step = rho < 20.0 ? 0.001 : 0.01)
    caught += lightwave_bounce_irradiance(glm::dvec3(rho, 0, 0), glm::dvec3(0, 1, 0), vpl, 0.01).x * 2.0 * pi * rho * step;
  CHECK(caught == doctest::Approx(3.0 * (1.0 - 4.0 / (200.0 * 200.0 + 4.0))).epsilon(1e-3));
  // Summed at a vertex: albedo / pi times the sum (diffuse_radiance).
  const auto fetch = [&](int index) { return index == 0 ? vpl : farther; };
  const glm::dvec3 radiance = lightwave_vertex_bounce(glm::dvec3(0.0), glm::dvec3(0, 1, 0), glm::dvec3(0.5), fetch, 2, irradiance_settings<double>{});
  CHECK(radiance.x == doctest::Approx(0.5 / pi * (e.x + e.x / 4.0)));
}

TEST_CASE("lightwave_bounce_sum in parts, each continuing the last one's sum, equals the sum in one loop to the bit") {
  // 300 float VPLs scattered over a floor and a wall, summed at points of the room: the sum over
  // all of them at once, and in parts of 1, 7, 64 and 299 (the pipeline's passes), the same floats.
  std::mt19937 random(11);
  std::uniform_real_distribution<float> uniform(-1.0f, 1.0f);
  std::vector<lightwave_flux_vpl<float>> vpls;
  for (int i = 0; i < 300; ++i) {
    const bool floor = i % 3 != 0;
    vpls.push_back({floor ? glm::vec3(uniform(random), 0.0f, uniform(random)) : glm::vec3(-1.0f, uniform(random) + 1.0f, uniform(random)),
                    floor ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0), glm::vec3(0.002f, 0.001f, 0.0005f) * (uniform(random) + 1.5f), 0.03f});
  }
  const int count = static_cast<int>(vpls.size());
  for (int point = 0; point < 20; ++point) {
    const glm::vec3 x(0.9f * uniform(random), 0.5f * uniform(random) + 0.6f, uniform(random));
    const glm::vec3 n = glm::normalize(glm::vec3(uniform(random), uniform(random), uniform(random)));
    const glm::vec3 whole = lightwave_bounce_sum(x, n, [&](int index) { return vpls[static_cast<std::size_t>(index)]; }, count, glm::vec3(0.0f), 0.01f);
    REQUIRE(whole.x + whole.y + whole.z > 0.0f);
    for (const int part : {1, 7, 64, 299}) {
      CAPTURE(part);
      glm::vec3 sum(0.0f);
      for (int first = 0; first < count; first += part)
        sum = lightwave_bounce_sum(x, n, [&](int index) { return vpls[static_cast<std::size_t>(first + index)]; }, std::min(part, count - first), sum, 0.01f);
      CHECK(sum == whole);
    }
    // lightwave_vertex_bounce is the sum from zero, as radiance.
    const glm::vec3 albedo(0.3f, 0.5f, 0.7f);
    CHECK(lightwave_vertex_bounce(x, n, albedo, [&](int index) { return vpls[static_cast<std::size_t>(index)]; }, count, irradiance_settings<float>{0.01f}) ==
          diffuse_radiance(albedo, glm::vec3(0.0f), 0.0f, whole));
  }
}

TEST_CASE("lightwave_bounce_sums: each of its receivers' sums equals lightwave_bounce_sum's for that receiver to the bit") {
  // Four receivers facing four ways, from four partial sums, over 200 VPLs of a floor and a wall;
  // a receiver's sum must not depend on its slot (a slot mix-up or a shared term fails).
  std::mt19937 random(23);
  std::uniform_real_distribution<float> uniform(-1.0f, 1.0f);
  std::vector<lightwave_flux_vpl<float>> vpls;
  for (int i = 0; i < 200; ++i) {
    const bool floor = i % 2 == 0;
    vpls.push_back({floor ? glm::vec3(uniform(random), 0.0f, uniform(random)) : glm::vec3(-1.0f, uniform(random) + 1.0f, uniform(random)),
                    floor ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0), glm::vec3(0.002f, 0.001f, 0.0005f) * (uniform(random) + 1.5f), 0.03f});
  }
  const auto fetch = [&](int index) { return vpls[static_cast<std::size_t>(index)]; };
  static_assert(lightwave_sum_receivers == 4);
  for (int trial = 0; trial < 10; ++trial) {
    std::array<glm::vec3, 4> x, n, partial;
    for (std::size_t k = 0; k < 4; ++k) {
      x[k] = glm::vec3(0.9f * uniform(random), 0.5f * uniform(random) + 0.6f, uniform(random));
      n[k] = glm::normalize(glm::vec3(uniform(random), uniform(random), uniform(random)));
      partial[k] = glm::vec3(0.01f * static_cast<float>(k) * (uniform(random) + 1.0f));
    }
    const std::array<glm::vec3, 4> sums = lightwave_bounce_sums(x, n, fetch, 200, partial, 0.01f);
    for (std::size_t k = 0; k < 4; ++k) {
      CAPTURE(trial);
      CAPTURE(k);
      CHECK(sums[k] == lightwave_bounce_sum(x[k], n[k], fetch, 200, partial[k], 0.01f));
    }
    CHECK(sums[0] != sums[1]);
  }
}

TEST_CASE("a patch's radius: the disk of the area the patch covers on the surface") {
  // A patch of solid angle w met head-on at distance d covers w d^2: pi r^2 = w d^2.
  const double r = lightwave_patch_radius(0.01, 3.0, 1.0);
  CHECK(pi * r * r == doctest::Approx(0.01 * 9.0));
  // At 60 degrees off the normal, twice the area; at grazing, at most 16 times.
  CHECK(lightwave_patch_radius(0.01, 3.0, -0.5) == doctest::Approx(r * std::sqrt(2.0)));
  CHECK(lightwave_patch_radius(0.01, 3.0, 0.0) == doctest::Approx(r * 4.0));
}

TEST_CASE("the flux energy reproduces a one-bounce integral: a spot over a floor lighting a wall") {
  // The spot at height 2 looks straight down at a floor of albedo 0.6 (y = 0); a wall point at
  // x = 3, height 1, facing -x. The VPLs sit where the cone's rays meet the floor. Reference: the
  // floor's reflected light integrated on a fine grid, E = integral of (albedo / pi) E_floor(q)
  // cos cos / r^2 dA, with E_floor the spot's irradiance there.
  spot_light<double> light;
  light.position = glm::dvec3(0, 2, 0);
  light.direction = glm::dvec3(0, -1, 0);
  light.intensity = glm::dvec3(5.0);
  light.cos_inner = std::cos(25.0 * pi / 180.0);
  light.cos_outer = std::cos(40.0 * pi / 180.0);
  const double albedo = 0.6;
  const glm::dvec3 receiver(3, 1, 0), normal(-1, 0, 0);
  lightwave_cone_settings<double> settings = cone_settings(5, 5, 40.0);
  settings.light_direction = light.direction;
  double vpl_sum = 0.0;
  for (int index = 0; index < lightwave_vpl_count(5, 5); ++index) {
    const glm::dvec4 sample = lightwave_cone_sample(index, settings);
    const glm::dvec3 direction(sample);
    const double distance = 2.0 / -direction.y;
    const lightwave_flux_vpl<double> vpl{light.position + direction * distance, glm::dvec3(0, 1, 0),
                                         lightwave_ray_flux(light, direction, sample.w, glm::dvec3(albedo), glm::dvec3(0, 1, 0)),
                                         lightwave_patch_radius(sample.w, distance, -direction.y)};
    vpl_sum += lightwave_bounce_irradiance(receiver, normal, vpl, 0.01).x;
  }
  double integral = 0.0;
  const double step = 0.01, reach = 2.0 * std::tan(40.0 * pi / 180.0) + 0.01;
  for (double x = -reach; x < reach; x += step)
    for (double z = -reach; z < reach; z += step) {
      const glm::dvec3 q(x + step / 2, 0, z + step / 2);
      const double e_floor = spot_light_irradiance(q, glm::dvec3(0, 1, 0), light).x;
      const glm::dvec3 to_receiver = receiver - q;
      const double r2 = glm::dot(to_receiver, to_receiver), r = std::sqrt(r2);
      integral += albedo / pi * e_floor * (to_receiver.y / r) * std::max(0.0, -glm::dot(normal, to_receiver) / r) / r2 * step * step;
    }
  CHECK(vpl_sum == doctest::Approx(integral).epsilon(0.01));
}

TEST_CASE("lightwave_map_fade: 0 outside a map and on its border, 1 from the margin in, rising smoothly") {
  CHECK(lightwave_map_fade(glm::dvec4(0.5, 0.5, 0.5, 1.0), 0.05) == 1.0);
  CHECK(lightwave_map_fade(glm::dvec4(0.5, 0.5, 0.5, 0.0), 0.05) == 0.0);  // outside (lightwave_map_coordinate's w)
  CHECK(lightwave_map_fade(glm::dvec4(0.0, 0.5, 0.5, 1.0), 0.05) == 0.0);
  CHECK(lightwave_map_fade(glm::dvec4(0.5, 1.0, 0.5, 1.0), 0.05) == 0.0);
  CHECK(lightwave_map_fade(glm::dvec4(0.05, 0.5, 0.5, 1.0), 0.05) == 1.0);
  CHECK(lightwave_map_fade(glm::dvec4(0.5, 0.975, 0.5, 1.0), 0.05) == doctest::Approx(0.5));  // halfway into the margin
  double previous = 0.0;
  for (double x = 0.0; x <= 0.05; x += 0.001) {
    const double fade = lightwave_map_fade(glm::dvec4(x, 0.5, 0.5, 1.0), 0.05);
    CHECK(fade >= previous);
    previous = fade;
  }
}

TEST_CASE("lightwave_group_confidence: 1 for a group seen as a point, 1/2 where its angular diameter (4 RMS radii) is one radian, falling with its size") {
  const glm::dvec3 x(0.0), group(0, 0, 4);
  CHECK(lightwave_group_confidence(x, group, 0.0) == 1.0);
  CHECK(lightwave_group_confidence(x, group, 1.0) == doctest::Approx(0.5));  // diameter 4 at distance 4
  CHECK(lightwave_group_confidence(x, group, 0.2) == doctest::Approx(1.0 / (1.0 + 0.04)));
  CHECK(lightwave_group_confidence(x, group, 1.0) > lightwave_group_confidence(x, group, 3.0));
  CHECK(lightwave_group_confidence(x, glm::dvec3(0, 0, 8), 2.0) > lightwave_group_confidence(x, group, 2.0));  // farther: smaller
  CHECK(lightwave_group_confidence(group, group, 1.0) >= 0.0);  // at its centre: finite, about 0
  CHECK(lightwave_group_confidence(group, group, 1.0) < 1e-9);
}

TEST_CASE("lightwave_flux_vpl_faces: exactly where a flux VPL's light is positive") {
  std::uint32_t state = 12345u;
  const auto next = [&] {
    state = state * 1664525u + 1013904223u;
    return static_cast<double>(state >> 8) / 16777216.0 * 2.0 - 1.0;
  };
  int lit = 0;
  for (int i = 0; i < 20000; ++i) {
    const glm::dvec3 x(next(), next(), next()), p(next(), next(), next());
    const glm::dvec3 n = glm::normalize(glm::dvec3(next(), next(), next())), normal = glm::normalize(glm::dvec3(next(), next(), next()));
    const lightwave_flux_vpl<double> vpl{p, normal, glm::dvec3(0.3, 0.2, 0.1), 0.05};
    const bool faces = lightwave_flux_vpl_faces(x, n, p, normal);
    REQUIRE(faces == (lightwave_bounce_weight(x, n, vpl, 0.01) > 0.0));
    lit += faces;
  }
  CHECK(lit > 2000);  // a quarter of random pairs face each other
  CHECK(lit < 8000);
}

TEST_CASE("a point light's flux layout: the sphere's patches' solid angles sum to 4 pi, every direction once, both hemispheres alike") {
  for (int angle : {5, 10, 30, 90})
    for (int per_ray : {1, 3, 5}) {
      lightwave_cone_settings<double> settings = cone_settings(angle, per_ray, 17.0);  // the half-angle is not read
      const int count = lightwave_sphere_sample_count(angle, per_ray), half = lightwave_vpl_count(angle, per_ray);
      REQUIRE(count == 2 * half);
      double total = 0.0, upper = 0.0;
      glm::dvec3 mean(0.0);  // sum of direction * solid angle
      for (int index = 0; index < count; ++index) {
        const glm::dvec4 sample = lightwave_sphere_sample(index, settings);
        const glm::dvec3 direction(sample);
        REQUIRE(glm::length(direction) == doctest::Approx(1.0).epsilon(1e-8));
        REQUIRE(sample.w > 0.0);
        // The first half faces the axis, the second its opposite (the equator's patches touch it).
        const double side = glm::dot(direction, settings.light_direction);
        REQUIRE((index < half ? side : -side) >= -1e-9);
        // The second half mirrors the first: the same solid angles in the same order.
        if (index >= half) REQUIRE(sample.w == doctest::Approx(lightwave_sphere_sample(index - half, settings).w).epsilon(1e-12));
        total += sample.w;
        if (index < half) upper += sample.w;
        mean += direction * sample.w;
      }
      CAPTURE(angle);
      CAPTURE(per_ray);
      CHECK(total == doctest::Approx(4.0 * pi).epsilon(1e-8));
      CHECK(upper == doctest::Approx(2.0 * pi).epsilon(1e-8));
      // The hemispheres mirror each other's polar angles: the component along the axis cancels
      // (a layout that put both halves on one side would give 2 pi).
      CHECK(std::abs(glm::dot(mean, settings.light_direction)) < 1e-6);
    }
}

TEST_CASE("a point light's flux: the VPLs of the sphere carry 4 pi I times the albedo; nothing on a back face") {
  point_light<double> light;
  light.position = {0.1, 1.5, -0.2};
  light.intensity = glm::dvec3(2.0, 1.0, 0.5);
  const glm::dvec3 albedo(0.5, 0.25, 1.0);
  const glm::dvec3 down(0, -1, 0);
  CHECK(lightwave_ray_flux(light, down, 0.01, albedo, glm::dvec3(0, 1, 0)) == glm::dvec3(0.01, 0.0025, 0.005));
  CHECK(lightwave_ray_flux(light, down, 0.01, albedo, glm::dvec3(0, -1, 0)) == glm::dvec3(0.0));  // the back of a surface
  // Every direction lit, the same as a spot whose cone is open everywhere.
  spot_light<double> open;
  open.position = light.position;
  open.direction = down;
  open.intensity = light.intensity;
  open.cos_inner = -1.0;
  open.cos_outer = -1.0 - 1e-9;
  const glm::dvec3 sideways = glm::normalize(glm::dvec3(1.0, 0.2, 0.0)), facing_it(-1.0, 0.0, 0.0);
  CHECK(lightwave_ray_flux(light, sideways, 0.02, albedo, facing_it) == lightwave_ray_flux(open, sideways, 0.02, albedo, facing_it));
  // Summed over the sphere with every surface facing its ray: 4 pi I albedo.
  const lightwave_cone_settings<double> settings = cone_settings(5, 5, 90.0);
  glm::dvec3 total(0.0);
  for (int index = 0; index < lightwave_sphere_sample_count(5, 5); ++index) {
    const glm::dvec4 sample = lightwave_sphere_sample(index, settings);
    total += lightwave_ray_flux(light, glm::dvec3(sample), sample.w, albedo, -glm::dvec3(sample));
  }
  CHECK(total.x == doctest::Approx(4.0 * pi * 2.0 * 0.5).epsilon(1e-8));
  CHECK(total.y == doctest::Approx(4.0 * pi * 1.0 * 0.25).epsilon(1e-8));
  CHECK(total.z == doctest::Approx(4.0 * pi * 0.5 * 1.0).epsilon(1e-8));
}

TEST_CASE("a point light's thesis layout: the stacked hemispheres on both sides, the equator's ring once, the first half the spot's layout") {
  for (int angle : {5, 10, 30, 45, 90}) {
    lightwave_layout_settings<double> settings;
    settings.light_position = {0.3, 2.0, -0.4};
    settings.light_direction = glm::normalize(glm::dvec3(0.2, -1.0, 0.1));
    settings.angle_deg = angle;
    settings.per_ray = 3;
    settings.max_distance = 3.0;
    const int rays = lightwave_ray_count(angle), count = lightwave_sphere_vpl_count(angle, 3);
    REQUIRE(count == 3 * (2 * rays - 360 / angle));
    std::vector<lightwave_vpl<double>> vpls;
    for (int index = 0; index < count; ++index) vpls.push_back(lightwave_sphere_layout_vpl(index, settings));
    int below = 0;
    for (int index = 0; index < count; ++index) {
      const lightwave_vpl<double>& vpl = vpls[static_cast<std::size_t>(index)];
      if (index < 3 * rays) {
        const lightwave_vpl<double> spot = lightwave_layout_vpl(index, settings);
        REQUIRE(vpl.position == spot.position);
        REQUIRE(vpl.attenuation == spot.attenuation);
      }
      const glm::dvec3 offset = vpl.position - settings.light_position;
      REQUIRE(glm::dot(vpl.normal, glm::normalize(offset)) == doctest::Approx(1.0).epsilon(1e-9));  // away from the light
      below += glm::dot(vpl.normal, settings.light_direction) < -1e-6;
    }
    CAPTURE(angle);
    // The second hemisphere: every ray strictly below the equator, as many as above it.
    CHECK(below == 3 * (rays - 360 / angle));
    // Each hemisphere's VPLs (same distance, same attenuation) at distinct places: none twice on the equator.
    double closest = 1e30;
    for (std::size_t i = 0; i < vpls.size(); ++i)
      for (std::size_t j = i + 1; j < vpls.size(); ++j)
        if (vpls[i].attenuation == vpls[j].attenuation) closest = std::min(closest, glm::length(vpls[i].position - vpls[j].position));
    CHECK(closest > 1e-3);
  }
}

TEST_CASE("a sun's flux layout: the samples tile the window, each cell holding per_ray of equal area; the flux is E x area x albedo, nothing on a back face") {
  for (int angle : {5, 10, 30, 90})
    for (int per_ray : {1, 3, 5}) {
      CAPTURE(angle);
      CAPTURE(per_ray);
      const int side = lightwave_parallel_side(angle);
      // The least square grid with a cell per ray of the cone layout: the same VPL count.
      REQUIRE(side * side >= lightwave_ray_count(angle));
      REQUIRE((side - 1) * (side - 1) < lightwave_ray_count(angle));
      const int count = lightwave_parallel_sample_count(angle, per_ray);
      REQUIRE(count == per_ray * side * side);
      double total = 0.0;
      glm::dvec2 mean(0.0);
      std::vector<int> per_cell(static_cast<std::size_t>(side * side), 0);
      for (int index = 0; index < count; ++index) {
        const glm::dvec3 sample = lightwave_parallel_sample<double>(index, angle, per_ray);
        REQUIRE(sample.x > -1.0);
        REQUIRE(sample.x < 1.0);
        REQUIRE(sample.y > -1.0);
        REQUIRE(sample.y < 1.0);
        REQUIRE(sample.z == doctest::Approx(4.0 / count).epsilon(1e-12));
        // Sample index k * cells + cell lies in that cell (row-major from the window's corner).
        const int cell = index % (side * side);
        const int column = static_cast<int>(std::floor((sample.x + 1.0) / 2.0 * side)), row = static_cast<int>(std::floor((sample.y + 1.0) / 2.0 * side));
        REQUIRE(row * side + column == cell);
        ++per_cell[static_cast<std::size_t>(cell)];
        total += sample.z;
        mean += glm::dvec2(sample) * sample.z;
      }
      CHECK(total == doctest::Approx(4.0).epsilon(1e-10));
      CHECK(std::all_of(per_cell.begin(), per_cell.end(), [&](int n) { return n == per_ray; }));
      // Stratified in each cell: the samples' centroid is near the window's centre.
      CHECK(glm::length(mean / total) < 1.0 / side);
    }
  directional_light<double> sun;
  sun.direction = glm::normalize(glm::dvec3(0.2, -1.0, 0.1));
  sun.irradiance = glm::dvec3(2.0, 1.0, 0.5);
  const glm::dvec3 albedo(0.5, 0.25, 1.0);
  CHECK(lightwave_ray_flux(sun, sun.direction, 0.01, albedo, glm::dvec3(0, 1, 0)) == glm::dvec3(0.01, 0.0025, 0.005));
  CHECK(lightwave_ray_flux(sun, sun.direction, 0.01, albedo, glm::dvec3(0, -1, 0)) == glm::dvec3(0.0));
}

TEST_CASE("lightwave_stratum_point: u stratified, v the golden-ratio lattice, both inside the unit square") {
  for (int per_ray : {1, 5, 16}) {
    std::vector<double> vs;
    for (int s = 0; s < per_ray; ++s) {
      const glm::dvec2 p = lightwave_stratum_point<double>(s, per_ray);
      CAPTURE(per_ray);
      CAPTURE(s);
      CHECK(p.x == doctest::Approx((s + 0.5) / per_ray));
      CHECK(p.y >= 0.0);
      CHECK(p.y < 1.0);
      vs.push_back(p.y);
    }
    // A rank-1 lattice with the golden ratio: any two of the first n points are more than 0.38 / n
    // apart in v (the golden ratio is the worst approximable number: n times the smallest gap stays
    // near 1 / sqrt(5) or above), so no two samples of a patch land together.
    std::sort(vs.begin(), vs.end());
    for (std::size_t k = 1; k < vs.size(); ++k) CHECK(vs[k] - vs[k - 1] > 0.38 / per_ray);
  }
  CHECK(lightwave_stratum_point<double>(1, 5).y == doctest::Approx(0.118033988749894848));
}
