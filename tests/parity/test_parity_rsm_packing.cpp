// CPU/GPU parity of include/vplkit/rsm_packing.hpp against shaders/lib/rsm_packing.glsl: the
// packed bits are identical, and the unpacked texel (normal, flux, rebuilt position) is exact:
// integer operations, exact conversions and one product per coordinate.
#include <doctest/doctest.h>

#include <random>

#include <glm/gtc/matrix_transform.hpp>

#include <vplkit/rsm_packing.hpp>

#include <vplkit/gl/settings_uniforms.hpp>
#include <vplkit/parity/doctest.hpp>

#include "tests/parity/targets.hpp"

using namespace vplkit;
using namespace vplkit::parity;

TEST_CASE("parity: pack_rsm_texel bit for bit, unpack_rsm_texel exactly, on every target") {
  std::mt19937 random(41);
  std::normal_distribution<float> normal;
  std::uniform_real_distribution<float> exponent(-12.0f, 6.0f), unit(0.0f, 1.0f);
  kernel_inputs inputs;
  inputs.width = inputs.height = 64;
  inputs.floats.assign(2, std::vector<glm::vec4>(inputs.size()));
  for (std::size_t i = 0; i < inputs.size(); ++i) {
    const glm::vec3 n = glm::normalize(glm::vec3(normal(random), normal(random), normal(random)));
    inputs.floats[0][i] = glm::vec4(n, -std::exp2(exponent(random)));  // normal | eye depth
    inputs.floats[1][i] = glm::vec4(std::exp2(exponent(random)), std::exp2(exponent(random)), unit(random), 0.0f);  // flux
  }
  inputs.floats[0][0] = glm::vec4(0.0f, 0.0f, -1.0f, -1.0f);  // an axis
  inputs.floats[1][1] = glm::vec4(0.0f);                      // no flux
  const rsm_unprojection<float> light = make_rsm_unprojection(1.1f, true, glm::ivec2(64, 64));

  kernel_source source;
  source.name = "rsm_packing";
  source.includes = {"lib/rsm_packing.glsl"};
  source.body =
      "uvec4 bits = pack_rsm_texel(fin0.w, fin0.xyz, fin1.xyz);\n"
      "rsm_texel back = unpack_rsm_texel(bits, texel, light);\n"
      "uout0 = bits;\n"
      "fout0 = vec4(back.position, 0.0);\n"
      "fout1 = vec4(back.normal, 0.0);\n"
      "fout2 = vec4(back.flux, 0.0);";
  source.float_outputs = 3;
  source.uint_outputs = 1;
  // The light's unprojection as a std140 block, which every target has.
  kernel_resources resources;
  resources.blocks = {settings_block("light", light)};
  std::vector<glm::uvec4> bits(inputs.size());
  std::vector<glm::vec4> position(inputs.size()), normal_back(inputs.size()), flux_back(inputs.size());
  for (std::size_t i = 0; i < inputs.size(); ++i) {
    bits[i] = pack_rsm_texel(inputs.floats[0][i].w, glm::vec3(inputs.floats[0][i]), glm::vec3(inputs.floats[1][i]));
    const glm::ivec2 texel(static_cast<int>(i % 64), static_cast<int>(i / 64));
    const rsm_texel<float> back = unpack_rsm_texel(bits[i], texel, light);
    position[i] = glm::vec4(back.position, 0.0f);
    normal_back[i] = glm::vec4(back.normal, 0.0f);
    flux_back[i] = glm::vec4(back.flux, 0.0f);
  }
  for (const testing::target_run& run : testing::every_target()) {
    const std::string target = run.name();
    CAPTURE(target);
    if (!testing::target_runs(run.where)) continue;
    source.name = "rsm_packing (" + target + ")";
    const kernel_outputs gpu = run.run(source, inputs, run.where, resources);
    // Integer and exact float operations only: the same bits.
    require_parity(compare_exact("pack_rsm_texel (" + target + ")", gpu.uints[0], bits, inputs));
    require_parity(compare("unpack_rsm_texel flux (" + target + ")", gpu.floats[2], flux_back, inputs, {0.0f, 0.0f, 0, 0.0, "bit shifts only: exact"}, 3));
    require_parity(compare("unpack_rsm_texel normal (" + target + ")", gpu.floats[1], normal_back, inputs,
                           {0.0f, 0.0f, 0, 0.0, "an exact conversion and one product"}, 3));
    require_parity(compare("unpack_rsm_texel position (" + target + ")", gpu.floats[0], position, inputs,
                           {1e-7f, 1e-6f, 2, 0.0, "the centre ray: a product and a sum that may fuse, then a product"}, 3));
  }
}
