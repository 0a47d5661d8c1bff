// Properties of Eq. 3.2 (include/vplkit/irradiance.hpp) and of the spot light term
// (include/vplkit/direct_light.hpp).
#include <doctest/doctest.h>

#include <cmath>
#include <random>

#include <glm/glm.hpp>

#include <vplkit/direct_light.hpp>
#include <vplkit/irradiance.hpp>
#include "tests/kernels/random_vectors.hpp"

using vplkit::irradiance_settings;
using vplkit::pixel_light_irradiance;

namespace {

template <typename T>
glm::vec<3, T> random_point(std::mt19937& random) {
  std::uniform_real_distribution<T> uniform(-2, 2);
  return {uniform(random), uniform(random), uniform(random)};
}

}  // namespace

TEST_CASE("Eq. 3.2 is symmetric under swapping the pixel light and the receiver") {
  // E(x, n; xp, np) = max(0, <np, x - xp>) max(0, <n, xp - x>) / r^4 is unchanged by the swap,
  // and the implementation computes it with exactly negated vectors, so the two agree bitwise.
  std::mt19937 random(1);
  const glm::vec3 flux(1.0f, 0.5f, 0.25f);
  for (int i = 0; i < 10000; ++i) {
    const glm::vec3 x = random_point<float>(random), xp = random_point<float>(random);
    const glm::vec3 n = vplkit::testing::random_unit_vector<float>(random), np = vplkit::testing::random_unit_vector<float>(random);
    const glm::vec3 forward = pixel_light_irradiance(x, n, xp, np, flux);
    const glm::vec3 swapped = pixel_light_irradiance(xp, np, x, n, flux);
    REQUIRE(forward == swapped);
  }
}

TEST_CASE("Eq. 3.2 is zero when the receiver is behind the pixel light or faces away") {
  const glm::dvec3 flux(1.0);
  const glm::dvec3 xp(0, 0, 0), np(0, 0, 1);
  // Receiver behind the light's surface.
  CHECK(pixel_light_irradiance(glm::dvec3(0.3, 0.1, -1.0), glm::dvec3(0, 0, 1), xp, np, flux) == glm::dvec3(0));
  // Receiver in front, but facing away from the light.
  CHECK(pixel_light_irradiance(glm::dvec3(0.3, 0.1, 1.0), glm::dvec3(0, 0, 1), xp, np, flux) == glm::dvec3(0));
  // Exactly tangent to either surface.
  CHECK(pixel_light_irradiance(glm::dvec3(1, 0, 0), glm::dvec3(-1, 0, 0), xp, np, flux) == glm::dvec3(0));
  // Facing each other: positive.
  CHECK(pixel_light_irradiance(glm::dvec3(0.3, 0.1, 1.0), glm::dvec3(0, 0, -1), xp, np, flux).x > 0.0);
}

TEST_CASE("Eq. 3.2 equals flux * <np, d> <n, -d> / |d|^4, so it falls as 1/r^2 along a fixed direction") {
  std::mt19937 random(2);
  const glm::dvec3 flux(2.0, 1.0, 0.5);
  for (int i = 0; i < 2000; ++i) {
    const glm::dvec3 xp = random_point<double>(random);
    const glm::dvec3 direction = vplkit::testing::random_unit_vector<double>(random);
    // Normals that see each other: the light's within 90 degrees of d, the receiver's of -d.
    glm::dvec3 np = vplkit::testing::random_unit_vector<double>(random), n = vplkit::testing::random_unit_vector<double>(random);
    if (glm::dot(np, direction) < 0) np = -np;
    if (glm::dot(n, direction) > 0) n = -n;
    const double r = 0.5 + i * 1e-3;
    const glm::dvec3 d = direction * r;
    const glm::dvec3 e = pixel_light_irradiance(xp + d, n, xp, np, flux);
    const double closed_form = glm::dot(np, d) * glm::dot(n, -d) / std::pow(glm::dot(d, d), 2.0);
    REQUIRE(e.x == doctest::Approx(flux.x * closed_form).epsilon(1e-12));
    // Doubling the distance along the same direction: the r^2 from the unnormalised dot products
    // against the r^4 below leaves 1/r^2, so a quarter.
    const glm::dvec3 e2 = pixel_light_irradiance(xp + 2.0 * d, n, xp, np, flux);
    REQUIRE(e2.y == doctest::Approx(e.y / 4.0).epsilon(1e-12));
  }
}

TEST_CASE("Eq. 3.2 clamps the distance at min_distance and is continuous there") {
  const irradiance_settings<double> settings{0.1};
  const glm::dvec3 flux(1.0), xp(0.0), np(0, 0, 1), n(0, 0, -1);
  // Face to face along z at distance r: unclamped E = 1 / r^2; clamped: r^2 / min^4.
  const auto e = [&](double r) { return pixel_light_irradiance(glm::dvec3(0, 0, r), n, xp, np, flux, settings).x; };
  CHECK(e(0.2) == doctest::Approx(1.0 / 0.04).epsilon(1e-12));
  CHECK(e(0.05) == doctest::Approx(0.05 * 0.05 / 1e-4).epsilon(1e-12));
  CHECK(e(0.1 - 1e-9) == doctest::Approx(e(0.1 + 1e-9)).epsilon(1e-6));
  CHECK(static_cast<bool>(vplkit::validate(irradiance_settings<float>{0.0f})));
  CHECK(static_cast<bool>(vplkit::validate(irradiance_settings<float>{-1.0f})));
  CHECK_FALSE(static_cast<bool>(vplkit::validate(irradiance_settings<float>{})));
}

TEST_CASE("Eq. 3.2 is finite for coincident points, zero vectors, huge and tiny distances") {
  const glm::vec3 flux(1.0f), n(0, 0, 1);
  const glm::vec3 zero(0.0f);
  const auto finite = [](const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); };
  CHECK(pixel_light_irradiance(zero, n, zero, -n, flux) == zero);                        // coincident
  CHECK(pixel_light_irradiance(glm::vec3(0, 0, 1), zero, zero, zero, flux) == zero);      // zero normals
  CHECK(finite(pixel_light_irradiance(glm::vec3(0, 0, 1e-30f), -n, zero, n, flux)));      // tiny distance
  CHECK(finite(pixel_light_irradiance(glm::vec3(0, 0, 1e18f), -n, zero, n, flux)));       // d^4 overflows float
  CHECK(finite(pixel_light_irradiance(glm::vec3(1e30f, 0, 1e30f), -n, zero, n, flux)));   // d^2 overflows float
}

TEST_CASE("Eq. 3.2 in float agrees with double to float precision") {
  std::mt19937 random(3);
  for (int i = 0; i < 10000; ++i) {
    const glm::dvec3 x = random_point<double>(random), xp = random_point<double>(random);
    const glm::dvec3 n = vplkit::testing::random_unit_vector<double>(random), np = vplkit::testing::random_unit_vector<double>(random);
    const double e_double = pixel_light_irradiance(x, n, xp, np, glm::dvec3(1.0)).x;
    const float e_float = pixel_light_irradiance(glm::vec3(x), glm::vec3(n), glm::vec3(xp), glm::vec3(np), glm::vec3(1.0f)).x;
    // The dot products cancel for near-tangent configurations, so compare against the scale
    // 1 / r^2 of the term rather than the term itself.
    const double scale = 1.0 / std::max(glm::dot(x - xp, x - xp), 1e-4);
    REQUIRE(std::fabs(e_float - e_double) <= 1e-5 * scale);
  }
}

TEST_CASE("spot_light_irradiance: I / r^2 on the axis, cone falloff, zero behind the receiver") {
  vplkit::spot_light<double> light;
  light.position = {0, 2, 0};
  light.direction = {0, -1, 0};
  light.intensity = glm::dvec3(3.0);
  light.cos_inner = std::cos(0.5);
  light.cos_outer = std::cos(0.7);
  REQUIRE_FALSE(static_cast<bool>(vplkit::validate(light)));
  const glm::dvec3 up(0, 1, 0);
  // On the axis, facing the light at distance 2: E = I / 4.
  CHECK(vplkit::spot_light_irradiance(glm::dvec3(0), up, light).x == doctest::Approx(0.75).epsilon(1e-14));
  // Inside the inner cone (angle 0.3 rad), tilted receiver: E = I cos(theta) / r^2.
  const double angle = 0.3, height = 2.0;
  const glm::dvec3 x(height * std::tan(angle), 0.0, 0.0);
  const double r2 = height * height + x.x * x.x;
  CHECK(vplkit::spot_light_irradiance(x, up, light).x == doctest::Approx(3.0 * std::cos(angle) / r2).epsilon(1e-12));
  // Outside the outer cone: nothing. Half-way through the falloff: smoothstep(0.5) = 0.5.
  CHECK(vplkit::spot_light_irradiance(glm::dvec3(2.0 * std::tan(0.75), 0, 0), up, light).x == 0.0);
  const double mid_cos = 0.5 * (light.cos_inner + light.cos_outer);
  const double mid_angle = std::acos(mid_cos);
  const glm::dvec3 x_mid(height * std::tan(mid_angle), 0, 0);
  const double r2_mid = height * height + x_mid.x * x_mid.x;
  CHECK(vplkit::spot_light_irradiance(x_mid, up, light).x == doctest::Approx(0.5 * 3.0 * mid_cos / r2_mid).epsilon(1e-9));
  // Receiver facing away.
  CHECK(vplkit::spot_light_irradiance(glm::dvec3(0), -up, light).x == 0.0);
  // Coincident with the light: finite (the distance clamp).
  CHECK(std::isfinite(vplkit::spot_light_irradiance(light.position, up, light).x));
  light.cos_inner = light.cos_outer;
  CHECK(static_cast<bool>(vplkit::validate(light)));
}
