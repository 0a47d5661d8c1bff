// Inputs shared by the kernel parity tests: random points and unit vectors, the geometry grid
// (x, n, x_p, n_p with edge cases in the first rows), a blank grid, and the pixel-light
// irradiance kernel run on both sides.
#pragma once

#include <random>
#include <vector>

#include <vplkit/irradiance.hpp>

#include "frontend/gl/settings_uniforms.hpp"
#include "tests/parity/parity_harness.hpp"

namespace vplkit::parity {


constexpr int grid = 64;  // 4096 texels per kernel

inline glm::vec4 random_point(std::mt19937& random, float extent) {
  std::uniform_real_distribution<float> uniform(-extent, extent);
  return {uniform(random), uniform(random), uniform(random), 0.0f};
}

inline glm::vec4 random_unit(std::mt19937& random) {
  std::normal_distribution<float> normal(0.0f, 1.0f);
  return glm::vec4(glm::normalize(glm::vec3(normal(random), normal(random), normal(random))), 0.0f);
}

// Four vec3 inputs per texel (x, n, xp, np): random, with edge cases in the first rows.
inline kernel_inputs geometry_inputs(unsigned seed) {
  std::mt19937 random(seed);
  kernel_inputs inputs;
  inputs.width = grid;
  inputs.height = grid;
  inputs.floats.assign(4, std::vector<glm::vec4>(inputs.size()));
  for (std::size_t i = 0; i < inputs.size(); ++i) {
    inputs.floats[0][i] = random_point(random, 2.0f);
    inputs.floats[1][i] = random_unit(random);
    inputs.floats[2][i] = random_point(random, 2.0f);
    inputs.floats[3][i] = random_unit(random);
  }
  const glm::vec4 up(0, 0, 1, 0), down(0, 0, -1, 0), zero(0.0f);
  const std::vector<std::array<glm::vec4, 4>> edge_cases = {
      {zero, up, zero, down},                                                // coincident points
      {glm::vec4(0, 0, 1, 0), zero, zero, zero},                             // zero normals
      {glm::vec4(0, 0, 1, 0), down, zero, up},                               // face to face
      {glm::vec4(1, 0, 0, 0), glm::vec4(-1, 0, 0, 0), zero, up},             // grazing: tangent to the light
      {glm::vec4(1, 0, 1e-4f, 0), glm::vec4(-1, 0, 0, 0), zero, up},         // nearly grazing
      {glm::vec4(0, 0, 1e-7f, 0), down, zero, up},                           // tiny distance (clamped)
      {glm::vec4(0, 0, 1e-3f, 0), down, zero, up},                           // below min_distance
      {glm::vec4(0, 0, 1e6f, 0), down, zero, up},                            // huge distance
      {glm::vec4(3e18f, 0, 3e18f, 0), down, zero, up},                       // d^4 overflows
      {glm::vec4(0, 0, -1, 0), up, zero, up},                                // behind the light
  };
  for (std::size_t i = 0; i < edge_cases.size(); ++i)
    for (int k = 0; k < 4; ++k) inputs.floats[static_cast<std::size_t>(k)][i] = edge_cases[i][static_cast<std::size_t>(k)];
  return inputs;
}

inline kernel_source irradiance_kernel() {
  kernel_source source;
  source.name = "pixel_light_irradiance";
  source.includes = {"lib/irradiance.glsl"};
  source.declarations = "uniform irradiance_settings settings;\nuniform vec3 flux;\n";
  source.body = "fout0 = vec4(pixel_light_irradiance(fin0.xyz, fin1.xyz, fin2.xyz, fin3.xyz, flux, settings), 0.0);";
  source.float_outputs = 1;
  return source;
}

inline std::vector<glm::vec4> irradiance_on_cpu(const kernel_inputs& inputs, const glm::vec3& flux, const irradiance_settings<float>& settings) {
  std::vector<glm::vec4> out(inputs.size());
  for (std::size_t i = 0; i < inputs.size(); ++i)
    out[i] = glm::vec4(pixel_light_irradiance(glm::vec3(inputs.floats[0][i]), glm::vec3(inputs.floats[1][i]),
                                              glm::vec3(inputs.floats[2][i]), glm::vec3(inputs.floats[3][i]), flux, settings),
                       0.0f);
  return out;
}

// Eq. 3.2 is two dot products (3 multiplies, 2 adds each), a max, two divides and a product:
// about 8 roundings. llvmpipe may contract a multiply-add into an FMA (one rounding fewer)
// where the C++ build does not, and near-tangent configurations cancel in the dot products, so
// the relative error of a tiny result is unbounded while its absolute error stays at float
// precision of the unclamped term: pass at 16 ulp, 1e-5 relative, or 1e-6 absolute (results
// here are O(1) to O(1e4): the scale is 1 / min_distance^2 = 1e4 at most).
inline tolerance irradiance_tolerance() {
  return {1e-6f, 1e-5f, 16, 0.0, "about 8 roundings, FMA contraction on llvmpipe, cancellation near tangency"};
}



inline kernel_inputs grid_of(int width, int height, int float_inputs, int uint_inputs = 0) {
  kernel_inputs inputs;
  inputs.width = width;
  inputs.height = height;
  inputs.floats.assign(static_cast<std::size_t>(float_inputs), std::vector<glm::vec4>(inputs.size()));
  inputs.uints.assign(static_cast<std::size_t>(uint_inputs), std::vector<glm::uvec4>(inputs.size()));
  return inputs;
}


}  // namespace vplkit::parity
