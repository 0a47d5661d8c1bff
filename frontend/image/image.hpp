// Every conversion of the frontend's one image type (frontend/core/image.hpp: a linear float
// RGBA image with rows bottom-up, the order in which GL reads a render target back and in which a
// PFM file stores its rows). Only PNG is top-down; to_srgb8 (and the PNG decoder in image_files)
// are the one place where rows are flipped. Rec. 709 luminance and the sRGB transfer function are
// defined here once.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "frontend/core/image.hpp"

namespace vplkit {

/// What an image file may claim before anything is allocated for it: a PNG of a few hundred bytes
/// can declare gigapixels. The defaults cover every image vplkit renders up to 8192^2.
struct image_read_limits {
  int max_side = max_image_side;
  std::size_t max_pixels = std::size_t{1} << 26;  ///< 64 Mi pixels: 256 MiB as RGBA8, 1 GiB as a float image
  /// PNG: the most bytes libspng keeps of one ancillary chunk (text, ICC profile, EXIF), and of
  /// all of them together, decompressed; beyond them the file is refused (a zTXt that inflates to
  /// 64 MiB is). vplkit uses none of them; an ICC profile is rarely over 1 MiB.
  std::size_t max_chunk_bytes = std::size_t{4} << 20;
  std::size_t max_chunk_cache_bytes = std::size_t{16} << 20;
};

/// Rec. 709 luminance of linear RGB, in the precision of T (double for sums over images: the
/// luminance of finite floats can exceed FLT_MAX).
template <typename T>
T luminance(const glm::vec<3, T>& rgb) {
  return T(0.2126) * rgb.r + T(0.7152) * rgb.g + T(0.0722) * rgb.b;
}

/// The sRGB transfer function of a linear value, clamped to [0, 1] first (NaN gives 0).
float linear_to_srgb(float value);
/// Its inverse, for values in [0, 1].
float srgb_to_linear(float value);
/// A linear value as an 8-bit sRGB code: lround(255 * linear_to_srgb(value)).
std::uint8_t linear_to_srgb8(float value);

/// exposure * RGB as 8-bit sRGB RGBA, alpha 255, rows top-down (the PNG raster order).
std::vector<std::uint8_t> to_srgb8(const image& linear, float exposure = 1.0f);

/// The exposure that maps the 99th percentile of the positive finite luminances to 0.8: a
/// deterministic display scale for images whose level depends on the scene (indirect light).
/// Returns 1 for an all-black image.
float percentile_exposure(const image& linear);

/// |L(a) - L(b)| * scale as grey (alpha 1): what the visibility approximation removes (Fig. 5.1c).
/// Throws vplkit::error when the sizes differ.
image luminance_difference(const image& a, const image& b, float scale);

/// The red channel of every texel as grey (alpha 1): a scalar buffer (e.g. the Light Wave
/// indirect shadow factor) shown as an image.
image red_as_grey(const image& source);

/// Throws vplkit::error naming `what` and both sizes when `a` and `b` differ in size.
void require_same_size(const image& a, const image& b, const std::string& what);

}  // namespace vplkit
