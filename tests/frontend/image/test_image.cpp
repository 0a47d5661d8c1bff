// The image type and its conversions (frontend/image/image.hpp): row order, Rec. 709 luminance,
// the sRGB transfer function and its inverse, the display exposure, the luminance difference.
#include <doctest/doctest.h>

#include <cmath>

#include "frontend/core/error.hpp"
#include "frontend/image/image.hpp"

using namespace vplkit;

TEST_CASE("texel (x, y) is at y * width + x with y = 0 at the bottom, as GL reads render targets") {
  image grid(3, 2);
  grid.at(2, 1) = glm::vec4(7.0f);
  CHECK(grid.texels[1 * 3 + 2] == glm::vec4(7.0f));
  CHECK(grid.at(glm::ivec2(2, 1)) == glm::vec4(7.0f));
  CHECK(grid.same_size(image(3, 2)));
  CHECK_FALSE(grid.same_size(image(2, 3)));
  CHECK(validate_image_size(max_image_side, 1).empty());
  CHECK(validate_image_size(max_image_side + 1, 1).find("image size must be in [1, 16384]") == 0);
  CHECK_FALSE(validate_image_size(0, 5).empty());
}

TEST_CASE("luminance: Rec. 709 weights summing to 1, in float and double") {
  CHECK(luminance(glm::vec3(1.0f)) == doctest::Approx(1.0f));
  CHECK(luminance(glm::dvec3(0.0, 1.0, 0.0)) == 0.7152);
  // In double, the luminance of FLT_MAX pixels is finite.
  CHECK(std::isfinite(luminance(glm::dvec3(3.4e38, 3.4e38, 3.4e38))));
}

TEST_CASE("sRGB: the piecewise curve, clamped, NaN to 0, and its inverse round-trips every 8-bit code") {
  CHECK(linear_to_srgb(0.0031308f) == doctest::Approx(12.92f * 0.0031308f));
  CHECK(linear_to_srgb(0.5f) == doctest::Approx(1.055 * std::pow(0.5, 1.0 / 2.4) - 0.055));
  CHECK(linear_to_srgb(2.0f) == doctest::Approx(1.0f));  // clamped to 1 first
  CHECK(linear_to_srgb8(2.0f) == 255);
  CHECK(linear_to_srgb(-1.0f) == 0.0f);
  CHECK(linear_to_srgb(std::nanf("")) == 0.0f);
  for (int code = 0; code < 256; ++code) CHECK(linear_to_srgb8(srgb_to_linear(static_cast<float>(code) / 255.0f)) == code);
}

TEST_CASE("to_srgb8 scales by the exposure, clamps, forces alpha opaque and writes rows top-down") {
  image two_rows(1, 2);
  two_rows.at(0, 0) = glm::vec4(0.0f, 0.5f, 1.0f, 0.0f);          // bottom
  two_rows.at(0, 1) = glm::vec4(0.0031308f, 2.0f, -1.0f, 0.0f);   // top
  const std::vector<std::uint8_t> encoded = to_srgb8(two_rows);
  CHECK(encoded[0] == std::lround(255.0 * 12.92 * 0.0031308));  // the top row first
  CHECK(encoded[1] == 255);
  CHECK(encoded[2] == 0);
  CHECK(encoded[3] == 255);
  CHECK(encoded[5] == std::lround(255.0 * (1.055 * std::pow(0.5, 1.0 / 2.4) - 0.055)));
  CHECK(to_srgb8(two_rows, 2.0f)[5] == 255);  // 0.5 x 2 = 1
}

TEST_CASE("percentile_exposure maps the 99th percentile luminance to 0.8; a black image gets 1") {
  image ramp(100, 1);
  for (int x = 0; x < 100; ++x) ramp.at(x, 0) = glm::vec4(static_cast<float>(x + 1));
  // 100 values 1..100: rank (100 - 1) * 99 / 100 = 98, the value 99.
  CHECK(percentile_exposure(ramp) == doctest::Approx(0.8f / 99.0f));
  CHECK(percentile_exposure(image(4, 4)) == 1.0f);
}

TEST_CASE("luminance_difference is |L(a) - L(b)| x scale as opaque grey; sizes must match") {
  image a(2, 1, glm::vec4(1.0f)), b(2, 1, glm::vec4(0.25f));
  const image difference = luminance_difference(a, b, 2.0f);
  CHECK(difference.at(1, 0) == glm::vec4(1.5f, 1.5f, 1.5f, 1.0f));
  CHECK_THROWS_WITH_AS(luminance_difference(a, image(1, 2), 1.0f), doctest::Contains("different sizes (2x1 and 1x2)"), vplkit::error);
  image factor(1, 1, glm::vec4(0.3f, 0.9f, 0.9f, 0.0f));
  CHECK(red_as_grey(factor).at(0, 0) == glm::vec4(0.3f, 0.3f, 0.3f, 1.0f));
}
