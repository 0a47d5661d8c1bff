// The bilateral post filter (include/vplkit/bilateral.hpp): a constant image is kept, and no
// light crosses a depth edge or a crease.
#include <doctest/doctest.h>

#include <cmath>
#include <initializer_list>

#include <vplkit/bilateral.hpp>

using namespace vplkit;

TEST_CASE("bilateral filter keeps a constant image and does not blur across a depth edge") {
  const glm::ivec2 size(32, 32);
  bilateral_settings<double> settings;
  // Constant irradiance on one plane: unchanged.
  const auto constant = [](glm::ivec2) { return bilateral_tap<double>{glm::dvec3(0.7, 0.2, 0.1), -5.0, glm::dvec3(0, 0, 1)}; };
  const glm::dvec3 kept = bilateral_filter(glm::dvec2(10.5, 20.5), -5.0, glm::dvec3(0, 0, 1), constant, size, settings);
  CHECK(kept.x == doctest::Approx(0.7).epsilon(1e-12));
  CHECK(kept.y == doctest::Approx(0.2).epsilon(1e-12));
  // Left half near (depth -5, irradiance 1), right half far (depth -10, irradiance 0): a pixel
  // next to the edge on the near side keeps its value; a plain blur would mix in about 0.4.
  const auto step = [](glm::ivec2 t) {
    return t.x < 16 ? bilateral_tap<double>{glm::dvec3(1.0), -5.0, glm::dvec3(0, 0, 1)}
                    : bilateral_tap<double>{glm::dvec3(0.0), -10.0, glm::dvec3(0, 0, 1)};
  };
  CHECK(bilateral_filter(glm::dvec2(15.5, 16.5), -5.0, glm::dvec3(0, 0, 1), step, size, settings).x > 0.999);
  CHECK(bilateral_filter(glm::dvec2(16.5, 16.5), -10.0, glm::dvec3(0, 0, 1), step, size, settings).x < 0.001);
  // The same across a crease (normals at 90 degrees, equal depth).
  const auto crease = [](glm::ivec2 t) {
    return t.x < 16 ? bilateral_tap<double>{glm::dvec3(1.0), -5.0, glm::dvec3(0, 0, 1)}
                    : bilateral_tap<double>{glm::dvec3(0.0), -5.0, glm::dvec3(1, 0, 0)};
  };
  CHECK(bilateral_filter(glm::dvec2(15.5, 16.5), -5.0, glm::dvec3(0, 0, 1), crease, size, settings).x == doctest::Approx(1.0));
  // Separable: each axis alone keeps the constant too.
  CHECK(bilateral_filter_axis(glm::dvec2(3.5, 3.5), -5.0, glm::dvec3(0, 0, 1), constant, size, 0, settings).z ==
        doctest::Approx(0.1).epsilon(1e-12));
  // Weights: spatial Gaussian (exp(-1/2) at one sigma), relative depth, normal power.
  CHECK(bilateral_weight(glm::dvec2(4.0, 0.0), -5.0, -5.0, glm::dvec3(0, 0, 1), glm::dvec3(0, 0, 1), settings) ==
        doctest::Approx(std::exp(-0.5)).epsilon(1e-12));
  CHECK(bilateral_weight(glm::dvec2(0.0), -10.0, -10.5, glm::dvec3(0, 0, 1), glm::dvec3(0, 0, 1), settings) ==
        doctest::Approx(std::exp(-0.5)).epsilon(1e-12));  // 5% of the depth = one depth sigma
  const glm::dvec3 tilted(std::sin(0.5), 0.0, std::cos(0.5));
  CHECK(bilateral_weight(glm::dvec2(0.0), -5.0, -5.0, glm::dvec3(0, 0, 1), tilted, settings) ==
        doctest::Approx(std::pow(std::cos(0.5), 8)).epsilon(1e-12));
}


TEST_CASE("integer_power (repeated squaring) equals std::pow for every power the settings allow") {
  for (int power = 0; power <= 64; ++power)
    for (double base : {0.0, 0.3, 0.9, 0.999, 1.0}) {
      CAPTURE(power);
      CAPTURE(base);
      CHECK(integer_power(base, power) == doctest::Approx(std::pow(base, power)).epsilon(1e-14));
      CHECK(double(integer_power(float(base), power)) == doctest::Approx(std::pow(double(float(base)), power)).epsilon(1e-5));
    }
  CHECK(integer_power(0.0, 0) == 1.0);  // k = 0: no normal weight, even for opposite normals
}

TEST_CASE("the one-exp weight equals the product of the two Gaussians and the normal power") {
  const bilateral_settings<double> settings;
  for (double depth_ratio : {1.0, 1.02, 1.1, 0.9}) {
    const glm::dvec2 offset(1.5, -2.5);
    const double centre_depth = -3.0, tap_depth = centre_depth * depth_ratio;
    const glm::dvec3 n(0, 0, 1), m = glm::normalize(glm::dvec3(0.2, 0, 1));
    const double relative = (tap_depth - centre_depth) / (settings.depth_sigma * centre_depth);
    const double expected = std::exp(-glm::dot(offset, offset) / (2.0 * settings.spatial_sigma * settings.spatial_sigma)) *
                            std::exp(-0.5 * relative * relative) * std::pow(glm::dot(n, m), settings.normal_power);
    CHECK(bilateral_weight(offset, centre_depth, tap_depth, n, m, settings) == doctest::Approx(expected).epsilon(1e-13));
  }
}
