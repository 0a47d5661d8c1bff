// The noise of a stochastic reference (the one-bounce Monte Carlo image) and what it does to an
// image's error against it. A Monte Carlo reference is itself an estimate: against it, even a
// perfect image has an error, and two images whose errors differ by less than the reference's
// noise cannot be ranked. The reference's per-pixel variance (of its estimate, per channel) is
// given, or estimated from two independent references of the same image (two seeds): each
// pixel's (a - b)^2 / 2 is an unbiased estimate of one reference's variance there.
#pragma once

#include <string>

#include "frontend/image/image.hpp"

namespace vplkit {

/// What the reference's noise does to relative_error_of(candidate, reference): over every pixel
/// (or the mask's), the three channels, as relative_error counts them.
struct reference_noise {
  bool defined = false;
  std::string why_undefined;  ///< as relative_error's: a black reference, no pixel
  /// The reference's own noise as a rel_rmse, sqrt(mean variance) / reference mean: what a perfect
  /// image scores against this reference.
  double noise = 0.0;
  /// rel_rmse with the reference's noise taken out: sqrt(max(0, MSE - mean variance)) / reference
  /// mean. The noise adds its variance to the expected MSE (it is independent of the image), so
  /// the corrected value estimates the error against the noise-free reference.
  double rmse_corrected = 0.0;
  /// The standard error of rel_rmse that the reference's noise causes (delta method on the MSE,
  /// Gaussian noise: var(d^2) = 4 t^2 v + 2 v^2 per value, t the error without noise).
  double rmse_se = 0.0;
  /// The standard error of rel_bias: the reference mean's, sqrt(sum v) / n, scaled by mean a / mean b^2.
  double bias_se = 0.0;
  /// noise / rel_rmse: the reference's noise as a fraction of the error reported (0 when the
  /// error is 0 and the noise too; 1 and above: the error is the reference's noise).
  double share = 0.0;
};

/// The per-pixel variance of one reference estimated from two independent ones (another seed):
/// (a - b)^2 / 2 per channel. Throws vplkit::error on a size mismatch or a non-finite pixel.
image variance_of_two(const image& first, const image& second);

/// The noise of `reference` (per-pixel, per-channel variance `variance`) in the error of
/// `candidate` against it. Throws vplkit::error on a size mismatch, a non-finite pixel or a
/// negative variance.
reference_noise reference_noise_of(const image& candidate, const image& reference, const image& variance, const image* mask = nullptr);

}  // namespace vplkit
