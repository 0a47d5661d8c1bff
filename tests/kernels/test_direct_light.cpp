// The primary lights (include/vplkit/direct_light.hpp): the flux of a spot light's RSM texels
// covers the solid angle of the frustum.
#include <doctest/doctest.h>

#include <cmath>
#include <initializer_list>

#include <glm/gtc/matrix_transform.hpp>

#include <vplkit/direct_light.hpp>

#include "tests/closed_forms.hpp"

using namespace vplkit;

TEST_CASE("RSM flux: the texels of a spot light's RSM cover the frustum's solid angle") {
  // A square frustum of half-angle a subtends 4 asin(sin^2 a); the texel solid angles must add
  // up to it (a midpoint rule of the exact cos^3 density).
  for (double half_angle : {0.3, 0.7, 1.2}) {
    const double t = std::tan(half_angle);
    const int size = 256;
    double total = 0.0;
    for (int y = 0; y < size; ++y)
      for (int x = 0; x < size; ++x) {
        const glm::dvec2 ndc((x + 0.5) / size * 2 - 1, (y + 0.5) / size * 2 - 1);
        total += perspective_texel_solid_angle(ndc, t, glm::ivec2(size));
      }
    const double exact = 4.0 * std::asin(std::sin(half_angle) * std::sin(half_angle));
    CAPTURE(half_angle);
    CHECK(total == doctest::Approx(exact).epsilon(1e-4));
  }
  // A texel flux is albedo * I * cone * solid angle, and nothing for a surface facing away.
  spot_light<double> light;
  light.position = {0, 2, 0};
  light.intensity = glm::dvec3(5.0);
  const glm::dvec3 albedo(0.5), below(0, 0, 0);
  const double omega = perspective_texel_solid_angle(glm::dvec2(0.0), 1.0, glm::ivec2(64));
  CHECK(spot_light_texel_flux(albedo, below, glm::dvec3(0, 1, 0), light, glm::dvec2(0.0), 1.0, glm::ivec2(64)).x ==
        doctest::Approx(0.5 * 5.0 * omega));
  CHECK(spot_light_texel_flux(albedo, below, glm::dvec3(0, -1, 0), light, glm::dvec2(0.0), 1.0, glm::ivec2(64)).x == 0.0);
  directional_light<double> sun;
  sun.irradiance = glm::dvec3(2.0);
  CHECK(directional_light_texel_flux(albedo, glm::dvec3(0, 1, 0), sun, 0.01).y == doctest::Approx(0.01));
  CHECK(directional_light_texel_flux(albedo, glm::dvec3(0, -1, 0), sun, 0.01).y == 0.0);
  CHECK(directional_light_irradiance(glm::dvec3(0, 1, 0), sun).z == doctest::Approx(2.0));
}

TEST_CASE("point light: the inverse-square law and cosine, the spot without its cone, a cube RSM covering the sphere") {
  point_light<double> bulb;
  bulb.position = {0.3, 2.0, -0.4};
  bulb.intensity = {4.0, 2.0, 1.0};
  // E = I cos / d^2 at a receiver 2 below, tilted by 60 degrees towards it.
  const glm::dvec3 x(0.3, 0.0, -0.4), tilted(std::sin(glm::radians(60.0)), std::cos(glm::radians(60.0)), 0.0);
  CHECK(point_light_irradiance(x, glm::dvec3(0, 1, 0), bulb).x == doctest::Approx(4.0 / 4.0));
  CHECK(point_light_irradiance(x, tilted, bulb).y == doctest::Approx(2.0 * 0.5 / 4.0));
  CHECK(point_light_irradiance(x, glm::dvec3(0, -1, 0), bulb).z == 0.0);
  // A spot whose cone is open everywhere (cos_outer below -1) is the point light, for any receiver.
  spot_light<double> open_spot;
  open_spot.position = bulb.position;
  open_spot.intensity = bulb.intensity;
  open_spot.cos_inner = -1.5;
  open_spot.cos_outer = -2.0;
  for (const glm::dvec3& at : {glm::dvec3(1, 5, 2), glm::dvec3(-3, 0, 0.5), glm::dvec3(0.3, 2.005, -0.4)}) {
    const glm::dvec3 n = glm::normalize(bulb.position - at + glm::dvec3(0.2, -0.1, 0.3));
    CAPTURE(at.x);
    CHECK(point_light_irradiance(at, n, bulb).x == doctest::Approx(spot_light_irradiance(at, n, open_spot).x).epsilon(1e-12));
  }
  // The six 90-degree faces of a cube RSM cover the sphere: their texel solid angles add up to
  // 4 pi, and a texel's flux is albedo * I * its solid angle (0 facing away).
  const int size = 128;
  double face = 0.0;
  for (int y = 0; y < size; ++y)
    for (int x2 = 0; x2 < size; ++x2)
      face += perspective_texel_solid_angle(glm::dvec2((x2 + 0.5) / size * 2 - 1, (y + 0.5) / size * 2 - 1), 1.0, glm::ivec2(size));
  CHECK(6.0 * face == doctest::Approx(4.0 * 3.14159265358979).epsilon(1e-4));
  const glm::dvec2 ndc(0.25, -0.5);
  const double omega = perspective_texel_solid_angle(ndc, 1.0, glm::ivec2(size));
  const glm::dvec3 below = bulb.position - glm::dvec3(0, 1, 0);
  CHECK(point_light_texel_flux(glm::dvec3(0.5), below, glm::dvec3(0, 1, 0), bulb, ndc, glm::ivec2(size)).x == doctest::Approx(0.5 * 4.0 * omega));
  CHECK(point_light_texel_flux(glm::dvec3(0.5), below, glm::dvec3(0, -1, 0), bulb, ndc, glm::ivec2(size)).x == 0.0);
}

TEST_CASE("direction_to_light_at: the unit direction to the light and the squared distance, clamped near the light") {
  double distance_squared = -1.0;
  const glm::dvec3 x(1, 2, 3), far_light(4, 6, 3);  // 3-4-5 triangle: distance 5
  const glm::dvec3 direction = direction_to_light_at(x, far_light, 0.1, distance_squared);
  CHECK(distance_squared == doctest::Approx(25.0));
  CHECK(direction.x == doctest::Approx(0.6));
  CHECK(direction.y == doctest::Approx(0.8));
  CHECK(direction.z == doctest::Approx(0.0));
  // Closer than min_distance: the distance is held at min_distance, so the direction shrinks
  // with it instead of being renormalised (the irradiance stays bounded and continuous).
  const glm::dvec3 near_light = x + glm::dvec3(0, 0.05, 0);
  const glm::dvec3 near_direction = direction_to_light_at(x, near_light, 0.1, distance_squared);
  CHECK(distance_squared == doctest::Approx(0.01));
  CHECK(near_direction.y == doctest::Approx(0.5));
}
