// CPU/GPU parity of the first kernels: each GLSL twin in shaders/lib/ against the C++ float
// instantiation, texel by texel, on random inputs (fixed seeds) plus the edge cases.
#include <doctest/doctest.h>

#include <array>
#include <cstring>
#include <random>

#include <vplkit/direct_light.hpp>
#include <vplkit/hash.hpp>
#include <vplkit/irradiance.hpp>
#include <vplkit/micro_linear_buffer.hpp>

#include "frontend/gl/settings_uniforms.hpp"
#include "tests/parity/parity_harness.hpp"

using namespace vplkit;
using namespace vplkit::parity;

namespace {

constexpr int grid = 64;  // 4096 texels per kernel

glm::vec4 random_point(std::mt19937& random, float extent) {
  std::uniform_real_distribution<float> uniform(-extent, extent);
  return {uniform(random), uniform(random), uniform(random), 0.0f};
}

glm::vec4 random_unit(std::mt19937& random) {
  std::normal_distribution<float> normal(0.0f, 1.0f);
  return glm::vec4(glm::normalize(glm::vec3(normal(random), normal(random), normal(random))), 0.0f);
}

// Four vec3 inputs per texel (x, n, xp, np): random, with edge cases in the first rows.
kernel_inputs geometry_inputs(unsigned seed) {
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

kernel_source irradiance_kernel() {
  kernel_source source;
  source.name = "pixel_light_irradiance";
  source.includes = {"lib/irradiance.glsl"};
  source.declarations = "uniform irradiance_settings settings;\nuniform vec3 flux;\n";
  source.body = "fout0 = vec4(pixel_light_irradiance(fin0.xyz, fin1.xyz, fin2.xyz, fin3.xyz, flux, settings), 0.0);";
  source.float_outputs = 1;
  return source;
}

std::vector<glm::vec4> irradiance_on_cpu(const kernel_inputs& inputs, const glm::vec3& flux, const irradiance_settings<float>& settings) {
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
tolerance irradiance_tolerance() {
  return {1e-6f, 1e-5f, 16, 0.0, "about 8 roundings, FMA contraction on llvmpipe, cancellation near tangency"};
}

}  // namespace

TEST_CASE("parity: hash_uint32, hash_combine and uniform_float_from_bits are bit-identical") {
  std::mt19937 random(7);
  kernel_inputs inputs;
  inputs.width = grid;
  inputs.height = grid;
  inputs.uints.assign(1, std::vector<glm::uvec4>(inputs.size()));
  for (std::size_t i = 0; i < inputs.size(); ++i) {
    const auto index = static_cast<std::uint32_t>(i);
    // x: consecutive values and the extremes, y/z: random words.
    inputs.uints[0][i] = glm::uvec4(index == 1 ? 0xffffffffu : index, random(), random(), 0u);
  }
  kernel_source source;
  source.name = "hash";
  source.includes = {"lib/hash.glsl"};
  source.body =
      "uout0 = uvec4(hash_uint32(uin0.x), hash_uint32(uin0.y), hash_combine(uin0.y, uin0.z),\n"
      "              floatBitsToUint(uniform_float_from_bits(hash_uint32(uin0.z))));";
  source.uint_outputs = 1;
  const kernel_outputs gpu = run_fragment(source, inputs);
  std::vector<glm::uvec4> cpu(inputs.size());
  for (std::size_t i = 0; i < inputs.size(); ++i) {
    const glm::uvec4& in = inputs.uints[0][i];
    const float u = uniform_float_from_bits(hash_uint32(in.z));
    std::uint32_t u_bits;
    std::memcpy(&u_bits, &u, sizeof u_bits);
    cpu[i] = glm::uvec4(hash_uint32(in.x), hash_uint32(in.y), hash_combine(in.y, in.z), u_bits);
  }
  require_parity(compare_exact("hash (exact)", gpu.uints[0], cpu, inputs));
}

TEST_CASE("parity: pixel_light_irradiance (Eq. 3.2) in the fragment stage") {
  const kernel_inputs inputs = geometry_inputs(8);
  const glm::vec3 flux(1.0f, 0.25f, 3.0f);
  const irradiance_settings<float> settings{0.01f};
  const kernel_outputs gpu = run_fragment(irradiance_kernel(), inputs, [&](const program& p) {
    set_uniforms(p, "settings", settings);
    p.set("flux", flux);
  });
  require_parity(compare("pixel_light_irradiance", gpu.floats[0], irradiance_on_cpu(inputs, flux, settings), inputs,
                         irradiance_tolerance(), 3));
}

TEST_CASE("parity: pixel_light_irradiance (Eq. 3.2) in the vertex stage, through transform feedback") {
  const kernel_inputs inputs = geometry_inputs(9);
  const glm::vec3 flux(2.0f, 1.0f, 0.5f);
  const irradiance_settings<float> settings{0.05f};
  const kernel_outputs gpu = run_vertex(irradiance_kernel(), inputs, [&](const program& p) {
    set_uniforms(p, "settings", settings);
    p.set("flux", flux);
  });
  require_parity(compare("pixel_light_irradiance (vertex)", gpu.floats[0], irradiance_on_cpu(inputs, flux, settings), inputs,
                         irradiance_tolerance(), 3));
}

TEST_CASE("parity: spot_light_irradiance") {
  const kernel_inputs inputs = geometry_inputs(10);  // x, n used; the light is a uniform
  spot_light<float> light;
  light.position = {0.2f, 1.9f, -0.1f};
  light.direction = glm::normalize(glm::vec3(0.1f, -1.0f, 0.05f));
  light.intensity = {6.0f, 5.0f, 4.0f};
  light.cos_inner = 0.6f;
  light.cos_outer = 0.3f;
  const irradiance_settings<float> settings{0.01f};
  kernel_source source;
  source.name = "spot_light_irradiance";
  source.includes = {"lib/direct_light.glsl"};
  source.declarations = "uniform spot_light light;\nuniform irradiance_settings settings;\n";
  source.body = "fout0 = vec4(spot_light_irradiance(fin0.xyz, fin1.xyz, light, settings), 0.0);";
  source.float_outputs = 1;
  const kernel_outputs gpu = run_fragment(source, inputs, [&](const program& p) {
    set_uniforms(p, "light", light);
    set_uniforms(p, "settings", settings);
  });
  std::vector<glm::vec4> cpu(inputs.size());
  for (std::size_t i = 0; i < inputs.size(); ++i)
    cpu[i] = glm::vec4(spot_light_irradiance(glm::vec3(inputs.floats[0][i]), glm::vec3(inputs.floats[1][i]), light, settings), 0.0f);
  // A sqrt, a divide per component, two dot products, the smoothstep polynomial: ~15 roundings,
  // and the smoothstep input (cos_axis - cos_outer) cancels near the outer cone edge, where the
  // result itself is near 0: 32 ulp, 1e-5 relative or 1e-6 absolute.
  require_parity(compare("spot_light_irradiance", gpu.floats[0], cpu, inputs,
                         {1e-6f, 1e-5f, 32, 0.0, "~15 roundings; cancellation at the cone edge where the result is ~0"}, 3));
}

TEST_CASE("parity: elevation_bucket makes the same decision on both sides, boundaries included") {
  std::mt19937 random(11);
  kernel_inputs inputs;
  inputs.width = grid;
  inputs.height = grid;
  inputs.floats.assign(2, std::vector<glm::vec4>(inputs.size()));
  const int slots = 5;
  const elevation_slots<float> table = make_elevation_slots<float>(slots);
  std::uniform_real_distribution<float> uniform(-2.0f, 2.0f);
  for (std::size_t i = 0; i < inputs.size(); ++i) {
    inputs.floats[0][i] = random_point(random, 2.0f);
    inputs.floats[1][i] = random_point(random, 2.0f);
    if (i % 4 == 0) {
      // Exactly on a boundary: dz = tangent * |dxy| computed in float as the kernel does.
      const glm::vec3 x(inputs.floats[0][i]);
      const float dx = uniform(random), dy = uniform(random);
      const float horizontal = std::sqrt(dx * dx + dy * dy);
      const float tangent = table.boundary_tangent[static_cast<std::size_t>(i / 4) % (slots - 1)];
      inputs.floats[1][i] = glm::vec4(x.x + dx, x.y + dy, x.z + tangent * horizontal, 0.0f);
    }
  }
  inputs.floats[0][1] = inputs.floats[1][1] = glm::vec4(0.5f);  // coincident
  kernel_source source;
  source.name = "elevation_bucket";
  source.includes = {"lib/micro_linear_buffer.glsl"};
  source.declarations = "uniform elevation_slots slots;\n";
  source.body = "uout0 = uvec4(uint(elevation_bucket(fin0.xyz, fin1.xyz, slots)), 0u, 0u, 0u);";
  source.uint_outputs = 1;
  const kernel_outputs gpu = run_fragment(source, inputs, [&](const program& p) { set_uniforms(p, "slots", table); });
  std::vector<glm::uvec4> cpu(inputs.size());
  for (std::size_t i = 0; i < inputs.size(); ++i)
    cpu[i] = glm::uvec4(static_cast<unsigned>(elevation_bucket(glm::vec3(inputs.floats[0][i]), glm::vec3(inputs.floats[1][i]), table)), 0u, 0u, 0u);
  // Subtractions, multiplies, one add, sqrt and compares are IEEE-exact on both sides, and the
  // tangents are the same floats: no flip is allowed, even on the boundaries.
  require_parity(compare_exact("elevation_bucket (exact)", gpu.uints[0], cpu, inputs, 0.0, 1));
}

TEST_CASE("parity: micro_linear_buffer Alg. 2, 3 and 6 verdicts on random slot sequences") {
  // Each texel holds a path of 10 slot indices (4 bits each, packed into two words) and a slot
  // count; the outputs are the verdict bit masks of the three algorithms, and the sum of the
  // unclamped Alg. 6 values (which exercises the decrements).
  std::mt19937 random(12);
  kernel_inputs inputs;
  inputs.width = grid;
  inputs.height = grid;
  inputs.uints.assign(1, std::vector<glm::uvec4>(inputs.size()));
  for (std::size_t i = 0; i < inputs.size(); ++i) {
    const unsigned slots = 1u + static_cast<unsigned>(i % micro_linear_buffer_max_slots);
    std::uniform_int_distribution<unsigned> pick(0, slots - 1);
    glm::uvec4 packed(0u, 0u, slots, 0u);
    for (unsigned sample = 0; sample < 10; ++sample) {
      const unsigned index = pick(random);
      if (sample < 5) packed.x |= index << (4 * sample);
      else packed.y |= index << (4 * (sample - 5));
    }
    inputs.uints[0][i] = packed;
  }
  kernel_source source;
  source.name = "micro_linear_buffer";
  source.includes = {"lib/micro_linear_buffer.glsl"};
  source.body = R"(
    int slots = int(uin0.z);
    micro_linear_buffer alg2; micro_linear_buffer alg3; micro_linear_buffer alg6;
    micro_linear_buffer_reset(alg2, slots);
    micro_linear_buffer_reset(alg3, slots);
    micro_linear_buffer_reset(alg6, slots);
    uint mask2 = 0u, mask3 = 0u, mask6 = 0u;
    float sum6 = 0.0;
    for (int sample = 0; sample < 10; ++sample) {
      uint word = sample < 5 ? uin0.x : uin0.y;
      int index = int((word >> uint(4 * (sample % 5))) & 15u);
      if (micro_linear_buffer_alg2(alg2, index) > 0.5) mask2 |= 1u << uint(sample);
      if (micro_linear_buffer_alg3(alg3, index) > 0.5) mask3 |= 1u << uint(sample);
      float nu = micro_linear_buffer_alg6(alg6, index);
      sum6 += nu;
      if (clamp(nu, 0.0, 1.0) > 0.5) mask6 |= 1u << uint(sample);
    }
    uout0 = uvec4(mask2, mask3, mask6, floatBitsToUint(sum6));)";
  source.uint_outputs = 1;
  const kernel_outputs gpu = run_fragment(source, inputs);
  std::vector<glm::uvec4> cpu(inputs.size());
  for (std::size_t i = 0; i < inputs.size(); ++i) {
    const glm::uvec4& in = inputs.uints[0][i];
    const int slots = static_cast<int>(in.z);
    micro_linear_buffer<float> alg2, alg3, alg6;
    micro_linear_buffer_reset(alg2, slots);
    micro_linear_buffer_reset(alg3, slots);
    micro_linear_buffer_reset(alg6, slots);
    unsigned mask2 = 0, mask3 = 0, mask6 = 0;
    float sum6 = 0.0f;
    for (int sample = 0; sample < 10; ++sample) {
      const unsigned word = sample < 5 ? in.x : in.y;
      const int index = static_cast<int>((word >> (4 * (sample % 5))) & 15u);
      if (micro_linear_buffer_alg2(alg2, index) > 0.5f) mask2 |= 1u << sample;
      if (micro_linear_buffer_alg3(alg3, index) > 0.5f) mask3 |= 1u << sample;
      const float nu = micro_linear_buffer_alg6(alg6, index);
      sum6 += nu;
      if (glm::clamp(nu, 0.0f, 1.0f) > 0.5f) mask6 |= 1u << sample;
    }
    std::uint32_t sum_bits;
    std::memcpy(&sum_bits, &sum6, sizeof sum_bits);
    cpu[i] = glm::uvec4(mask2, mask3, mask6, sum_bits);
  }
  // Small integers in float: every operation is exact, so everything must match to the bit.
  require_parity(compare_exact("micro_linear_buffer (exact)", gpu.uints[0], cpu, inputs));
  // And on the GPU too, Alg. 6 agrees with Alg. 3.
  std::size_t alg6_differs = 0;
  for (const glm::uvec4& out : gpu.uints[0]) alg6_differs += out.y != out.z;
  CHECK(alg6_differs == 0);
}
