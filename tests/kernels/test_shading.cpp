// The final composition (vplkit/shading.hpp): a white surface under irradiance pi returns 1, the
// result is linear in each irradiance, the visibility scales only the direct term, and the float
// instantiation matches a double evaluation.
#include <doctest/doctest.h>

#include <random>

#include <vplkit/shading.hpp>

using namespace vplkit;

TEST_CASE("diffuse_radiance: albedo / pi times the irradiance, closed forms") {
  const glm::dvec3 white(1.0);
  const glm::dvec3 pi_irradiance(3.14159265358979323846);
  CHECK(diffuse_radiance(white, pi_irradiance, 1.0, glm::dvec3(0.0)).x == doctest::Approx(1.0).epsilon(1e-15));
  CHECK(diffuse_radiance(white, glm::dvec3(0.0), 1.0, pi_irradiance).y == doctest::Approx(1.0).epsilon(1e-15));
  // Fully shadowed: only the indirect light is left; half visible: half the direct term.
  CHECK(diffuse_radiance(white, pi_irradiance, 0.0, glm::dvec3(0.0)) == glm::dvec3(0.0));
  CHECK(diffuse_radiance(white, pi_irradiance, 0.5, pi_irradiance).z == doctest::Approx(1.5).epsilon(1e-15));
  // Each channel is the albedo's: a red surface reflects no green.
  CHECK(diffuse_radiance(glm::dvec3(0.6, 0.0, 0.0), pi_irradiance, 1.0, pi_irradiance) == glm::dvec3(1.2, 0.0, 0.0));
}

TEST_CASE("diffuse_radiance: linear in the irradiances, float within a few ulp of double") {
  std::mt19937 random(12);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f), level(0.0f, 50.0f);
  for (int i = 0; i < 1000; ++i) {
    const glm::vec3 albedo(unit(random), unit(random), unit(random));
    const glm::vec3 direct(level(random), level(random), level(random)), indirect(level(random), level(random), level(random));
    const float visibility = unit(random);
    const glm::vec3 sum = diffuse_radiance(albedo, direct, visibility, indirect);
    const glm::vec3 parts = diffuse_radiance(albedo, direct, visibility, glm::vec3(0.0f)) + diffuse_radiance(albedo, glm::vec3(0.0f), 0.0f, indirect);
    const glm::dvec3 exact = diffuse_radiance(glm::dvec3(albedo), glm::dvec3(direct), double{visibility}, glm::dvec3(indirect));
    for (int c = 0; c < 3; ++c) {
      CHECK(sum[c] == doctest::Approx(parts[c]).epsilon(1e-6));
      CHECK(sum[c] == doctest::Approx(exact[c]).epsilon(1e-6));
    }
  }
}
