// The inputs of a parity run (vplkit/parity/parity.hpp) and seeded generators for them: uniform
// and log-uniform numbers, unit vectors, points, special float values, and grids whose first
// texels are edge cases. GLM and the standard library only.
//
// The same seed gives the same inputs with every compiler and standard library, so a failure
// seen on one machine is reproduced on another: the engine is std::mt19937, whose output the
// standard fixes, and the conversions to floats are written out here (the standard leaves
// std::uniform_real_distribution's and std::normal_distribution's to each library).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace vplkit::parity {

/// The inputs of one run: a width x height grid, texel (x, y) at index y * width + x. Each input
/// holds one value per texel; a kernel's GLSL body reads float input i as `fin<i>` (vec4) and
/// uint input i as `uin<i>` (uvec4).
struct kernel_inputs {
  int width = 0;   ///< grid width (the vertex stage runs width * height vertices)
  int height = 0;
  std::vector<std::vector<glm::vec4>> floats;   ///< each width * height long
  std::vector<std::vector<glm::uvec4>> uints;   ///< each width * height long
  std::size_t size() const { return static_cast<std::size_t>(width) * static_cast<std::size_t>(height); }
};

/// A width x height grid with `float_inputs` vec4 and `uint_inputs` uvec4 inputs, all zero. With
/// no inputs it is the grid of a whole image compared texel by texel (a pass against its CPU
/// mirror): compare() then reports coordinates only.
inline kernel_inputs grid_of(int width, int height, int float_inputs, int uint_inputs = 0) {
  if (width < 1 || height < 1 || float_inputs < 0 || uint_inputs < 0)
    throw std::invalid_argument("vplkit::parity::grid_of: the grid must be at least 1x1 with no negative input count, got " +
                                std::to_string(width) + "x" + std::to_string(height));
  kernel_inputs inputs;
  inputs.width = width;
  inputs.height = height;
  inputs.floats.assign(static_cast<std::size_t>(float_inputs), std::vector<glm::vec4>(inputs.size()));
  inputs.uints.assign(static_cast<std::size_t>(uint_inputs), std::vector<glm::uvec4>(inputs.size()));
  return inputs;
}

/// Seeded random numbers for test inputs, the same sequence on every platform.
class random_inputs {
 public:
  explicit random_inputs(std::uint32_t seed) : engine_(seed) {}

  /// 32 random bits (one draw of the engine).
  std::uint32_t bits() { return static_cast<std::uint32_t>(engine_()); }

  /// Uniform in [0, 1): the top 24 bits of one draw, k / 2^24, each exactly a float.
  float unit_interval() { return static_cast<float>(bits() >> 8) * (1.0f / 16777216.0f); }

  /// Uniform in [low, high] (low <= high, both finite).
  float uniform(float low, float high) {
    if (!(low <= high) || !std::isfinite(low) || !std::isfinite(high))
      throw std::invalid_argument("vplkit::parity::random_inputs::uniform needs finite low <= high");
    const double value = static_cast<double>(low) + (static_cast<double>(high) - static_cast<double>(low)) * static_cast<double>(unit_interval());
    return clamp_to(static_cast<float>(value), low, high);
  }

  /// Log-uniform in [low, high] (0 < low <= high): every factor of ten between them equally
  /// likely, for inputs that span magnitudes (distances, intensities, roughness near 0).
  float log_uniform(float low, float high) {
    if (!(low > 0.0f) || !(low <= high) || !std::isfinite(high))
      throw std::invalid_argument("vplkit::parity::random_inputs::log_uniform needs 0 < low <= high, both finite");
    const double log_low = std::log(static_cast<double>(low)), log_high = std::log(static_cast<double>(high));
    return clamp_to(static_cast<float>(std::exp(log_low + (log_high - log_low) * static_cast<double>(unit_interval()))), low, high);
  }

  /// A uniform integer in [low, high] (no modulo bias: draws outside the largest multiple of the
  /// range are rejected).
  std::uint32_t uniform_uint(std::uint32_t low, std::uint32_t high) {
    if (low > high) throw std::invalid_argument("vplkit::parity::random_inputs::uniform_uint needs low <= high");
    const std::uint64_t range = static_cast<std::uint64_t>(high) - low + 1;
    const std::uint64_t limit = (std::uint64_t{1} << 32) - (std::uint64_t{1} << 32) % range;
    std::uint64_t draw = bits();
    while (draw >= limit) draw = bits();
    return low + static_cast<std::uint32_t>(draw % range);
  }

  /// A unit vector uniform on the sphere: z uniform in [-1, 1] and the azimuth uniform
  /// (Archimedes' hat-box theorem), computed in double; its length is 1 within float rounding.
  glm::vec3 unit_vector() {
    const double z = 2.0 * static_cast<double>(unit_interval()) - 1.0;
    const double azimuth = 6.283185307179586476925 * static_cast<double>(unit_interval());
    const double radius = std::sqrt(std::max(0.0, 1.0 - z * z));
    return glm::vec3(static_cast<float>(radius * std::cos(azimuth)), static_cast<float>(radius * std::sin(azimuth)), static_cast<float>(z));
  }

  /// A point with each coordinate uniform in [-extent, extent].
  glm::vec3 point(float extent) {
    const float x = uniform(-extent, extent);
    const float y = uniform(-extent, extent);
    return glm::vec3(x, y, uniform(-extent, extent));
  }

  /// The engine, for distributions of one's own.
  std::mt19937& engine() { return engine_; }

 private:
  static float clamp_to(float value, float low, float high) { return value < low ? low : (value > high ? high : value); }
  std::mt19937 engine_;
};

/// Finite float values where arithmetic goes wrong, each with both signs: zero, the smallest
/// subnormal, the smallest normal, machine epsilon, the floats either side of 1, 1, 1e-20 and 1e20
/// (whose squares underflow and overflow), and the largest float.
inline std::vector<float> special_values() {
  using limits = std::numeric_limits<float>;
  const std::vector<float> magnitudes = {0.0f, limits::denorm_min(), limits::min(), limits::epsilon(), 1e-20f,
                                         std::nextafter(1.0f, 0.0f), 1.0f, std::nextafter(1.0f, 2.0f), 1e20f, limits::max()};
  std::vector<float> values;
  for (float magnitude : magnitudes) {
    values.push_back(magnitude);
    values.push_back(-magnitude);
  }
  return values;
}

/// Draws one texel's value of one float input.
using float_generator = std::function<glm::vec4(random_inputs&)>;

/// Points with coordinates uniform in [-extent, extent] (w = 0).
inline float_generator points(float extent) {
  return [extent](random_inputs& random) { return glm::vec4(random.point(extent), 0.0f); };
}
/// Unit vectors uniform on the sphere (w = 0).
inline float_generator unit_vectors() {
  return [](random_inputs& random) { return glm::vec4(random.unit_vector(), 0.0f); };
}
/// Four independent values uniform in [low, high].
inline float_generator uniform_values(float low, float high) {
  return [low, high](random_inputs& random) {
    glm::vec4 value;
    for (int c = 0; c < 4; ++c) value[c] = random.uniform(low, high);
    return value;
  };
}
/// Four independent values log-uniform in [low, high] (0 < low).
inline float_generator log_uniform_values(float low, float high) {
  return [low, high](random_inputs& random) {
    glm::vec4 value;
    for (int c = 0; c < 4; ++c) value[c] = random.log_uniform(low, high);
    return value;
  };
}

/// A width x height grid with one float input per generator, drawn texel by texel (texel 0's
/// inputs 0, 1, ..., then texel 1's) from random_inputs(seed); then the first texels are replaced
/// by `edge_cases`, each one texel's values (one vec4 per input), so that a test always meets
/// them and a failure among them is easy to find (texels (0, 0), (1, 0), ...). Throws
/// std::invalid_argument when an edge case has the wrong number of values or there are more edge
/// cases than texels.
inline kernel_inputs seeded_grid(int width, int height, std::uint32_t seed, const std::vector<float_generator>& generators,
                                 const std::vector<std::vector<glm::vec4>>& edge_cases = {}) {
  kernel_inputs inputs = grid_of(width, height, static_cast<int>(generators.size()));
  if (edge_cases.size() > inputs.size())
    throw std::invalid_argument("vplkit::parity::seeded_grid: " + std::to_string(edge_cases.size()) + " edge cases do not fit in " +
                                std::to_string(inputs.size()) + " texels");
  random_inputs random(seed);
  for (std::size_t texel = 0; texel < inputs.size(); ++texel)
    for (std::size_t input = 0; input < generators.size(); ++input) inputs.floats[input][texel] = generators[input](random);
  for (std::size_t texel = 0; texel < edge_cases.size(); ++texel) {
    if (edge_cases[texel].size() != generators.size())
      throw std::invalid_argument("vplkit::parity::seeded_grid: edge case " + std::to_string(texel) + " has " +
                                  std::to_string(edge_cases[texel].size()) + " values for " + std::to_string(generators.size()) + " inputs");
    for (std::size_t input = 0; input < generators.size(); ++input) inputs.floats[input][texel] = edge_cases[texel][input];
  }
  return inputs;
}

/// Pairs of oriented points for kernels between a receiver and a light (irradiance, form
/// factors): inputs x, n, x_p, n_p (points in [-2, 2]^3 and unit normals), with the classic edge
/// cases first: coincident points, zero normals, face to face, grazing and nearly grazing,
/// distances below and far above a clamp, a distance whose fourth power overflows, a receiver
/// behind the light.
inline kernel_inputs geometry_inputs(std::uint32_t seed, int width = 64, int height = 64) {
  const glm::vec4 up(0, 0, 1, 0), down(0, 0, -1, 0), zero(0.0f);
  return seeded_grid(width, height, seed, {points(2.0f), unit_vectors(), points(2.0f), unit_vectors()},
                     {
                         {zero, up, zero, down},                                         // coincident points
                         {glm::vec4(0, 0, 1, 0), zero, zero, zero},                      // zero normals
                         {glm::vec4(0, 0, 1, 0), down, zero, up},                        // face to face
                         {glm::vec4(1, 0, 0, 0), glm::vec4(-1, 0, 0, 0), zero, up},      // grazing: tangent to the light
                         {glm::vec4(1, 0, 1e-4f, 0), glm::vec4(-1, 0, 0, 0), zero, up},  // nearly grazing
                         {glm::vec4(0, 0, 1e-7f, 0), down, zero, up},                    // tiny distance (clamped)
                         {glm::vec4(0, 0, 1e-3f, 0), down, zero, up},                    // below a 0.01 clamp
                         {glm::vec4(0, 0, 1e6f, 0), down, zero, up},                     // huge distance
                         {glm::vec4(3e18f, 0, 3e18f, 0), down, zero, up},                // d^4 overflows
                         {glm::vec4(0, 0, -1, 0), up, zero, up},                         // behind the light
                     });
}

}  // namespace vplkit::parity
