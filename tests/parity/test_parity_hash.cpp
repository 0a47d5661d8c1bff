// CPU/GPU parity of include/vplkit/hash.hpp against shaders/lib/hash.glsl: hash_uint32, hash_combine and uniform_float_from_bits, texel by
// texel (vplkit/parity/parity.hpp).
#include <doctest/doctest.h>

#include <array>
#include <cstring>
#include <random>

#include <glm/gtc/matrix_transform.hpp>

#include <vplkit/hash.hpp>

#include <vplkit/gl/settings_uniforms.hpp>
#include <vplkit/parity/doctest.hpp>

#include "tests/parity/targets.hpp"

using namespace vplkit;
using namespace vplkit::parity;

TEST_CASE("parity: hash_uint32, hash_combine and uniform_float_from_bits are bit-identical, on every target") {
  random_inputs random(7);
  kernel_inputs inputs = grid_of(64, 64, 0, 1);
  for (std::size_t i = 0; i < inputs.size(); ++i) {
    const auto index = static_cast<std::uint32_t>(i);
    // x: consecutive values and the extremes, y/z: random words.
    const std::uint32_t y = random.bits();
    inputs.uints[0][i] = glm::uvec4(index == 1 ? 0xffffffffu : index, y, random.bits(), 0u);
  }
  kernel_source source;
  source.name = "hash";
  source.includes = {"lib/hash.glsl"};
  source.body =
      "uout0 = uvec4(hash_uint32(uin0.x), hash_uint32(uin0.y), hash_combine(uin0.y, uin0.z),\n"
      "              floatBitsToUint(uniform_float_from_bits(hash_uint32(uin0.z))));";
  source.uint_outputs = 1;
  std::vector<glm::uvec4> cpu(inputs.size());
  for (std::size_t i = 0; i < inputs.size(); ++i) {
    const glm::uvec4& in = inputs.uints[0][i];
    const float u = uniform_float_from_bits(hash_uint32(in.z));
    std::uint32_t u_bits;
    std::memcpy(&u_bits, &u, sizeof u_bits);
    cpu[i] = glm::uvec4(hash_uint32(in.x), hash_uint32(in.y), hash_combine(in.y, in.z), u_bits);
  }
  for (const testing::target_run& run : testing::every_target()) {
    const std::string target = run.name();
    CAPTURE(target);
    if (!testing::target_runs(run.where)) continue;
    source.name = std::string("hash") + " (" + target + ")";
    const kernel_outputs gpu = run.run(source, inputs, run.where, {});
    require_parity(compare_exact(source.name + " (exact)", gpu.uints[0], cpu, inputs));
  }
}
