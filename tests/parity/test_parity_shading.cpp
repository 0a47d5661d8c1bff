// CPU/GPU parity of the final composition: shaders/lib/shading.glsl against
// vplkit/shading.hpp, texel by texel, on random albedos, irradiances and visibilities.
#include <doctest/doctest.h>

#include <random>

#include <vplkit/shading.hpp>

#include <vplkit/parity/doctest.hpp>

#include "tests/parity/targets.hpp"

using namespace vplkit;
using namespace vplkit::parity;

TEST_CASE("parity: diffuse_radiance (the final composition of every technique), on every target") {
  std::mt19937 random(31);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f), level(0.0f, 100.0f);
  kernel_inputs inputs;
  inputs.width = inputs.height = 64;
  inputs.floats.assign(3, std::vector<glm::vec4>(inputs.size()));
  for (std::size_t i = 0; i < inputs.size(); ++i) {
    inputs.floats[0][i] = glm::vec4(unit(random), unit(random), unit(random), unit(random));  // albedo | visibility
    inputs.floats[1][i] = glm::vec4(level(random), level(random), level(random), 0.0f);      // direct irradiance
    inputs.floats[2][i] = glm::vec4(level(random), level(random), level(random), 0.0f);      // indirect irradiance
  }
  // Edge cases: black, unshadowed, fully shadowed, no light at all.
  inputs.floats[0][0] = glm::vec4(0.0f, 0.0f, 0.0f, 1.0f);
  inputs.floats[0][1].w = 1.0f;
  inputs.floats[0][2].w = 0.0f;
  inputs.floats[1][3] = inputs.floats[2][3] = glm::vec4(0.0f);
  kernel_source source;
  source.name = "diffuse_radiance";
  source.includes = {"lib/shading.glsl"};
  source.body = "fout0 = vec4(diffuse_radiance(fin0.xyz, fin1.xyz, fin0.w, fin2.xyz), 0.0);";
  source.float_outputs = 1;
  std::vector<glm::vec4> cpu(inputs.size());
  for (std::size_t i = 0; i < inputs.size(); ++i)
    cpu[i] = glm::vec4(diffuse_radiance(glm::vec3(inputs.floats[0][i]), glm::vec3(inputs.floats[1][i]), inputs.floats[0][i].w,
                                        glm::vec3(inputs.floats[2][i])),
                       0.0f);
  // Three products and a sum: a GLSL compiler may fuse the multiply-add (GLSL allows it), 2 ulp.
  for (const testing::target_run& run : testing::every_target()) {
    const std::string target = run.name();
    CAPTURE(target);
    if (!testing::target_runs(run.where)) continue;
    source.name = std::string("diffuse_radiance") + " (" + target + ")";
    const kernel_outputs gpu = run.run(source, inputs, run.where, {});
    require_parity(compare(source.name, gpu.floats[0], cpu, inputs, {0.0f, 0.0f, 2, 0.0, "three products and a sum, maybe fused"}, 3));
  }
}
