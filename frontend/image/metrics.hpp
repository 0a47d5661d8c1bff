// Image comparison for the quality report (`vplkit compare`): the metrics that turn "looks right" into numbers: RMSE and relative MSE on linear floats,
// PSNR, SSIM on luminance, the Light Wave similarity (Alg. 1), a light-leak error restricted to
// pixels a mask marks, and a false-colour error image.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "frontend/image/image.hpp"

namespace vplkit {

/// An error relative to the reference's level: RMSE and signed mean difference, each divided by
/// the reference's mean, over all three channels of the pixels counted. Against a reference whose
/// mean is 0 (black) or below, or over no pixel, the relative numbers do not exist: `defined` is
/// then false and `why_undefined` says why. They are not 0: a 0 would read as a perfect match and
/// rank that configuration best. Callers print "undefined" with the reason (text), null (JSON) or
/// "undefined" (CSV), never the number fields.
struct relative_error {
  double rmse = 0.0;   ///< sqrt(mean (a - b)^2) / mean b
  double bias = 0.0;   ///< (mean a - mean b) / mean b: > 0 too bright, < 0 too dark
  std::size_t pixels = 0;
  bool defined = false;
  std::string why_undefined;  ///< empty when defined
};

/// Over the pixels `mask` marks (luminance > 0.5), every pixel without a mask. Throws
/// vplkit::error on a size mismatch or a non-finite pixel; undefined (see relative_error) when no
/// pixel counts or the reference's mean over them is not above 0.
relative_error relative_error_of(const image& candidate, const image& reference, const image* mask = nullptr);

struct image_metrics {
  double rmse = 0.0;           ///< sqrt(mean over pixels and channels of (a - b)^2)
  double relative_mse = 0.0;   ///< mean of (a - b)^2 / (b^2 + 0.01), b the reference
  double psnr = 0.0;           ///< 10 log10(peak^2 / MSE), peak = the reference's largest value; inf when equal
  /// Whether psnr exists: not when the images differ and the reference's peak is 0 (black), where
  /// the ratio has no scale; why_psnr_undefined then says so.
  bool psnr_defined = true;
  std::string why_psnr_undefined;
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
image_metrics compare_images(const image& candidate, const image& reference, const image* mask = nullptr);

/// |luminance(a) - luminance(b)| / scale through a blue-green-yellow-red ramp, as sRGB RGBA8
/// rows top-down (for write_png). scale <= 0: the largest difference.
std::vector<std::uint8_t> false_colour_error(const image& candidate, const image& reference, float scale);

}  // namespace vplkit
