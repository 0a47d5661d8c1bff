// Image metrics (frontend/image_metrics.hpp) on known pairs: identical images, a constant offset,
// a shifted copy; PFM round trips; the errors for bad input.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>

#include "frontend/error.hpp"
#include "frontend/image_io.hpp"
#include "frontend/image_metrics.hpp"

namespace fs = std::filesystem;
using namespace vplkit;

namespace {

float_image gradient(int width, int height, float offset = 0.0f, int shift = 0) {
  float_image image{width, height, std::vector<glm::vec3>(static_cast<std::size_t>(width) * static_cast<std::size_t>(height))};
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const int sx = std::clamp(x - shift, 0, width - 1);
      const float v = 0.1f + 0.8f * static_cast<float>(sx) / static_cast<float>(width - 1);
      image.pixels[static_cast<std::size_t>(y * width + x)] = glm::vec3(v + offset, 0.5f * v + offset, 0.25f + offset);
    }
  return image;
}

}  // namespace

TEST_CASE("identical images: RMSE 0, PSNR infinite, SSIM 1, 100% similar, no leak") {
  const float_image a = gradient(40, 30);
  float_image mask = a;
  for (auto& p : mask.pixels) p = glm::vec3(1.0f);
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
  const float_image reference = gradient(40, 30), offset = gradient(40, 30, c);
  const image_metrics m = compare_images(offset, reference);
  CHECK(m.rmse == doctest::Approx(c).epsilon(1e-5));
  double peak = 0.0, relative = 0.0;
  for (const glm::vec3& p : reference.pixels)
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
  const float_image reference = gradient(width, 16), shifted = gradient(width, 16, 0.0f, shift);
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
  float_image mask = reference;
  for (int y = 0; y < 16; ++y)
    for (int x = 0; x < width; ++x) mask.pixels[static_cast<std::size_t>(y * width + x)] = glm::vec3(x < width / 2 ? 1.0f : 0.0f);
  const image_metrics masked = compare_images(shifted, reference, &mask);
  double left = 0.0;
  for (int x = 0; x < width / 2; ++x) {
    const double d = x >= shift ? step * shift : step * x;
    left += d * d + 0.25 * d * d;
  }
  CHECK(*masked.leak_rmse == doctest::Approx(std::sqrt(left / (3.0 * width / 2))).epsilon(1e-4));
  CHECK(masked.leak_pixels == static_cast<std::size_t>(16 * width / 2));
}

TEST_CASE("PFM round trip, PNG reading, false colour, and errors naming the file") {
  const fs::path folder = fs::temp_directory_path() / ("vplkit-metrics-" + std::to_string(std::random_device{}()));
  const float_image a = gradient(17, 9);
  write_pfm(folder / "a.pfm", a);
  const float_image back = read_image_file(folder / "a.pfm");
  REQUIRE(back.width == 17);
  REQUIRE(back.height == 9);
  CHECK(back.pixels == a.pixels);
  // A PNG of the same image reads back within 8-bit sRGB quantisation.
  std::vector<float> rgba;
  for (int y = 8; y >= 0; --y)
    for (int x = 0; x < 17; ++x) {
      const glm::vec3 p = a.at(x, y);
      rgba.insert(rgba.end(), {p.r, p.g, p.b, 1.0f});
    }
  write_png(folder / "a.png", 17, 9, to_srgb8(rgba, 17, 9));
  CHECK(compare_images(read_image_file(folder / "a.png"), a).rmse < 0.005);
  const std::vector<std::uint8_t> colours = false_colour_error(gradient(17, 9, 0.1f), a, 0.1f);
  CHECK(colours[0] == 255);  // the full scale is red
  CHECK(colours[1] == 0);
  CHECK(false_colour_error(a, a, 1.0f)[2] == 255);  // no difference: blue
  // Errors.
  CHECK_THROWS_WITH_AS(read_image_file(folder / "none.pfm"), doctest::Contains("none.pfm: no such PFM image"), vplkit::error);
  std::ofstream(folder / "bad.pfm") << "P6\n1 1\n255\n";
  CHECK_THROWS_WITH_AS(read_image_file(folder / "bad.pfm"), doctest::Contains("not an RGB PFM file"), vplkit::error);
  std::ofstream(folder / "short.pfm") << "PF\n4 4\n-1.0\n1234";
  CHECK_THROWS_WITH_AS(read_image_file(folder / "short.pfm"), doctest::Contains("ends before its 4x4 pixels"), vplkit::error);
  std::ofstream(folder / "text.png") << "not a png";
  CHECK_THROWS_WITH_AS(read_image_file(folder / "text.png"), doctest::Contains("text.png: not a PNG file (no PNG signature)"), vplkit::error);
  // A PNG signature with a broken body reaches stb's PNG decoder, and only that one.
  std::ofstream(folder / "broken.png", std::ios::binary) << "\x89PNG\r\n\x1a\nbroken";
  CHECK_THROWS_WITH_AS(read_image_file(folder / "broken.png"), doctest::Contains("broken.png: not a readable PNG"), vplkit::error);
  CHECK_THROWS_WITH_AS(read_image_file(folder / "a.jpg"), doctest::Contains("unsupported image format '.jpg'"), vplkit::error);
  std::ofstream(folder / "a.exr") << "x";
  CHECK_THROWS_WITH_AS(read_image_file(folder / "a.exr"), doctest::Contains("unsupported image format '.exr'"), vplkit::error);
  CHECK_THROWS_WITH_AS(compare_images(gradient(4, 4), gradient(5, 4)), doctest::Contains("different sizes (4x4 and 5x4)"), vplkit::error);
  fs::remove_all(folder);
}

TEST_CASE("PFM decoding: exact size, finite pixels, header limits checked before allocating") {
  const auto pfm = [](const std::string& header, std::vector<float> values, const std::string& tail = "") {
    std::string bytes = header;
    bytes.append(reinterpret_cast<const char*>(values.data()), values.size() * sizeof(float));
    return bytes + tail;
  };
  const float_image ok = decode_image(pfm("PF\n2 1\n-1.0\n", {1, 2, 3, 4, 5, 6}), image_file_format::pfm, "ok.pfm");
  CHECK(ok.at(1, 0) == glm::vec3(4, 5, 6));
  CHECK_THROWS_WITH_AS(decode_image(pfm("PF\n1 1\n-1.0\n", {1, 2, 3}, "xy"), image_file_format::pfm, "t.pfm"),
                       "t.pfm: 2 bytes follow the 1x1 pixels of the PFM file", vplkit::error);
  CHECK_THROWS_WITH_AS(decode_image(pfm("PF\n1 2\n-1.0\n", {1, 2, 3, 4, 5, std::nanf("")}), image_file_format::pfm, "t.pfm"),
                       "t.pfm: pixel (0, 0) (from the top left) is NaN; vplkit compares finite images", vplkit::error);
  CHECK_THROWS_WITH_AS(decode_image(pfm("PF\n20000 20000\n-1.0\n", {0, 0, 0}), image_file_format::pfm, "t.pfm"),
                       doctest::Contains("t.pfm: the image claims 20000x20000 pixels, more than vplkit reads"), vplkit::error);
  image_read_limits tiny;
  tiny.max_pixels = 1;
  CHECK_THROWS_WITH_AS(decode_image(pfm("PF\n2 1\n-1.0\n", {1, 2, 3, 4, 5, 6}), image_file_format::pfm, "t.pfm", tiny),
                       doctest::Contains("the image claims 2x1 pixels"), vplkit::error);
  CHECK_THROWS_WITH_AS(decode_image(pfm("PF\n1 1\n1.0\n", {1, 2, 3}), image_file_format::pfm, "t.pfm"), doctest::Contains("big-endian"), vplkit::error);
  CHECK_THROWS_WITH_AS(decode_image(pfm("PF\n1 1\nnan\n", {1, 2, 3}), image_file_format::pfm, "t.pfm"), doctest::Contains("scale 'nan'"), vplkit::error);
  CHECK_THROWS_WITH_AS(decode_image(pfm("Pf\n1 1\n-1\n", {1}), image_file_format::pfm, "t.pfm"), doctest::Contains("greyscale"), vplkit::error);
}

TEST_CASE("metrics of finite pixels are finite, FLT_MAX included; non-finite pixels are refused") {
  const float big = std::numeric_limits<float>::max();
  const float_image extreme{2, 1, {glm::vec3(big, -big, 3e38f), glm::vec3(-3e38f, big, 0.0f)}};
  const float_image zero{2, 1, {glm::vec3(0.0f), glm::vec3(0.0f)}};
  const image_metrics m = compare_images(extreme, zero, &extreme);
  for (const double value : {m.rmse, m.relative_mse, m.psnr, m.ssim, m.similarity, *m.leak_rmse})
    CHECK(std::isfinite(value));
  CHECK(m.rmse > 1e38);
  const std::vector<std::uint8_t> colours = false_colour_error(extreme, zero, 0.0f);
  CHECK(colours[0] == 255);  // the largest difference is full red
  float_image with_nan = zero;
  with_nan.pixels[1].g = std::nanf("");
  CHECK_THROWS_WITH_AS(compare_images(with_nan, zero), "compare: the image: pixel (1, 0) is not finite", vplkit::error);
  CHECK_THROWS_WITH_AS(false_colour_error(zero, with_nan, 0.0f), "error image: the reference: pixel (1, 0) is not finite", vplkit::error);
}

TEST_CASE("relative RMSE and bias: a scaled copy, an offset, and a mask that selects the pixels they count") {
  // Reference: value 1 on the left half, 3 on the right half (every channel).
  const int w = 8, h = 4;
  float_image reference{w, h, std::vector<glm::vec3>(static_cast<std::size_t>(w * h))};
  float_image mask = reference;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      reference.pixels[static_cast<std::size_t>(y * w + x)] = glm::vec3(x < w / 2 ? 1.0f : 3.0f);
      mask.pixels[static_cast<std::size_t>(y * w + x)] = glm::vec3(x < w / 2 ? 1.0f : 0.2f);  // 0.2 <= 0.5: not counted
    }
  // 1.1 x the reference: bias exactly +10 %, RMSE = 0.1 sqrt(mean b^2) / mean b = 0.1 sqrt(5) / 2.
  float_image scaled = reference;
  for (glm::vec3& p : scaled.pixels) p *= 1.1f;
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
  float_image darker = reference;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w / 2; ++x) darker.pixels[static_cast<std::size_t>(y * w + x)] -= glm::vec3(0.5f);
  CHECK(relative_error_of(darker, reference, &mask).bias == doctest::Approx(-0.5));
  CHECK(relative_error_of(darker, reference).bias == doctest::Approx(-0.125));
  CHECK(relative_error_of(darker, reference).rmse == doctest::Approx(std::sqrt(0.125) / 2.0));
  // compare_images reports both, the masked one only with a mask.
  const image_metrics m = compare_images(darker, reference, &mask);
  REQUIRE(m.masked);
  CHECK(m.masked->bias == doctest::Approx(-0.5));
  CHECK(m.relative.bias == doctest::Approx(-0.125));
  CHECK_FALSE(compare_images(darker, reference).masked);
  // An empty mask or a black reference: no pixels, zeros rather than NaN.
  float_image nothing = mask;
  for (glm::vec3& p : nothing.pixels) p = glm::vec3(0.0f);
  const relative_error none = relative_error_of(scaled, reference, &nothing);
  CHECK(none.pixels == 0);
  CHECK(none.rmse == 0.0);
  CHECK(relative_error_of(scaled, nothing).rmse == 0.0);
  CHECK_THROWS_AS(relative_error_of(scaled, float_image{2, 2, std::vector<glm::vec3>(4)}), vplkit::error);
}
