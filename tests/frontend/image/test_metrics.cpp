// Image metrics (frontend/image/metrics.hpp) on known pairs: identical images, a constant offset,
// a shifted copy, a scaled copy; finite results for extreme pixels; the errors for bad input.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "frontend/core/error.hpp"
#include "frontend/image/metrics.hpp"

using namespace vplkit;

namespace {

image shifted_gradient(int width, int height, float offset = 0.0f, int shift = 0) {
  image ramp(width, height);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const int sx = std::clamp(x - shift, 0, width - 1);
      const float v = 0.1f + 0.8f * static_cast<float>(sx) / static_cast<float>(width - 1);
      ramp.at(x, y) = glm::vec4(v + offset, 0.5f * v + offset, 0.25f + offset, 1.0f);
    }
  return ramp;
}

}  // namespace

TEST_CASE("identical images: RMSE 0, PSNR infinite, SSIM 1, 100% similar, no leak") {
  const image a = shifted_gradient(40, 30);
  image mask = a;
  for (auto& p : mask.texels) p = glm::vec4(1.0f);
  const image_metrics m = compare_images(a, a, &mask);
  CHECK(m.rmse == 0.0);
  CHECK(m.relative_mse == 0.0);
  CHECK(std::isinf(m.psnr));
  CHECK(m.ssim == doctest::Approx(1.0).epsilon(1e-12));
  CHECK(m.similarity == 100.0);
  CHECK(*m.leak_rmse == 0.0);
  CHECK(m.leak_pixels == 40u * 30u);
}

TEST_CASE("a constant offset c: RMSE = c, PSNR = 20 log10(peak / c), relative MSE closed form, SSIM below 1") {
  const float c = 0.05f;
  const image reference = shifted_gradient(40, 30), offset = shifted_gradient(40, 30, c);
  const image_metrics m = compare_images(offset, reference);
  CHECK(m.rmse == doctest::Approx(c).epsilon(1e-5));
  double peak = 0.0, relative = 0.0;
  for (const glm::vec4& p : reference.texels)
    for (int k = 0; k < 3; ++k) {
      peak = std::max(peak, static_cast<double>(p[k]));
      relative += static_cast<double>(c) * c / (static_cast<double>(p[k]) * p[k] + 0.01);
    }
  CHECK(m.psnr == doctest::Approx(20.0 * std::log10(peak / c)).epsilon(1e-4));
  CHECK(m.relative_mse == doctest::Approx(relative / (3.0 * 40 * 30)).epsilon(1e-4));
  CHECK(m.ssim < 1.0);
  CHECK(m.ssim > 0.9);  // the structure is the same; only the mean moved
  CHECK(m.similarity < 100.0);
}

TEST_CASE("a shifted copy: RMSE from the shifted ramp, SSIM and similarity drop, the leak error counts only the mask") {
  const int width = 64, shift = 3;
  const image reference = shifted_gradient(width, 16), shifted = shifted_gradient(width, 16, 0.0f, shift);
  const image_metrics m = compare_images(shifted, reference);
  // Per row: x >= shift differ by 0.8 shift / (w - 1) in red, half that in green, 0 in blue;
  // x < shift by 0.8 x / (w - 1), half in green.
  const double step = 0.8 / (width - 1);
  double squared = 0.0;
  for (int x = 0; x < width; ++x) {
    const double d = x >= shift ? step * shift : step * x;
    squared += d * d + 0.25 * d * d;
  }
  CHECK(m.rmse == doctest::Approx(std::sqrt(squared / (3.0 * width))).epsilon(1e-4));
  CHECK(m.ssim < 1.0);
  // A mask of the left half only: the leak error is that half's.
  image mask = reference;
  for (int y = 0; y < 16; ++y)
    for (int x = 0; x < width; ++x) mask.at(x, y) = glm::vec4(x < width / 2 ? 1.0f : 0.0f);
  const image_metrics masked = compare_images(shifted, reference, &mask);
  double left = 0.0;
  for (int x = 0; x < width / 2; ++x) {
    const double d = x >= shift ? step * shift : step * x;
    left += d * d + 0.25 * d * d;
  }
  CHECK(*masked.leak_rmse == doctest::Approx(std::sqrt(left / (3.0 * width / 2))).epsilon(1e-4));
  CHECK(masked.leak_pixels == static_cast<std::size_t>(16 * width / 2));
}

TEST_CASE("metrics of finite pixels are finite, FLT_MAX included; non-finite pixels are refused") {
  const float big = std::numeric_limits<float>::max();
  image extreme(2, 1);
  extreme.texels = {glm::vec4(big, -big, 3e38f, 1.0f), glm::vec4(-3e38f, big, 0.0f, 1.0f)};
  const image zero(2, 1);
  const image_metrics m = compare_images(extreme, zero, &extreme);
  for (const double value : {m.rmse, m.relative_mse, m.ssim, m.similarity, *m.leak_rmse})
    CHECK(std::isfinite(value));
  CHECK(m.rmse > 1e38);
  CHECK_FALSE(m.psnr_defined);  // a black reference has no peak to be relative to
  const image_metrics reversed = compare_images(zero, extreme);
  CHECK(reversed.psnr_defined);
  CHECK(std::isfinite(reversed.psnr));
  CHECK(reversed.relative.defined);  // the reference's channels sum to FLT_MAX > 0
  CHECK(std::isfinite(reversed.relative.rmse));
  CHECK(std::isfinite(reversed.relative.bias));
  const std::vector<std::uint8_t> colours = false_colour_error(extreme, zero, 0.0f);
  CHECK(colours[0] == 255);  // the largest difference is full red
  image with_nan = zero;
  with_nan.texels[1].g = std::nanf("");
  CHECK_THROWS_WITH_AS(compare_images(with_nan, zero), "compare: the image: pixel (1, 0) (from the top left) is not finite", vplkit::error);
  CHECK_THROWS_WITH_AS(false_colour_error(zero, with_nan, 0.0f), "error image: the reference: pixel (1, 0) (from the top left) is not finite", vplkit::error);
}

TEST_CASE("relative RMSE and bias: a scaled copy, an offset, and a mask that selects the pixels they count") {
  // Reference: value 1 on the left half, 3 on the right half (every channel).
  const int w = 8, h = 4;
  image reference(w, h);
  image mask = reference;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      reference.at(x, y) = glm::vec4(x < w / 2 ? 1.0f : 3.0f);
      mask.at(x, y) = glm::vec4(x < w / 2 ? 1.0f : 0.2f);  // 0.2 <= 0.5: not counted
    }
  // 1.1 x the reference: bias exactly +10 %, RMSE = 0.1 sqrt(mean b^2) / mean b = 0.1 sqrt(5) / 2.
  image scaled = reference;
  for (glm::vec4& p : scaled.texels) p *= 1.1f;
  const relative_error whole = relative_error_of(scaled, reference);
  CHECK(whole.pixels == static_cast<std::size_t>(w * h));
  CHECK(whole.bias == doctest::Approx(0.1).epsilon(1e-5));
  CHECK(whole.rmse == doctest::Approx(0.1 * std::sqrt(5.0) / 2.0).epsilon(1e-5));
  // Over the mask (the left half, reference 1): bias and RMSE both 10 %.
  const relative_error left = relative_error_of(scaled, reference, &mask);
  CHECK(left.pixels == static_cast<std::size_t>(w * h / 2));
  CHECK(left.bias == doctest::Approx(0.1).epsilon(1e-5));
  CHECK(left.rmse == doctest::Approx(0.1).epsilon(1e-5));
  // An offset of -0.5 on the left half only: bias -0.5 / 1 over the mask, -0.25 / 2 over all.
  image darker = reference;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w / 2; ++x) darker.at(x, y) -= glm::vec4(0.5f);
  CHECK(relative_error_of(darker, reference, &mask).bias == doctest::Approx(-0.5));
  CHECK(relative_error_of(darker, reference).bias == doctest::Approx(-0.125));
  CHECK(relative_error_of(darker, reference).rmse == doctest::Approx(std::sqrt(0.125) / 2.0));
  // compare_images reports both, the masked one only with a mask.
  const image_metrics m = compare_images(darker, reference, &mask);
  REQUIRE(m.masked);
  CHECK(m.masked->bias == doctest::Approx(-0.5));
  CHECK(m.relative.bias == doctest::Approx(-0.125));
  CHECK_FALSE(compare_images(darker, reference).masked);
  CHECK(whole.defined);
  CHECK(whole.why_undefined.empty());
  // An empty mask or a black reference: no relative number exists (not 0, which would read as a
  // perfect match), and the reason says which.
  image nothing = mask;
  for (glm::vec4& p : nothing.texels) p = glm::vec4(0.0f);
  const relative_error none = relative_error_of(scaled, reference, &nothing);
  CHECK(none.pixels == 0);
  CHECK_FALSE(none.defined);
  CHECK(none.why_undefined == "the mask marks no pixel (luminance > 0.5)");
  const relative_error black = relative_error_of(scaled, nothing);
  CHECK_FALSE(black.defined);
  CHECK(black.pixels == static_cast<std::size_t>(w * h));
  CHECK(black.why_undefined == "the reference's mean is 0 (black) over the 32 pixels: there is no level to be relative to");
  CHECK_THROWS_AS(relative_error_of(scaled, image(2, 2)), vplkit::error);
}

TEST_CASE("against a black reference the relative numbers and PSNR are undefined, with the reason; the others stay numbers") {
  // A configuration that draws something where the reference is black: relative RMSE and bias
  // once read 0 here, a perfect score a sweep would rank best.
  image reference(6, 4), lit(6, 4), black(6, 4), half(6, 4), mask(6, 4);
  for (glm::vec4& p : lit.texels) p = glm::vec4(0.5f, 0.25f, 0.125f, 1.0f);
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 6; ++x) {
      half.at(x, y) = glm::vec4(x < 3 ? 0.0f : 1.0f);  // black on the left only
      mask.at(x, y) = glm::vec4(x < 3 ? 1.0f : 0.0f);
    }
  const image_metrics m = compare_images(lit, reference);
  CHECK_FALSE(m.relative.defined);
  CHECK(m.relative.why_undefined.find("the reference's mean is 0 (black) over the 24 pixels") == 0);
  CHECK_FALSE(m.psnr_defined);
  CHECK(m.why_psnr_undefined.find("the reference is black") == 0);
  CHECK(m.rmse > 0.0);  // absolute numbers still compare
  CHECK(std::isfinite(m.relative_mse));
  CHECK(m.similarity < 100.0);
  // Black against black: equal images, PSNR infinite as for any equal pair, relative still undefined.
  const image_metrics same = compare_images(black, reference);
  CHECK(std::isinf(same.psnr));
  CHECK(same.psnr_defined);
  CHECK_FALSE(same.relative.defined);
  // A reference black only inside the mask: the whole image's numbers exist, the masked ones do not.
  const image_metrics masked = compare_images(lit, half, &mask);
  CHECK(masked.relative.defined);
  REQUIRE(masked.masked);
  CHECK_FALSE(masked.masked->defined);
  CHECK(masked.masked->why_undefined.find("over the 12 masked pixels") != std::string::npos);
}
