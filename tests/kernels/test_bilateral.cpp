// The bilateral post filter (include/vplkit/bilateral.hpp): a constant image is kept, and no
// light crosses a depth edge or a crease.
#include <doctest/doctest.h>

#include <array>
#include <cmath>
#include <cstring>
#include <initializer_list>
#include <vector>

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

TEST_CASE("bilateral_filter_axis_quad equals bilateral_filter_axis at each of the 2 x 2 pixels, bit for bit, on both axes") {
  // Random taps on a 13 x 11 buffer: two depths, tilted normals, holes (depth 0), and texels near
  // every edge, so the taps' bounds and the holes are exercised; the pixels' own depths and normals
  // differ from their texel's (the G-buffer is full resolution).
  const glm::ivec2 size(13, 11);
  std::vector<bilateral_tap<float>> taps;
  unsigned state = 12345u;
  const auto next = [&state]() {
    state = state * 1664525u + 1013904223u;
    return static_cast<float>(state >> 8) / 16777216.0f;
  };
  for (int i = 0; i < size.x * size.y; ++i) {
    const float depth = next() < 0.1f ? 0.0f : (next() < 0.5f ? -4.0f : -4.4f) * (1.0f + 0.01f * next());
    taps.push_back({glm::vec3(next(), next(), next()), depth, glm::normalize(glm::vec3(next() - 0.5f, next() - 0.5f, 2.0f))});
  }
  const auto fetch = [&](glm::ivec2 t) { return taps[static_cast<std::size_t>(t.y * size.x + t.x)]; };
  bilateral_settings<float> settings;
  settings.kernel_size = 9;
  settings.normal_power = 5;  // odd: the power's bits 0 and 2
  int compared = 0, lit = 0;
  for (int axis = 0; axis < 2; ++axis)
    for (int y = 0; y < size.y; ++y)
      for (int x = 0; x < size.x; ++x) {
        std::array<float, 4> depth;
        std::array<glm::vec3, 4> normal;
        for (std::size_t s = 0; s < 4; ++s) {
          depth[s] = s == 3 && x == 2 ? 0.0f : -4.0f - 0.5f * next();  // one pixel with nothing there
          normal[s] = glm::normalize(glm::vec3(next() - 0.5f, next() - 0.5f, 2.0f));
        }
        const glm::ivec2 texel(x, y);
        const std::array<glm::vec3, 4> quad = bilateral_filter_axis_quad(texel, depth, normal, fetch, size, axis, settings);
        for (int s = 0; s < 4; ++s) {
          const glm::vec2 centre = bilateral_quad_centre<float>(texel, s);
          CHECK(glm::ivec2(glm::floor(centre)) == texel);
          CHECK(centre == (glm::vec2(2 * texel + glm::ivec2(s & 1, s >> 1)) + 0.5f) / 2.0f);  // the post pass's centre
          const glm::vec3 single =
              bilateral_filter_axis(centre, depth[static_cast<std::size_t>(s)], normal[static_cast<std::size_t>(s)], fetch, size, axis, settings);
          CAPTURE(axis);
          CAPTURE(x);
          CAPTURE(y);
          CAPTURE(s);
          CHECK(std::memcmp(&quad[static_cast<std::size_t>(s)], &single, sizeof single) == 0);
          ++compared;
          lit += single.x > 0.0f ? 1 : 0;
        }
      }
  CHECK(compared == 2 * 4 * 13 * 11);
  CHECK(lit > compared / 2);  // most pixels have weighted taps: the comparison is of sums, not of zeros
}

TEST_CASE("integer_power covers every normal_power the settings allow, and its loop's bits match the setting's range") {
  CHECK(bilateral_max_normal_power < (1 << integer_power_bits));
  // The top power and one with every bit set: each bit's factor is taken.
  CHECK(integer_power(0.99, bilateral_max_normal_power) == doctest::Approx(std::pow(0.99, bilateral_max_normal_power)).epsilon(1e-14));
  CHECK(integer_power(0.99, 63) == doctest::Approx(std::pow(0.99, 63)).epsilon(1e-14));
  CHECK(integer_power(2.0, 63) == std::ldexp(1.0, 63));
}
