// CPU/GPU parity of include/vplkit/direct_light.hpp against shaders/lib/direct_light.glsl: spot_light_irradiance, texel by
// texel (vplkit/parity/parity.hpp).
#include <doctest/doctest.h>

#include <array>
#include <cstring>
#include <random>

#include <glm/gtc/matrix_transform.hpp>

#include <vplkit/direct_light.hpp>

#include <vplkit/gl/settings_uniforms.hpp>
#include <vplkit/parity/doctest.hpp>

#include "tests/parity/targets.hpp"

using namespace vplkit;
using namespace vplkit::parity;

TEST_CASE("parity: spot_light_irradiance, on every target") {
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
  source.body = "fout0 = vec4(spot_light_irradiance(fin0.xyz, fin1.xyz, light, settings), 0.0);";
  source.float_outputs = 1;
  // The light and the settings as std140 blocks, which every target has.
  kernel_resources resources;
  resources.blocks = {settings_block("light", light), settings_block("settings", settings)};
  std::vector<glm::vec4> cpu(inputs.size());
  for (std::size_t i = 0; i < inputs.size(); ++i)
    cpu[i] = glm::vec4(spot_light_irradiance(glm::vec3(inputs.floats[0][i]), glm::vec3(inputs.floats[1][i]), light, settings), 0.0f);
  // A sqrt, a divide per component, two dot products, the smoothstep polynomial: ~15 roundings,
  // and the smoothstep input (cos_axis - cos_outer) cancels near the outer cone edge, where the
  // result itself is near 0: 32 ulp, 1e-5 relative or 1e-6 absolute.
  for (const testing::target_run& run : testing::every_target()) {
    const std::string target = run.name();
    CAPTURE(target);
    if (!testing::target_runs(run.where)) continue;
    source.name = std::string("spot_light_irradiance") + " (" + target + ")";
    const kernel_outputs gpu = run.run(source, inputs, run.where, resources);
    require_parity(compare(source.name, gpu.floats[0], cpu, inputs,
                           {1e-6f, 1e-5f, 32, 0.0, "~15 roundings; cancellation at the cone edge where the result is ~0"}, 3));
  }
}
