// Where an RSM gather samples: the radial pattern of [RSMV] (section 3.2, Alg. 1 and 5) and
// the original RSM disk pattern (Dachsbacher and Stamminger 2005) as the baseline. Offsets are
// in RSM texels from the receiver's projection onto the RSM; weights in texels^2 (the RSM area
// a sample stands for), so sum(weight * E_p) estimates the sum of E_p over all pixel lights.
//
// Radial pattern: P straight paths from the projection, S samples per path, near to far. The
// annulus [r_min, r_max] is cut into S log-spaced rings, r_j = r_min * q^j with
// q = (r_max / r_min)^(1/S); sample j lies uniformly in ring j, at angle 2 pi (p + rotation +
// jitter) / P. Its weight (2 pi / P) * r * (r_(j+1) - r_j) is the inverse of its area density,
// so the weighted sum is an unbiased estimate of the integral over the annulus, and since the
// ring widths grow like r, the weight grows like r^2: "density decreases and weight grows with
// the square of the distance" (docs/errata.md, RSMV-2). The inner disk
// r < r_min is not sampled: with the default r_min = 1 texel it is the receiver's own texel,
// whose surface cannot light itself (Eq. 3.2 is 0 for coplanar points).
// Per pixel, the whole pattern is rotated by up to one path spacing and scaled by a factor near
// 1; per sample, the angle is jittered by a fraction of the path spacing (Alg. 1, lines 4-5).
// The thesis gives no amounts: they are settings. Randomness comes from hash.hpp and angles go
// through direction_from_turns, so the GLSL twin computes the same offsets to the bit.
//
// Disk pattern: offset = r_max * xi1 * (sin 2 pi xi2, cos 2 pi xi2). The original draws the same
// (xi1, xi2) for every pixel, so every receiver makes the same error: a bright patch that the N
// samples hit or miss is over- or under-counted across the whole image at once (the image's mean
// off by -21 to +28 % on the frames of docs/rsm-study.md, "The disk shifted per pixel"). By default
// each pixel shifts its pattern on the unit square (xi + u mod 1, u a hash of the pixel: a
// Cranley-Patterson rotation), which leaves every receiver's estimate unbiased and makes the
// receivers' errors independent, so the image's mean converges and the post filter averages the
// noise; `per_pixel_shift = false` is the original's fixed pattern, bit for bit (u = 0).
// Uniform xi1 puts the samples' area density at 1 / (2 pi r_max r): dense near the receiver, as
// the original RSM intends. The weight that makes the sum an unbiased estimate is the inverse of
// that density over N, xi1 * 2 pi r_max^2 / N (weights ~ r; they sum to the disk's area in
// expectation, E[xi1] = 1/2): the default. The original RSM prints xi1^2 (normalised here by
// 3 pi r_max^2 / N so that those weights sum to the area as well, E[xi1^2] = 1/3), which
// over-compensates the density: far samples weigh too much, near ones too little, and the estimate
// is biased for anything but a constant (-23 % to -57 % on the frames of docs/rsm-study.md);
// `printed_weights` keeps it (docs/errata.md, RSMV-9).
//
// GLSL twin: shaders/lib/rsm_pattern.glsl.
#pragma once

#include <cstdint>
#include <limits>

#include <glm/glm.hpp>

#include <vplkit/hash.hpp>
#include <vplkit/polynomial_math.hpp>
#include <vplkit/settings.hpp>

namespace vplkit {

/// A sample of a pattern: where (RSM texels from the projection) and how much area it stands for.
template <typename T>
struct pattern_sample {
  glm::vec<2, T> offset;
  T weight;
};

/// Settings of the radial pattern (defaults: the thesis's 15 x 10).
template <typename T = float>
struct radial_pattern_settings {
  int paths = 15;              ///< P, straight paths from the projection (>= 1)
  int samples_per_path = 10;   ///< S, samples along each path, near to far (>= 1)
  T min_radius = T(1);         ///< r_min in RSM texels (> 0)
  T max_radius = T(64);        ///< r_max in RSM texels (> r_min); 1/8 of a 512^2 RSM
  T rotation_jitter = T(1);    ///< per-pixel rotation, in path spacings: uniform in [0, this)
  T angle_jitter = T(0.25);    ///< per-sample angle jitter, in path spacings: +-half of this
  T scale_jitter = T(0.2);     ///< per-pixel radius scale: uniform in [1 - this/2, 1 + this/2)
  std::uint32_t seed = 0;      ///< changes every per-pixel and per-sample random number
};

template <typename T>
struct settings_description<radial_pattern_settings<T>> {
  using S = radial_pattern_settings<T>;
  static constexpr const char* name = "radial_pattern_settings";
  static constexpr bool glsl_twin = false;  // the GLSL side reads radial_pattern_constants
  static constexpr auto fields() {
    return std::make_tuple(
        schema::field(&S::paths, "paths", schema::closed_range(1, 256), "", "P: straight paths from the receiver's projection"),
        schema::field(&S::samples_per_path, "samples_per_path", schema::closed_range(1, 256), "", "S: samples along each path, near to far"),
        schema::field(&S::min_radius, "min_radius", schema::above(0.0), "RSM texels", "r_min: the inner radius the rings start from"),
        schema::field(&S::max_radius, "max_radius", schema::above(0.0), "RSM texels", "r_max: the outer radius of the pattern"),
        schema::field(&S::rotation_jitter, "rotation_jitter", schema::closed_range(0, 1), "path spacings", "per-pixel rotation of the pattern: uniform in [0, this)"),
        schema::field(&S::angle_jitter, "angle_jitter", schema::closed_range(0, 1), "path spacings", "per-sample angle jitter: +-half of this"),
        schema::field(&S::scale_jitter, "scale_jitter", schema::closed_open_range(0, 1), "", "per-pixel radius scale: uniform in [1 - this/2, 1 + this/2)"),
        schema::field(&S::seed, "seed", schema::closed_range(0, 4294967295.0), "", "changes every per-pixel and per-sample random number"));
  }
  static setting_problem rules(const S& settings) {
    if (!(settings.max_radius > settings.min_radius)) return setting_problem("radial_pattern_settings::max_radius must be finite and > min_radius");
    return {};
  }
};

/// The constants both sides use, derived once from the settings. GLSL twin: struct
/// radial_pattern_constants (a uniform).
template <typename T>
struct radial_pattern_constants {
  int paths;
  int samples_per_path;
  T min_radius;
  T ring_ratio;     ///< q = (r_max / r_min)^(1 / S)
  T path_turns;     ///< 1 / P: the angle between paths in turns
  T path_angle;     ///< 2 pi / P: the same in radians, for the weights
  T rotation_jitter;
  T angle_jitter;
  T scale_jitter;
  std::uint32_t seed;
  T max_radius;     ///< r_max: how far the unscaled pattern reaches
};

template <typename T>
struct settings_description<radial_pattern_constants<T>> {
  using S = radial_pattern_constants<T>;
  using from = radial_pattern_settings<T>;
  static constexpr const char* name = "radial_pattern_constants";
  static constexpr bool glsl_twin = true;
  static constexpr auto fields() {
    return std::make_tuple(schema::field(&S::paths, describe_field(&from::paths)), schema::field(&S::samples_per_path, describe_field(&from::samples_per_path)),
                           schema::field(&S::min_radius, describe_field(&from::min_radius)),
                           schema::field(&S::ring_ratio, "ring_ratio", schema::at_least(1.0), "", "q = (r_max / r_min)^(1 / S): each ring's outer over inner radius"),
                           schema::field(&S::path_turns, "path_turns", schema::open_closed_range(0, 1), "turns", "1 / P: the angle between paths"),
                           schema::field(&S::path_angle, "path_angle", schema::open_closed_range(0, 6.28318530717958647692), "radians", "2 pi / P: the same, for the weights"),
                           schema::field(&S::rotation_jitter, describe_field(&from::rotation_jitter)), schema::field(&S::angle_jitter, describe_field(&from::angle_jitter)),
                           schema::field(&S::scale_jitter, describe_field(&from::scale_jitter)), schema::field(&S::seed, describe_field(&from::seed)),
                           schema::field(&S::max_radius, describe_field(&from::max_radius)));
  }
  static setting_problem rules(const S& settings) { return schema::no_rules(settings); }
};

template <typename T>
radial_pattern_constants<T> make_radial_pattern_constants(const radial_pattern_settings<T>& settings) {
  const double ratio = static_cast<double>(settings.max_radius) / static_cast<double>(settings.min_radius);
  return {settings.paths,
          settings.samples_per_path,
          settings.min_radius,
          static_cast<T>(std::pow(ratio, 1.0 / settings.samples_per_path)),
          static_cast<T>(1.0 / settings.paths),
          static_cast<T>(6.28318530717958647692 / settings.paths),
          settings.rotation_jitter,
          settings.angle_jitter,
          settings.scale_jitter,
          settings.seed,
          settings.max_radius};
}

/// The per-receiver part of the radial pattern: its hash, rotation and scale.
template <typename T>
struct radial_pixel {
  std::uint32_t hash;
  T rotation;  ///< in path spacings
  T scale;     ///< of every radius
};

/// The hash of a receiver's pixel under a pattern's seed: where each pattern's per-pixel
/// randomness starts.
inline std::uint32_t pattern_pixel_hash(std::uint32_t seed, const glm::uvec2& pixel) { return hash_combine(hash_combine(seed, pixel.x), pixel.y); }

template <typename T>
radial_pixel<T> radial_pattern_pixel(const glm::uvec2& pixel, const radial_pattern_constants<T>& constants) {
  const std::uint32_t pixel_hash = pattern_pixel_hash(constants.seed, pixel);
  const T rotation = constants.rotation_jitter * T(uniform_float_from_bits(hash_combine(pixel_hash, 0u)));
  const T scale = T(1) + constants.scale_jitter * (T(uniform_float_from_bits(hash_combine(pixel_hash, 1u))) - T(0.5));
  return {pixel_hash, rotation, scale};
}

/// Sample `sample_index` (0 = nearest) of path `path` for a receiver, given the inner radius of its
/// ring, r_min * q^sample_index (the gather keeps it as a running product along the path).
template <typename T>
pattern_sample<T> radial_pattern_sample(int path, int sample_index, T ring_inner_radius, const radial_pixel<T>& pixel,
                                        const radial_pattern_constants<T>& constants) {
  const std::uint32_t sample_hash =
      hash_combine(pixel.hash, static_cast<std::uint32_t>(2 + path * constants.samples_per_path + sample_index));
  const T angle_offset = constants.angle_jitter * (T(uniform_float_from_bits(sample_hash)) - T(0.5));
  const T radial_position = T(uniform_float_from_bits(hash_uint32(sample_hash)));
  const T ring_width = pixel.scale * (ring_inner_radius * constants.ring_ratio - ring_inner_radius);
  const T radius = pixel.scale * ring_inner_radius + radial_position * ring_width;
  const glm::vec<2, T> direction = direction_from_turns(constants.path_turns * (T(path) + pixel.rotation + angle_offset));
  return {direction * radius, constants.path_angle * radius * ring_width};
}

/// Sample `sample_index` (0 = nearest) of path `path` for the receiver at RSM pixel `pixel`: the same
/// as the two calls above (the ring radius by repeated multiplication, as the gather does).
template <typename T>
pattern_sample<T> radial_pattern_sample(int path, int sample_index, const glm::uvec2& pixel, const radial_pattern_constants<T>& constants) {
  T inner = constants.min_radius;
  for (int ring = 0; ring < sample_index; ++ring) inner *= constants.ring_ratio;
  return radial_pattern_sample(path, sample_index, inner, radial_pattern_pixel(pixel, constants), constants);
}

/// Settings of the original RSM disk pattern (defaults: 400 samples, as suggested there).
template <typename T = float>
struct disk_pattern_settings {
  int samples = 400;         ///< N (>= 1)
  T max_radius = T(64);      ///< r_max in RSM texels (> 0)
  std::uint32_t seed = 0;
  bool printed_weights = false;  ///< the original's xi1^2 weights (biased) instead of the unbiased xi1
  bool per_pixel_shift = true;   ///< each pixel shifts the pattern (rsm_disk_pixel_shift); false: the original's, the same everywhere
};

template <typename T>
struct settings_description<disk_pattern_settings<T>> {
  using S = disk_pattern_settings<T>;
  static constexpr const char* name = "disk_pattern_settings";
  static constexpr bool glsl_twin = true;
  static constexpr auto fields() {
    return std::make_tuple(schema::field(&S::samples, "samples", schema::closed_range(1, 65536), "", "N: samples of the original RSM's disk"),
                           schema::field(&S::max_radius, "max_radius", schema::above(0.0), "RSM texels", "r_max: the disk's radius"),
                           schema::field(&S::seed, "seed", schema::closed_range(0, 4294967295.0), "", "changes every sample"),
                           schema::field(&S::printed_weights, "printed_weights", schema::closed_range(0, 1), "", "the original's xi1^2 weights (biased) instead of xi1"),
                           schema::field(&S::per_pixel_shift, "per_pixel_shift", schema::closed_range(0, 1), "",
                                 "each pixel shifts the pattern (its errors independent of its neighbours'); 0: the original's fixed pattern"));
  }
  static setting_problem rules(const S& settings) { return schema::no_rules(settings); }
};

/// The pixel's shift of the disk pattern's (xi1, xi2), each in [0, 1): a hash of the pixel, or 0
/// without per_pixel_shift.
template <typename T>
glm::vec<2, T> rsm_disk_pixel_shift(const glm::uvec2& pixel, const disk_pattern_settings<T>& settings) {
  if (!settings.per_pixel_shift) return glm::vec<2, T>(0);
  // The seed is salted (with another constant than the samples' 0x5bd1e995) so that a disk and a
  // radial pattern given the same seed draw unrelated numbers, and the shift is unrelated to the
  // samples it shifts.
  const std::uint32_t pixel_hash = pattern_pixel_hash(settings.seed ^ 0x27d4eb2fu, pixel);
  return glm::vec<2, T>(T(uniform_float_from_bits(hash_combine(pixel_hash, 0u))), T(uniform_float_from_bits(hash_combine(pixel_hash, 1u))));
}

/// Sample `sample_index` of the disk pattern for a pixel whose shift is `shift` (rsm_disk_pixel_shift;
/// 0: the original's pattern, the same for every receiver).
template <typename T>
pattern_sample<T> rsm_disk_sample(int sample_index, glm::vec<2, T> shift, const disk_pattern_settings<T>& settings) {
  const std::uint32_t sample_hash = hash_combine(settings.seed ^ 0x5bd1e995u, static_cast<std::uint32_t>(sample_index));
  const T xi1 = glm::fract(T(uniform_float_from_bits(sample_hash)) + shift.x);
  const T xi2 = glm::fract(T(uniform_float_from_bits(hash_uint32(sample_hash))) + shift.y);
  const glm::vec<2, T> direction = direction_from_turns(xi2);
  const T radius = settings.max_radius * xi1;
  // (sin, cos) as printed in the RSM paper.
  const glm::vec<2, T> offset = glm::vec<2, T>(direction.y, direction.x) * radius;
  if (settings.printed_weights) {
    const T normalisation = T(3) * T(3.14159265358979323846) * settings.max_radius * settings.max_radius / T(settings.samples);
    return {offset, xi1 * xi1 * normalisation};
  }
  const T normalisation = T(2) * T(3.14159265358979323846) * settings.max_radius * settings.max_radius / T(settings.samples);
  return {offset, xi1 * normalisation};
}

}  // namespace vplkit
