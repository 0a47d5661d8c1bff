// The post filter of [RSMV] (section 4.5): the half-resolution indirect irradiance is
// upsampled and blurred by an edge-aware (bilateral) kernel of size 17 whose weight falls with
// the distance, the depth difference and the normal difference.
//
// Joint upsampling and blur in one pass: for a full-resolution pixel at low-resolution
// coordinate c (texels, continuous), the taps are the kernel_size x kernel_size low-resolution
// texels around c; each weighs
//   w = exp(-|q - c|^2 / (2 sigma_s^2)) * exp(-((z_q - z_c) / (sigma_z z_c))^2 / 2) * max(0, <n_c, n_q>)^k
// (z: camera eye-space depth, relative difference, so the filter does not depend on the scene's
// scale; n: normals; k an integer power, computed by repeated squaring). Taking the taps
// on the low-resolution grid means kernel 17 spans 17 distinct irradiance samples per axis.
// The thesis does not give the sigmas or the power: settings.
// `bilateral_filter` is the full 2D kernel; `bilateral_filter_axis` one axis of the separable
// approximation (two passes, 2 x 17 taps instead of 17^2); `bilateral_filter_axis_quad` that axis
// for the 2 x 2 full-resolution pixels of one half-resolution texel, which share its taps.
//
// GLSL twin: shaders/lib/bilateral.glsl; the including shader defines
// `bilateral_tap bilateral_fetch(ivec2 texel)`.
#pragma once

#include <array>
#include <cmath>
#include <cstddef>

#include <glm/glm.hpp>

#include <vplkit/settings.hpp>

namespace vplkit {

/// A low-resolution texel as the filter sees it.
template <typename T>
struct bilateral_tap {
  glm::vec<3, T> value;   ///< indirect irradiance
  T depth;                ///< camera eye-space depth (negative in front; >= 0: no surface)
  glm::vec<3, T> normal;  ///< world space, unit
};

/// GLSL twin: struct bilateral_settings.
template <typename T = float>
struct bilateral_settings {
  int kernel_size = 17;      ///< taps per axis (odd, >= 1); the thesis's 17
  T spatial_sigma = T(4);    ///< in low-resolution texels
  T depth_sigma = T(0.05);   ///< relative depth difference (0.05 = 5% of the depth)
  int normal_power = 8;      ///< k in max(0, <n_c, n_q>)^k (>= 0)
};

/// The largest normal_power the settings allow, and its bits: integer_power's loop runs that many
/// times (GLSL twin: integer_power_bits).
inline constexpr int bilateral_max_normal_power = 64;
inline constexpr int integer_power_bits = 7;
static_assert(bilateral_max_normal_power < (1 << integer_power_bits), "integer_power must cover every allowed normal_power");

template <typename T>
struct settings_description<bilateral_settings<T>> {
  using S = bilateral_settings<T>;
  static constexpr const char* name = "bilateral_settings";
  static constexpr bool glsl_twin = true;
  static constexpr auto fields() {
    return std::make_tuple(schema::field(&S::kernel_size, "kernel_size", schema::closed_range(1, 63), "taps", "taps per axis of the post filter (odd)"),
                           schema::field(&S::spatial_sigma, "spatial_sigma", schema::above(0.0), "indirect texels", "the post filter's spatial Gaussian"),
                           schema::field(&S::depth_sigma, "depth_sigma", schema::above(0.0), "of the depth", "relative depth difference of half weight"),
                           schema::field(&S::normal_power, "normal_power", schema::closed_range(0, bilateral_max_normal_power), "", "k of the normal weight max(0, <n_c, n_q>)^k"));
  }
  static setting_problem rules(const S& settings) {
    if (settings.kernel_size % 2 == 0) return setting_problem("bilateral_settings::kernel_size must be odd and in [1, 63]");
    return {};
  }
};

/// base^power for an integer power in [0, 2^integer_power_bits) by repeated squaring:
/// multiplies instead of power calls, the same on both twins. The loop runs over every bit of the
/// range, a constant trip count the compilers unroll into multiplies and selects (llvmpipe ran a
/// loop of data-dependent trip count with mask tests per iteration); a bit that is 0 multiplies by
/// 1, exact, so the value is that of the loop over the power's own bits.
template <typename T>
T integer_power(T base, int power) {
  T result = T(1);
  for (int b = 0; b < integer_power_bits; ++b) {
    result *= ((power >> b) & 1) != 0 ? base : T(1);
    base *= base;
  }
  return result;
}

namespace detail {

/// What a tap's weight needs of its centre, computed once per centre: the filters divide once
/// per pixel, not twice per tap.
template <typename T>
struct bilateral_centre {
  T depth;                  ///< camera eye-space depth; 0: nothing there
  glm::vec<3, T> normal;
  T spatial_scale;          ///< 1 / (2 sigma_s^2)
  T depth_scale;            ///< 1 / (sigma_z depth); unused at depth 0
};

template <typename T>
bilateral_centre<T> make_bilateral_centre(T depth, const glm::vec<3, T>& normal, const bilateral_settings<T>& settings) {
  return {depth, normal, T(1) / (T(2) * settings.spatial_sigma * settings.spatial_sigma),
          depth != T(0) ? T(1) / (settings.depth_sigma * depth) : T(0)};
}

/// The spatial and the depth Gaussians share one exp of the sum of their exponents (one exp per
/// tap, not two).
template <typename T>
T bilateral_weight(const glm::vec<2, T>& offset, T tap_depth, const glm::vec<3, T>& tap_normal, const bilateral_centre<T>& centre,
                   int normal_power) {
  T exponent = glm::dot(offset, offset) * centre.spatial_scale;
  // Relative to the centre's depth; a centre at depth 0 (nothing there) matches only depth 0.
  // Selects, not a branch, as the GLSL twin (where llvmpipe runs both sides of a branch under a
  // lane mask): at depth 0 the exponent gains 0, exact, so the values are those of the branch.
  const bool surface = centre.depth != T(0);
  const T relative = surface ? (tap_depth - centre.depth) * centre.depth_scale : T(0);
  exponent += T(0.5) * relative * relative;
  const T depth = surface || tap_depth == centre.depth ? T(1) : T(0);
  const T facing = glm::max(T(0), glm::dot(centre.normal, tap_normal));
  return std::exp(-exponent) * depth * integer_power(facing, normal_power);
}

/// One fetched tap, `offset` from a centre, weighed and added to that centre's sums: what every
/// filter does per tap and centre (the quad's four centres share the fetch, not this).
template <typename T>
void bilateral_accumulate(const bilateral_tap<T>& tap, const glm::vec<2, T>& offset, const bilateral_centre<T>& centre, int normal_power,
                          glm::vec<3, T>& sum, T& weight_sum) {
  const T weight = bilateral_weight(offset, tap.depth, tap.normal, centre, normal_power);
  sum += weight * tap.value;
  weight_sum += weight;
}

template <typename T, typename Fetch>
void bilateral_add_tap(const glm::ivec2& texel, const glm::vec<2, T>& centre_coordinate, const bilateral_centre<T>& centre, Fetch& fetch,
                       const glm::ivec2& size, int normal_power, glm::vec<3, T>& sum, T& weight_sum) {
  if (texel.x < 0 || texel.y < 0 || texel.x >= size.x || texel.y >= size.y) return;
  const bilateral_tap<T> tap = fetch(texel);
  if (!(tap.depth < T(0))) return;
  bilateral_accumulate(tap, glm::vec<2, T>(texel) + T(0.5) - centre_coordinate, centre, normal_power, sum, weight_sum);
}

/// One axis of taps around texel `base` for N centres that all lie in it (floor(centre) == base):
/// each tap is fetched once and weighed for every centre, each centre's weights summed in
/// bilateral_filter_axis's order, so each result is bit for bit the one of a filter per centre.
template <typename T, std::size_t N, typename Fetch>
std::array<glm::vec<3, T>, N> bilateral_filter_axis_shared(const glm::ivec2& base, const std::array<glm::vec<2, T>, N>& centres,
                                                           const std::array<bilateral_centre<T>, N>& constants, Fetch& fetch,
                                                           const glm::ivec2& size, int axis, const bilateral_settings<T>& settings) {
  const glm::ivec2 step = axis == 0 ? glm::ivec2(1, 0) : glm::ivec2(0, 1);
  const int radius = settings.kernel_size / 2;
  std::array<glm::vec<3, T>, N> sum;
  std::array<T, N> weight_sum;
  sum.fill(glm::vec<3, T>(0));
  weight_sum.fill(T(0));
  for (int i = -radius; i <= radius; ++i) {
    const glm::ivec2 texel = base + step * i;
    if (texel.x < 0 || texel.y < 0 || texel.x >= size.x || texel.y >= size.y) continue;
    const bilateral_tap<T> tap = fetch(texel);
    if (!(tap.depth < T(0))) continue;
    for (std::size_t s = 0; s < N; ++s)
      bilateral_accumulate(tap, glm::vec<2, T>(texel) + T(0.5) - centres[s], constants[s], settings.normal_power, sum[s], weight_sum[s]);
  }
  std::array<glm::vec<3, T>, N> filtered;
  for (std::size_t s = 0; s < N; ++s) filtered[s] = weight_sum[s] > T(0) ? sum[s] / weight_sum[s] : glm::vec<3, T>(0);
  return filtered;
}

}  // namespace detail

/// The weight of one tap at `offset` (low-resolution texels) from the centre.
template <typename T>
T bilateral_weight(const glm::vec<2, T>& offset, T centre_depth, T tap_depth, const glm::vec<3, T>& centre_normal,
                   const glm::vec<3, T>& tap_normal, const bilateral_settings<T>& settings) {
  return detail::bilateral_weight(offset, tap_depth, tap_normal, detail::make_bilateral_centre(centre_depth, centre_normal, settings),
                                  settings.normal_power);
}

/// Full 2D kernel around low-resolution coordinate `centre`. Returns 0 where no tap has weight.
template <typename T, typename Fetch>
glm::vec<3, T> bilateral_filter(const glm::vec<2, T>& centre, T centre_depth, const glm::vec<3, T>& centre_normal,
                                Fetch&& fetch, const glm::ivec2& size, const bilateral_settings<T>& settings) {
  const glm::ivec2 base = glm::ivec2(glm::floor(centre));
  const int radius = settings.kernel_size / 2;
  const detail::bilateral_centre<T> constants = detail::make_bilateral_centre(centre_depth, centre_normal, settings);
  glm::vec<3, T> sum(0);
  T weight_sum = T(0);
  for (int j = -radius; j <= radius; ++j)
    for (int i = -radius; i <= radius; ++i)
      detail::bilateral_add_tap(base + glm::ivec2(i, j), centre, constants, fetch, size, settings.normal_power, sum, weight_sum);
  return weight_sum > T(0) ? sum / weight_sum : glm::vec<3, T>(0);
}

/// One axis (0: x, 1: y) of the separable approximation.
template <typename T, typename Fetch>
glm::vec<3, T> bilateral_filter_axis(const glm::vec<2, T>& centre, T centre_depth, const glm::vec<3, T>& centre_normal,
                                     Fetch&& fetch, const glm::ivec2& size, int axis, const bilateral_settings<T>& settings) {
  return detail::bilateral_filter_axis_shared<T, 1>(glm::ivec2(glm::floor(centre)), {centre},
                                                   {detail::make_bilateral_centre(centre_depth, centre_normal, settings)}, fetch, size, axis,
                                                   settings)[0];
}

/// The centre of full-resolution pixel 2 `texel` + (s & 1, s >> 1) (s = 0..3) on the
/// half-resolution grid (indirect divisor 2): texel + (0.25 | 0.75), as the post pass computes it.
template <typename T>
glm::vec<2, T> bilateral_quad_centre(const glm::ivec2& texel, int s) {
  return (glm::vec<2, T>(2 * texel + glm::ivec2(s & 1, s >> 1)) + T(0.5)) / T(2);
}

/// `bilateral_filter_axis` for the 2 x 2 full-resolution pixels of half-resolution texel `texel`
/// (indirect divisor 2; pixel s = 0..3 is 2 texel + (s & 1, s >> 1), its centre
/// bilateral_quad_centre): their centres lie in the same texel, so they share its taps, fetched
/// once instead of four times. Result s is bit for bit bilateral_filter_axis at centre s with
/// depth and normal s.
template <typename T, typename Fetch>
std::array<glm::vec<3, T>, 4> bilateral_filter_axis_quad(const glm::ivec2& texel, const std::array<T, 4>& centre_depth,
                                                         const std::array<glm::vec<3, T>, 4>& centre_normal, Fetch&& fetch,
                                                         const glm::ivec2& size, int axis, const bilateral_settings<T>& settings) {
  std::array<glm::vec<2, T>, 4> centres;
  std::array<detail::bilateral_centre<T>, 4> constants;
  for (int s = 0; s < 4; ++s) {
    centres[static_cast<std::size_t>(s)] = bilateral_quad_centre<T>(texel, s);
    constants[static_cast<std::size_t>(s)] = detail::make_bilateral_centre(centre_depth[static_cast<std::size_t>(s)], centre_normal[static_cast<std::size_t>(s)], settings);
  }
  return detail::bilateral_filter_axis_shared<T, 4>(texel, centres, constants, fetch, size, axis, settings);
}

}  // namespace vplkit
