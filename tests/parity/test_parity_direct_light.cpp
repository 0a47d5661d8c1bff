// CPU/GPU parity of include/vplkit/direct_light.hpp against shaders/lib/direct_light.glsl: spot_light_irradiance,
// point_light_irradiance and point_light_texel_flux, texel by texel (vplkit/parity/parity.hpp).
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

TEST_CASE("parity: point_light_irradiance and point_light_texel_flux, on every target") {
  const kernel_inputs inputs = geometry_inputs(10);  // x, n and (as albedo) the third table used; the light is a uniform
  point_light<float> light;
  light.position = {0.2f, 1.9f, -0.1f};
  light.intensity = {6.0f, 5.0f, 4.0f};
  const irradiance_settings<float> settings{0.01f};
  const glm::ivec2 size(64, 48);
  kernel_source source;
  source.includes = {"lib/direct_light.glsl"};
  // The texel's normalised device coordinate comes from the position, so it varies per texel.
  source.body = "fout0 = vec4(point_light_irradiance(fin0.xyz, fin1.xyz, light, settings), 0.0);\n"
                "fout1 = vec4(point_light_texel_flux(abs(fin1.xyz), fin0.xyz, fin1.xyz, light, fract(fin0.xy) * 2.0 - 1.0, ivec2(64, 48)), 0.0);";
  source.float_outputs = 2;
  kernel_resources resources;
  resources.blocks = {settings_block("light", light), settings_block("settings", settings)};
  std::vector<glm::vec4> irradiance(inputs.size()), flux(inputs.size());
  for (std::size_t i = 0; i < inputs.size(); ++i) {
    const glm::vec3 x(inputs.floats[0][i]), n(inputs.floats[1][i]);
    irradiance[i] = glm::vec4(point_light_irradiance(x, n, light, settings), 0.0f);
    flux[i] = glm::vec4(point_light_texel_flux(glm::abs(n), x, n, light, glm::fract(glm::vec2(x)) * 2.0f - 1.0f, size), 0.0f);
  }
  for (const testing::target_run& run : testing::every_target()) {
    const std::string target = run.name();
    CAPTURE(target);
    if (!testing::target_runs(run.where)) continue;
    source.name = std::string("point_light_irradiance") + " (" + target + ")";
    const kernel_outputs gpu = run.run(source, inputs, run.where, resources);
    // A sqrt, a divide per component, two dot products: ~10 roundings. The flux's fract() is
    // exact and its solid angle a sqrt and a divide.
    require_parity(compare(source.name, gpu.floats[0], irradiance, inputs, {1e-6f, 1e-5f, 32, 0.0, "~10 roundings"}, 3));
    require_parity(compare(std::string("point_light_texel_flux") + " (" + target + ")", gpu.floats[1], flux, inputs,
                           {1e-9f, 1e-5f, 32, 0.0, "~12 roundings"}, 3));
  }
}
