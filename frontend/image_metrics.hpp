// Image comparison for the quality report (`vplkit compare`): float images (PFM) and PNG, and
// the metrics that turn "looks right" into numbers: RMSE and relative MSE on linear floats,
// PSNR, SSIM on luminance, the Light Wave similarity (Alg. 1), a light-leak error restricted to
// pixels a mask marks, and a false-colour error image.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace vplkit {

struct image_buffer;  // frontend/render_target.hpp

/// A linear RGB float image, rows top-down.
struct float_image {
  int width = 0;
  int height = 0;
  std::vector<glm::vec3> pixels;
  const glm::vec3& at(int x, int y) const { return pixels[static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x)]; }
};

/// From the frontend's RGBA float read-back (rows bottom-up).
float_image float_image_from_rgba(const std::vector<float>& rgba, int width, int height);

/// From an image_buffer read back from a render target (rows bottom-up): its RGB.
float_image float_image_from_buffer(const image_buffer& buffer);

/// Back to RGBA floats with rows bottom-up (alpha 1), e.g. for to_srgb8.
std::vector<float> rgba_from_float_image(const float_image& image);

/// PFM (portable float map, RGB, little-endian): the file's bytes, and the file written whole or
/// not at all.
std::vector<std::uint8_t> encode_pfm(const float_image& image);
void write_pfm(const std::filesystem::path& path, const float_image& image);

/// What an image file may claim before anything is allocated for it: a PNG of a few hundred bytes
/// can declare gigapixels. The defaults cover every image vplkit renders up to 8192^2.
struct image_read_limits {
  int max_side = 16384;
  std::size_t max_pixels = std::size_t{1} << 26;  ///< 64 Mi pixels (768 MiB as RGB floats)
};

enum class image_file_format { pfm, png };

/// Decodes a PFM (RGB, little-endian, exactly width x height x 12 bytes of finite floats after
/// the header) or a PNG (only when the bytes carry the PNG signature; sRGB, converted to linear).
/// Throws vplkit::error starting with `name` and saying what is wrong (header, size over the
/// limits, truncated or trailing data, the first non-finite pixel).
float_image decode_image(const std::string& bytes, image_file_format format, const std::string& name, const image_read_limits& limits = {});

/// Reads a .pfm or a .png file (the extension picks the format) with decode_image. Throws
/// vplkit::error naming the file.
float_image read_image_file(const std::filesystem::path& path, const image_read_limits& limits = {});

/// An error relative to the reference's level: RMSE and signed mean difference, each divided by
/// the reference's mean, over all three channels of the pixels counted.
struct relative_error {
  double rmse = 0.0;   ///< sqrt(mean (a - b)^2) / mean b
  double bias = 0.0;   ///< (mean a - mean b) / mean b: > 0 too bright, < 0 too dark
  std::size_t pixels = 0;
};

/// Over the pixels `mask` marks (luminance > 0.5), every pixel without a mask. Throws
/// vplkit::error on a size mismatch or a non-finite pixel; 0 for both when no pixel counts or the reference's mean is 0.
relative_error relative_error_of(const float_image& image, const float_image& reference, const float_image* mask = nullptr);

struct image_metrics {
  double rmse = 0.0;           ///< sqrt(mean over pixels and channels of (a - b)^2)
  double relative_mse = 0.0;   ///< mean of (a - b)^2 / (b^2 + 0.01), b the reference
  double psnr = 0.0;           ///< 10 log10(peak^2 / MSE), peak = the reference's largest value; inf when equal
  double ssim = 1.0;           ///< mean SSIM of the luminance (see compare_images)
  double similarity = 100.0;   ///< Light Wave Alg. 1 on 8-bit sRGB, percent
  std::optional<double> leak_rmse;  ///< RMSE over the pixels the mask marks (> 0.5), if a mask was given
  std::size_t leak_pixels = 0;
  relative_error relative;                 ///< over every pixel
  std::optional<relative_error> masked;    ///< over the mask's pixels, if a mask was given
};

/// Compares `image` with `reference` (same size and finite pixels, else vplkit::error). Sums
/// are taken in double, so every metric is finite for any finite float pixels, ±FLT_MAX included. SSIM: Wang et al. 2004 on
/// luminance with an 11x11 Gaussian window (sigma 1.5), C1 = (0.01 L)^2, C2 = (0.03 L)^2, L the
/// reference's largest luminance (linear images have no fixed range). `mask` (optional, same
/// size) selects the pixels of the light-leak error.
image_metrics compare_images(const float_image& image, const float_image& reference, const float_image* mask = nullptr);

/// |luminance(a) - luminance(b)| / scale through a blue-green-yellow-red ramp, as sRGB RGBA8
/// rows top-down (for write_png). scale <= 0: the largest difference.
std::vector<std::uint8_t> false_colour_error(const float_image& image, const float_image& reference, float scale);

}  // namespace vplkit
