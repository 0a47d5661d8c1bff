#include "frontend/image/reference_noise.hpp"

#include <cmath>

#include <vplkit/lightwave.hpp>

#include "frontend/core/error.hpp"

namespace vplkit {

namespace {

void require_finite_image(const image& i, const std::string& what) {
  for (const glm::vec4& t : i.texels)
    if (!std::isfinite(t.r) || !std::isfinite(t.g) || !std::isfinite(t.b)) throw error(what + " has a pixel that is not finite");
}

}  // namespace

image variance_of_two(const image& first, const image& second) {
  require_same_size(first, second, "the variance of two references");
  require_finite_image(first, "the first reference");
  require_finite_image(second, "the second reference");
  image variance(first.width, first.height);
  for (std::size_t i = 0; i < first.texels.size(); ++i)
    for (int c = 0; c < 3; ++c) {
      const double d = static_cast<double>(first.texels[i][c]) - static_cast<double>(second.texels[i][c]);
      variance.texels[i][c] = static_cast<float>(d * d / 2.0);
    }
  return variance;
}

reference_noise reference_noise_of(const image& candidate, const image& reference, const image& variance, const image* mask) {
  require_same_size(candidate, reference, "the reference's noise");
  require_same_size(variance, reference, "the reference's noise (its variance)");
  if (mask) require_same_size(*mask, reference, "the reference's noise (the mask)");
  require_finite_image(candidate, "the image");
  require_finite_image(reference, "the reference");
  require_finite_image(variance, "the reference's variance");
  double squared = 0.0, sum_a = 0.0, sum_b = 0.0, sum_v = 0.0, var_squared = 0.0;
  std::size_t pixels = 0;
  for (std::size_t i = 0; i < reference.texels.size(); ++i) {
    if (mask && !(luminance(glm::dvec3(mask->texels[i])) > 0.5)) continue;
    for (int c = 0; c < 3; ++c) {
      const double a = candidate.texels[i][c], b = reference.texels[i][c], v = variance.texels[i][c], d = a - b;
      if (v < 0.0) throw error("the reference's variance is negative at pixel " + std::to_string(i) + " (a variance is a square)");
      squared += d * d;
      sum_a += a;
      sum_b += b;
      sum_v += v;
      // var(d^2) for d = t + e, e ~ N(0, v): 4 t^2 v + 2 v^2, with t^2 estimated by d^2 - v.
      const double t2 = std::max(0.0, d * d - v);
      var_squared += 4.0 * t2 * v + 2.0 * v * v;
    }
    ++pixels;
  }
  reference_noise result;
  if (pixels == 0) {
    result.why_undefined = mask ? "the mask marks no pixel (luminance > 0.5)" : "the image has no pixel";
    return result;
  }
  if (!(sum_b > 0.0)) {
    result.why_undefined = "the reference's mean is not above 0: there is no level to be relative to";
    return result;
  }
  result.defined = true;
  const double n = 3.0 * static_cast<double>(pixels), mean_b = sum_b / n, mse = squared / n, mean_v = sum_v / n;
  result.noise = std::sqrt(mean_v) / mean_b;
  result.rmse_corrected = std::sqrt(std::max(0.0, mse - mean_v)) / mean_b;
  // rel_rmse = sqrt(MSE) / mean b: d rel_rmse = d MSE / (2 sqrt(MSE) mean b).
  const double mse_se = std::sqrt(var_squared) / n;
  result.rmse_se = mse > 0.0 ? mse_se / (2.0 * std::sqrt(mse) * mean_b) : std::sqrt(mse_se) / mean_b;
  const double mean_a = sum_a / n, mean_b_se = std::sqrt(sum_v) / n;
  result.bias_se = std::fabs(mean_a) / (mean_b * mean_b) * mean_b_se;
  const double rel_rmse = std::sqrt(mse) / mean_b;
  result.share = rel_rmse > 0.0 ? result.noise / rel_rmse : (result.noise > 0.0 ? 1.0 : 0.0);
  return result;
}

}  // namespace vplkit
