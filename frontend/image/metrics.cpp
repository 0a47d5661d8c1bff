#include "frontend/image/metrics.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <vplkit/lightwave.hpp>

#include "frontend/core/error.hpp"

namespace vplkit {

namespace {

// In double: the luminance of finite float pixels can exceed FLT_MAX.
double luminance_of(const glm::vec4& c) { return luminance(glm::dvec3(c)); }

// The metrics promise finite numbers; an image made in memory could hold NaN (files cannot).
void require_finite(const image& candidate, const std::string& what) {
  for (std::size_t i = 0; i < candidate.texels.size(); ++i)
    if (!std::isfinite(candidate.texels[i].r) || !std::isfinite(candidate.texels[i].g) || !std::isfinite(candidate.texels[i].b))
      throw error(what + ": pixel (" + std::to_string(i % static_cast<std::size_t>(candidate.width)) + ", " +
                  std::to_string(candidate.height - 1 - static_cast<int>(i / static_cast<std::size_t>(candidate.width))) + ") (from the top left) is not finite");
}

// Two images of the same size with finite pixels (and the mask, if any).
void require_comparable(const image& candidate, const image& reference, const image* mask, const char* what) {
  require_same_size(candidate, reference, what);
  if (mask) require_same_size(*mask, reference, what);
  require_finite(candidate, std::string(what) + ": the image");
  require_finite(reference, std::string(what) + ": the reference");
  if (mask) require_finite(*mask, std::string(what) + ": the mask");
}

// relative_error_of without the checks, for callers that made them.
relative_error relative_error_over(const image& candidate, const image& reference, const image* mask) {
  double squared = 0.0, sum_image = 0.0, sum_reference = 0.0;
  relative_error result;
  for (std::size_t i = 0; i < candidate.texels.size(); ++i) {
    if (mask && !(luminance_of(mask->texels[i]) > 0.5f)) continue;
    for (int c = 0; c < 3; ++c) {
      const double a = candidate.texels[i][c], b = reference.texels[i][c];
      squared += (a - b) * (a - b);
      sum_image += a;
      sum_reference += b;
    }
    ++result.pixels;
  }
  if (result.pixels == 0) {
    result.why_undefined = mask ? "the mask marks no pixel (luminance > 0.5)" : "the image has no pixel";
    return result;
  }
  if (!(sum_reference > 0.0)) {
    result.why_undefined = std::string(sum_reference == 0.0 ? "the reference's mean is 0 (black)" : "the reference's mean is negative") + " over the " +
                           std::to_string(result.pixels) + (mask ? " masked" : "") + " pixels: there is no level to be relative to";
    return result;
  }
  result.defined = true;
  const double n = 3.0 * static_cast<double>(result.pixels), mean = sum_reference / n;
  result.rmse = std::sqrt(squared / n) / mean;
  result.bias = (sum_image - sum_reference) / sum_reference;
  return result;
}

}  // namespace

relative_error relative_error_of(const image& candidate, const image& reference, const image* mask) {
  require_comparable(candidate, reference, mask, "relative error");
  return relative_error_over(candidate, reference, mask);
}

image_metrics compare_images(const image& candidate, const image& reference, const image* mask) {
  require_comparable(candidate, reference, mask, "compare");
  image_metrics m;
  const std::size_t count = candidate.texels.size();
  double squared = 0.0, relative = 0.0, peak = 0.0, leak_squared = 0.0;
  for (std::size_t i = 0; i < count; ++i) {
    const bool in_mask = mask && luminance_of(mask->texels[i]) > 0.5f;
    for (int c = 0; c < 3; ++c) {
      const double a = candidate.texels[i][c], b = reference.texels[i][c], d = a - b;
      squared += d * d;
      relative += d * d / (b * b + 0.01);
      peak = std::max(peak, std::fabs(b));
      if (in_mask) leak_squared += d * d;
    }
    m.leak_pixels += in_mask;
  }
  const double mse = squared / (3.0 * static_cast<double>(count));
  m.rmse = std::sqrt(mse);
  m.relative_mse = relative / (3.0 * static_cast<double>(count));
  if (mse == 0.0) {
    m.psnr = std::numeric_limits<double>::infinity();
  } else if (peak > 0.0) {
    m.psnr = 10.0 * std::log10(peak * peak / mse);
  } else {
    m.psnr_defined = false;
    m.why_psnr_undefined = "the reference is black (its peak is 0): there is no signal level to be relative to";
  }
  if (mask) m.leak_rmse = m.leak_pixels > 0 ? std::sqrt(leak_squared / (3.0 * static_cast<double>(m.leak_pixels))) : 0.0;
  m.relative = relative_error_over(candidate, reference, nullptr);
  if (mask) m.masked = relative_error_over(candidate, reference, mask);

  // SSIM on luminance, Gaussian window 11 x 11, sigma 1.5 (Wang et al. 2004), clipped at borders.
  const int w = candidate.width, h = candidate.height, radius = 5;
  std::vector<double> la(count), lb(count);
  double l_max = 0.0;
  for (std::size_t i = 0; i < count; ++i) {
    la[i] = luminance_of(candidate.texels[i]);
    lb[i] = luminance_of(reference.texels[i]);
    l_max = std::max(l_max, lb[i]);
  }
  const double range = std::max(l_max, 1e-6), c1 = (0.01 * range) * (0.01 * range), c2 = (0.03 * range) * (0.03 * range);
  double ssim_sum = 0.0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      double weight = 0.0, mean_a = 0.0, mean_b = 0.0;
      for (int dy = -radius; dy <= radius; ++dy)
        for (int dx = -radius; dx <= radius; ++dx) {
          const int sx = x + dx, sy = y + dy;
          if (sx < 0 || sy < 0 || sx >= w || sy >= h) continue;
          const double g = std::exp(-(dx * dx + dy * dy) / (2.0 * 1.5 * 1.5));
          const std::size_t j = static_cast<std::size_t>(sy) * static_cast<std::size_t>(w) + static_cast<std::size_t>(sx);
          weight += g;
          mean_a += g * la[j];
          mean_b += g * lb[j];
        }
      mean_a /= weight;
      mean_b /= weight;
      double var_a = 0.0, var_b = 0.0, covariance = 0.0;
      for (int dy = -radius; dy <= radius; ++dy)
        for (int dx = -radius; dx <= radius; ++dx) {
          const int sx = x + dx, sy = y + dy;
          if (sx < 0 || sy < 0 || sx >= w || sy >= h) continue;
          const double g = std::exp(-(dx * dx + dy * dy) / (2.0 * 1.5 * 1.5)) / weight;
          const std::size_t j = static_cast<std::size_t>(sy) * static_cast<std::size_t>(w) + static_cast<std::size_t>(sx);
          var_a += g * (la[j] - mean_a) * (la[j] - mean_a);
          var_b += g * (lb[j] - mean_b) * (lb[j] - mean_b);
          covariance += g * (la[j] - mean_a) * (lb[j] - mean_b);
        }
      ssim_sum += ((2 * mean_a * mean_b + c1) * (2 * covariance + c2)) / ((mean_a * mean_a + mean_b * mean_b + c1) * (var_a + var_b + c2));
    }
  m.ssim = ssim_sum / static_cast<double>(count);

  // Alg. 1 on the 8-bit sRGB encodings, RGB channels.
  std::vector<std::uint8_t> a8, b8;
  a8.reserve(count * 3);
  b8.reserve(count * 3);
  for (std::size_t i = 0; i < count; ++i)
    for (int c = 0; c < 3; ++c) {
      a8.push_back(linear_to_srgb8(candidate.texels[i][c]));
      b8.push_back(linear_to_srgb8(reference.texels[i][c]));
    }
  m.similarity = lightwave_similarity(a8.data(), b8.data(), a8.size());
  return m;
}

std::vector<std::uint8_t> false_colour_error(const image& candidate, const image& reference, float scale) {
  require_comparable(candidate, reference, nullptr, "error image");
  if (!std::isfinite(scale)) throw error("error image: the scale must be finite");
  std::vector<double> differences(candidate.texels.size());
  double largest = 0.0;
  for (std::size_t i = 0; i < differences.size(); ++i) {
    differences[i] = std::fabs(luminance_of(candidate.texels[i]) - luminance_of(reference.texels[i]));
    largest = std::max(largest, differences[i]);
  }
  const double full_red = scale > 0.0f ? double{scale} : largest > 0.0 ? largest : 1.0;
  // Blue (0) -> cyan -> green -> yellow -> red (scale and above).
  const glm::vec3 ramp[5] = {{0, 0, 1}, {0, 1, 1}, {0, 1, 0}, {1, 1, 0}, {1, 0, 0}};
  std::vector<std::uint8_t> out(differences.size() * 4);
  for (std::size_t i = 0; i < differences.size(); ++i) {
    const int x = static_cast<int>(i % static_cast<std::size_t>(candidate.width)), y = static_cast<int>(i / static_cast<std::size_t>(candidate.width));
    std::uint8_t* rgba = &out[candidate.index(x, candidate.height - 1 - y) * 4];  // PNG rows are top-down
    const float t = static_cast<float>(std::clamp(differences[i] / full_red, 0.0, 1.0)) * 4.0f;
    const int k = std::min(3, static_cast<int>(t));
    const glm::vec3 c = glm::mix(ramp[k], ramp[k + 1], t - static_cast<float>(k));
    for (int channel = 0; channel < 3; ++channel) rgba[channel] = static_cast<std::uint8_t>(std::lround(255.0f * c[channel]));
    rgba[3] = 255;
  }
  return out;
}

}  // namespace vplkit
