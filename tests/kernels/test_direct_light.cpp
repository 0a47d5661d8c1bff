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
