// What both test programs share: the seeded inputs, the kernel run, the C++ side and the
// tolerance of the property "shaders/my/two_lights.glsl equals two_lights.hpp".
#pragma once

#include <algorithm>
#include <cstdint>
#include <vector>

#include <vplkit/parity/parity.hpp>

#include "two_lights.hpp"

namespace two_lights {

namespace parity = vplkit::parity;

// 100 x 100 = 10^4 receivers, each with two lights. Inputs: fin0 the receiver x, fin1 its normal
// n, fin2 light a's position (anywhere in [-2, 2]^3), fin3 its normal, fin4 light b's position
// at a log-uniform distance in [1e-3, 1e3] from the receiver (below, across and far above the
// 0.01 distance clamp), fin5 its normal. The first texels are edge cases: both lights on the
// receiver, zero normals, face to face, grazing, a light behind the receiver, b far away.
inline parity::kernel_inputs inputs(std::uint32_t seed) {
  const glm::vec4 up(0, 0, 1, 0), down(0, 0, -1, 0), zero(0.0f), one_up(0, 0, 1, 0);
  parity::kernel_inputs grid = parity::seeded_grid(
      100, 100, seed,
      {parity::points(2.0f), parity::unit_vectors(), parity::points(2.0f), parity::unit_vectors(), parity::unit_vectors(), parity::unit_vectors()},
      {
          {zero, up, zero, down, zero, down},                                  // both lights on the receiver
          {one_up, zero, zero, zero, zero, zero},                              // zero normals
          {one_up, down, zero, up, glm::vec4(0, 0, 2, 0), down},               // face to face, b behind the receiver
          {glm::vec4(1, 0, 0, 0), glm::vec4(-1, 0, 0, 0), zero, up, zero, up},  // grazing
          {one_up, down, zero, up, glm::vec4(0, 0, -1e3f, 0), up},             // b far below a
      });
  // fin4 holds a direction so far; place b along it at a log-uniform distance from the receiver.
  parity::random_inputs random(seed + 1);
  for (std::size_t i = 5; i < grid.size(); ++i)
    grid.floats[4][i] = grid.floats[0][i] + grid.floats[4][i] * random.log_uniform(1e-3f, 1e3f);
  return grid;
}

inline parity::kernel_source kernel() {
  parity::kernel_source source;
  source.name = "two_lights_irradiance";
  source.includes = {"my/two_lights.glsl"};
  source.declarations = "uniform irradiance_settings settings;\nuniform vec3 flux;\n";
  source.body = "fout0 = vec4(two_lights_irradiance(fin0.xyz, fin1.xyz, fin2.xyz, fin3.xyz, fin4.xyz, fin5.xyz, flux, settings), 0.0);";
  source.float_outputs = 1;
  return source;
}

inline const glm::vec3 flux(1.0f, 0.25f, 3.0f);
inline const vplkit::irradiance_settings<float> settings{0.01f};

// The same kernel in a form every target runs (vplkit::parity::target): the settings in a std140
// uniform block (settings_block, from vplkit/std140.hpp; a uniform buffer on Vulkan, which has no
// default-block uniforms) and the flux a constant, exact in GLSL as in C++.
inline parity::kernel_source kernel_on_targets() {
  parity::kernel_source source = kernel();
  source.declarations = "const vec3 flux = vec3(1.0, 0.25, 3.0);\n";
  return source;
}

inline parity::kernel_resources resources_on_targets() {
  parity::kernel_resources resources;
  resources.blocks = {parity::settings_block("settings", settings)};
  return resources;
}

inline parity::uniform_setter uniforms() {
  return [](const parity::program& p) {
    parity::set_uniforms(p, "settings", settings);
    p.set("flux", flux);
  };
}

inline std::vector<glm::vec4> on_cpu(const parity::kernel_inputs& in) {
  std::vector<glm::vec4> out(in.size());
  for (std::size_t i = 0; i < in.size(); ++i) {
    auto v = [&](int input) { return glm::vec3(in.floats[static_cast<std::size_t>(input)][i]); };
    out[i] = glm::vec4(two_lights_irradiance(v(0), v(1), v(2), v(3), v(4), v(5), flux, settings), 0.0f);
  }
  return out;
}

// The rounding error of each texel, in the units the tolerance's max_abs counts. A term of Eq. 3.2
// is flux * (emit / d^2) * (receive / d^2), d = max(|x - x_p|, min_distance), emit and receive
// the dot products of a unit normal with x - x_p. Where a dot product cancels (a light near the
// tangent plane) its absolute error is some eps * d whatever its value, so the term's absolute
// error is some eps * |flux| / d^2 however small the term itself: error scale
// s = |flux| (1 / d_a^2 + 1 / d_b^2) per channel.
inline std::vector<glm::vec4> error_scales(const parity::kernel_inputs& in) {
  std::vector<glm::vec4> scales(in.size());
  const double min_distance_squared = static_cast<double>(settings.min_distance) * static_cast<double>(settings.min_distance);
  for (std::size_t i = 0; i < in.size(); ++i) {
    const glm::dvec3 x(in.floats[0][i]), xa(in.floats[2][i]), xb(in.floats[4][i]);
    const double inverse_squares = 1.0 / std::max(glm::dot(x - xa, x - xa), min_distance_squared) +
                                   1.0 / std::max(glm::dot(x - xb, x - xb), min_distance_squared);
    scales[i] = glm::vec4(glm::dvec4(glm::abs(glm::dvec3(flux)) * inverse_squares, 1.0));
  }
  return scales;
}

// Counting roundings in units of that scale: x - x_p one per component, a dot product three
// products and two sums (with the first, at most ~7 eps * d for a unit normal), the clamp's d^2
// three more, each divide and product one: at most ~25 eps per side (eps = 2^-23), and the GPU
// may fuse a multiply-add where C++ rounds twice. Both sides within 25 eps of the exact value: they
// differ by at most 50 eps = 6e-6 of the scale. A 0.1 % error is far larger wherever the result
// is more than 1 % of its scale (both cosines above ~0.1).
inline parity::tolerance tolerance(const parity::kernel_inputs& in) {
  return {6e-6f, 0.0f, 0, 0.0, "two terms of Eq. 3.2: 50 eps of |flux| (1/d_a^2 + 1/d_b^2), cancelling dot products included", error_scales(in)};
}

inline parity::comparison compare(const std::vector<glm::vec4>& gpu, const parity::kernel_inputs& in) {
  return parity::compare("two_lights_irradiance", gpu, on_cpu(in), in, tolerance(in), 3);
}

}  // namespace two_lights
