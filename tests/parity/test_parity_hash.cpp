// CPU/GPU parity of include/vplkit/hash.hpp against shaders/lib/hash.glsl: hash_uint32, hash_combine and uniform_float_from_bits, texel by
// texel (tests/parity/parity_harness.hpp).
#include <doctest/doctest.h>

#include <array>
#include <cstring>
#include <random>

#include <glm/gtc/matrix_transform.hpp>

#include <vplkit/hash.hpp>

#include "frontend/gl/settings_uniforms.hpp"
#include "tests/parity/parity_harness.hpp"
#include "tests/parity/parity_inputs.hpp"

using namespace vplkit;
using namespace vplkit::parity;

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
