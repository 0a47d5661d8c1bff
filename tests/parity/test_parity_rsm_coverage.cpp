// CPU/GPU parity of include/vplkit/rsm_coverage.hpp against shaders/lib/rsm_coverage.glsl: a
// coarse light's irradiance on random geometry, and the reduction of RSM blocks read from a packed
// RSM (a uint table: a usampler2D, or a uvec4 storage buffer), on every target
// (vplkit/parity/parity.hpp). The gather's use of the coarse lights is compared
// pass by pass in tests/frontend/techniques/test_rsm_pipeline.cpp.
#include <doctest/doctest.h>

#include <random>

#include <vplkit/rsm_coverage.hpp>
#include <vplkit/rsm_packing.hpp>

#include <vplkit/parity/doctest.hpp>

#include "tests/parity/targets.hpp"


using namespace vplkit;
using namespace vplkit::parity;

TEST_CASE("parity: coarse_light_irradiance on random geometry, extents and unnormalised normals, on every target") {
  kernel_inputs inputs = geometry_inputs(23);
  std::mt19937 random(29);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  inputs.floats.push_back(std::vector<glm::vec4>(inputs.size()));
  for (std::size_t i = 0; i < inputs.size(); ++i) {
    inputs.floats[3][i] *= unit(random);                                                  // a mean normal, length <= 1
    inputs.floats[4][i] = glm::vec4(unit(random), 0.5f * unit(random), 2.0f * unit(random), unit(random) * unit(random));  // flux | extent
  }
  const irradiance_settings<float> settings{0.01f};
  kernel_source source;
  source.name = "coarse_light_irradiance";
  source.includes = {"lib/rsm_coverage.glsl"};
  source.body = "fout0 = vec4(coarse_light_irradiance(fin0.xyz, fin1.xyz, coarse_light(fin2.xyz, fin3.xyz, fin4.xyz, fin4.w), settings), 0.0);";
  source.float_outputs = 1;
  // The settings in a std140 block, which every target has (Vulkan has no default-block uniforms).
  kernel_resources resources;
  resources.blocks = {settings_block("settings", settings)};
  std::vector<glm::vec4> cpu(inputs.size());
  for (std::size_t i = 0; i < inputs.size(); ++i) {
    const coarse_light<float> light{glm::vec3(inputs.floats[2][i]), glm::vec3(inputs.floats[3][i]), glm::vec3(inputs.floats[4][i]),
                                    inputs.floats[4][i].w};
    cpu[i] = glm::vec4(coarse_light_irradiance(glm::vec3(inputs.floats[0][i]), glm::vec3(inputs.floats[1][i]), light, settings), 0.0f);
  }
  // Eq. 3.2's arithmetic (test_parity_irradiance.cpp's tolerance and its reasoning) and one more add.
  for (const testing::target_run& run : testing::every_target()) {
    const std::string target = run.name();
    CAPTURE(target);
    if (!testing::target_runs(run.where)) continue;
    source.name = std::string("coarse_light_irradiance") + " (" + target + ")";
    const kernel_outputs gpu = run.run(source, inputs, run.where, resources);
    require_parity(compare(source.name, gpu.floats[0], cpu, inputs,
                           {1e-6f, 1e-5f, 16, 0.0, "about 8 roundings, FMA contraction on llvmpipe, cancellation near tangency"}, 3));
  }
}

TEST_CASE("parity: reduce_rsm_block over a packed RSM, 8 x 8 blocks of 64^2 texels, empty texels among them, on every target") {
  // A random packed RSM as the gather reads it: depths, unit normals, flux; a fifth of the texels
  // empty. Each fragment of an 8 x 8 grid reduces its block of 8 x 8 texels.
  constexpr int size = 64, blocks = 8;
  std::mt19937 random(31);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  std::normal_distribution<float> normal;
  std::vector<glm::uvec4> packed(static_cast<std::size_t>(size * size));
  for (glm::uvec4& texel : packed) {
    if (unit(random) < 0.2f) continue;  // empty: all bits 0
    const glm::vec3 n = glm::normalize(glm::vec3(normal(random), normal(random), normal(random)));
    texel = pack_rsm_texel(-0.5f - 4.0f * unit(random), n, glm::vec3(unit(random), unit(random), 0.3f * unit(random)));
  }
  const rsm_unprojection<float> light = make_rsm_unprojection(1.2f, true, glm::ivec2(size));
  kernel_inputs inputs;
  inputs.width = inputs.height = blocks;
  kernel_source source;
  source.name = "reduce_rsm_block";
  source.defines = {{"VPLKIT_RSM_COVERAGE_REDUCE", "1"}};
  source.includes = {"lib/rsm_coverage.glsl", "lib/rsm_packing.glsl"};
  // The packed words as a uint table, the unprojection as a std140 block: every target has both.
  source.declarations = "rsm_texel rsm_fetch(ivec2 t) { return unpack_rsm_texel(rsm_packed(t), t, light); }\n";
  source.body =
      "coarse_light c = reduce_rsm_block(texel, 8, ivec2(64));\n"
      "fout0 = vec4(c.position, c.extent);\nfout1 = vec4(c.normal, 0.0);\nfout2 = vec4(c.flux, 0.0);";
  source.float_outputs = 3;
  kernel_resources resources;
  resources.uint_tables = {{"rsm_packed", size, size, packed}};
  resources.blocks = {settings_block("light", light)};
  std::vector<glm::vec4> position_extent(inputs.size()), normals(inputs.size()), flux(inputs.size());
  const auto fetch = [&](glm::ivec2 t) { return unpack_rsm_texel(packed[static_cast<std::size_t>(t.y * size + t.x)], t, light); };
  for (int y = 0; y < blocks; ++y)
    for (int x = 0; x < blocks; ++x) {
      const coarse_light<float> c = reduce_rsm_block<float>(glm::ivec2(x, y), blocks, glm::ivec2(size), fetch);
      const std::size_t i = static_cast<std::size_t>(y * blocks + x);
      position_extent[i] = glm::vec4(c.position, c.extent);
      normals[i] = glm::vec4(c.normal, 0.0f);
      flux[i] = glm::vec4(c.flux, 0.0f);
    }
  // Sums of about 50 products in the same order on both sides; llvmpipe may fuse a multiply-add
  // (one rounding fewer per term). The extent is a difference of two such sums (a mean square less
  // a squared mean, relative to the block's first light), so its error is relative to the mean
  // square of the block's offsets.
  for (const testing::target_run& run : testing::every_target()) {
    const std::string target = run.name();
    CAPTURE(target);
    if (!testing::target_runs(run.where)) continue;
    source.name = "reduce_rsm_block (" + target + ")";
    const kernel_outputs gpu = run.run(source, inputs, run.where, resources);
    require_parity(compare("reduce_rsm_block flux (" + target + ")", gpu.floats[2], flux, inputs, {0.0f, 1e-6f, 8, 0.0, "~50-term sums"}, 3));
    require_parity(compare("reduce_rsm_block normal (" + target + ")", gpu.floats[1], normals, inputs, {1e-6f, 1e-5f, 16, 0.0, "~50-term weighted sums"}, 3));
    require_parity(compare("reduce_rsm_block position and extent (" + target + ")", gpu.floats[0], position_extent, inputs,
                           {1e-5f, 1e-5f, 16, 0.0, "~50-term weighted sums; the extent a difference of two"}, 4));
  }
}
