// CPU/GPU parity of include/vplkit/temporal_accumulation.hpp against
// shaders/lib/temporal_accumulation.glsl: the clamped blend from random neighbourhoods and
// histories, and the depth test, texel by texel (vplkit/parity/parity.hpp). The whole pass
// (reprojection included) is compared with its CPU mirror in test_rsm_pipeline.cpp.
#include <doctest/doctest.h>

#include <random>

#include <vplkit/temporal_accumulation.hpp>

#include <vplkit/gl/settings_uniforms.hpp>
#include <vplkit/parity/doctest.hpp>

#include "tests/parity/targets.hpp"

using namespace vplkit;
using namespace vplkit::parity;

TEST_CASE("parity: temporal_resolve and temporal_history_matches on random neighbourhoods, on every target") {
  std::mt19937 random(17);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  kernel_inputs inputs = grid_of(64, 64, 5);
  for (std::size_t i = 0; i < inputs.size(); ++i) {
    for (int k = 0; k < 3; ++k)  // three neighbours, the current value, the history (| expected depth, stored depth)
      inputs.floats[static_cast<std::size_t>(k)][i] = glm::vec4(unit(random), unit(random), unit(random), 0.0f) * 3.0f;
    inputs.floats[3][i] = glm::vec4(unit(random), unit(random), unit(random), -10.0f * unit(random) - 0.1f);
    const float expected = inputs.floats[3][i].w;
    inputs.floats[4][i] = glm::vec4(unit(random) * 5.0f, unit(random) * 5.0f, unit(random) * 5.0f, expected * (0.96f + 0.08f * unit(random)));
  }
  const temporal_settings<float> settings{0.2f, 1.0f, 0.02f};
  kernel_source source;
  source.name = "temporal_accumulation";
  source.includes = {"lib/temporal_accumulation.glsl"};
  source.body = R"(
    neighbourhood_moments m = neighbourhood_moments(vec3(0.0), vec3(0.0), 0.0);
    neighbourhood_add(m, fin0.xyz);
    neighbourhood_add(m, fin1.xyz);
    neighbourhood_add(m, fin2.xyz);
    bool valid = temporal_history_matches(fin3.w, fin4.w, settings);
    fout0 = vec4(temporal_resolve(fin3.xyz, fin4.xyz, valid, m, settings), valid ? 1.0 : 0.0);)";
  source.float_outputs = 1;
  // The settings as a std140 block, which every target has.
  kernel_resources resources;
  resources.blocks = {settings_block("settings", settings)};
  std::vector<glm::vec4> cpu(inputs.size());
  for (std::size_t i = 0; i < inputs.size(); ++i) {
    neighbourhood_moments<float> m;
    for (int k = 0; k < 3; ++k) neighbourhood_add(m, glm::vec3(inputs.floats[static_cast<std::size_t>(k)][i]));
    const bool valid = temporal_history_matches(inputs.floats[3][i].w, inputs.floats[4][i].w, settings);
    cpu[i] = glm::vec4(temporal_resolve(glm::vec3(inputs.floats[3][i]), glm::vec3(inputs.floats[4][i]), valid, m, settings), valid ? 1.0f : 0.0f);
  }
  // Sums, a square root and a blend: a few roundings, some of which llvmpipe may fuse; the depth
  // test's decision must match exactly (w).
  for (const testing::target_run& run : testing::every_target()) {
    const std::string target = run.name();
    CAPTURE(target);
    if (!testing::target_runs(run.where)) continue;
    source.name = std::string("temporal_resolve") + " (" + target + ")";
    const kernel_outputs gpu = run.run(source, inputs, run.where, resources);
    require_parity(compare(source.name, gpu.floats[0], cpu, inputs, {1e-6f, 1e-5f, 16, 0.0, "sums, sqrt, a blend"}, 4));
  }
}
