// CPU/GPU parity of include/vplkit/shadow.hpp against shaders/lib/shadow.glsl: shadow_density (Alg. 4) and the
// slope-scaled, normal-offset bias, texel by texel (vplkit/parity/parity.hpp).
#include <doctest/doctest.h>

#include <array>
#include <cstring>
#include <random>

#include <glm/gtc/matrix_transform.hpp>

#include <vplkit/shadow.hpp>
#include <vplkit/transform.hpp>

#include <vplkit/gl/settings_uniforms.hpp>
#include <vplkit/parity/doctest.hpp>

#include "tests/parity/targets.hpp"

using namespace vplkit;
using namespace vplkit::parity;

TEST_CASE("parity: shadow_density (Alg. 4) over a synthetic depth map, on every target") {
  // float input 0 is the depth map (x), a slope with steps, and float input 1 the receivers:
  // (rsm coordinate, receiver depth, gradient x); gradient y is 0.
  kernel_inputs inputs = grid_of(64, 64, 2);
  std::mt19937 random(22);
  std::uniform_real_distribution<float> uniform(0.0f, 1.0f);
  for (std::size_t i = 0; i < inputs.size(); ++i) {
    const float x = static_cast<float>(i % 64), y = static_cast<float>(i / 64);
    const float step = (static_cast<int>(x) / 9 + static_cast<int>(y) / 13) % 3 == 0 ? 0.5f : 0.0f;
    inputs.floats[0][i] = glm::vec4(-10.0f + 0.01f * x + step, 0, 0, 0);
    if (i % 97 == 0) inputs.floats[0][i].x = 0.0f;  // empty texels
    const glm::vec2 coordinate(uniform(random) * 70.0f - 3.0f, uniform(random) * 70.0f - 3.0f);
    inputs.floats[1][i] = glm::vec4(coordinate, -10.0f + 0.01f * coordinate.x + 0.3f * (uniform(random) - 0.5f),
                                    0.01f * (uniform(random) - 0.5f));
  }
  shadow_density_settings<float> settings;
  settings.kernel_size = 5;
  kernel_source source;
  source.name = "shadow_density";
  source.includes = {"lib/shadow.glsl"};
  // The depth map as a table and the settings as a std140 block: both exist on every target.
  source.declarations = "float rsm_depth_fetch(ivec2 texel) { return depth_map(texel).x; }\n";
  source.body = "fout0 = vec4(shadow_density(fin1.xy, fin1.z, vec2(fin1.w, 0.0), ivec2(64), settings), 0.0, 0.0, 0.0);";
  source.float_outputs = 1;
  kernel_resources resources;
  resources.tables = {{"depth_map", 64, 64, inputs.floats[0]}};
  resources.blocks = {settings_block("settings", settings)};
  std::vector<glm::vec4> cpu(inputs.size());
  for (std::size_t i = 0; i < inputs.size(); ++i) {
    const glm::vec4 r = inputs.floats[1][i];
    cpu[i] = glm::vec4(shadow_density(glm::vec2(r), r.z, glm::vec2(r.w, 0.0f),
                                      [&](glm::ivec2 t) { return inputs.floats[0][static_cast<std::size_t>(t.y * 64 + t.x)].x; },
                                      glm::ivec2(64), settings),
                       0.0f, 0.0f, 0.0f);
  }
  // A count of depth tests over exactly the same floats (the plane depth is +,* only): the
  // result is a multiple of 1/25 and must match exactly.
  for (const testing::target_run& run : testing::every_target()) {
    const std::string target = run.name();
    CAPTURE(target);
    if (!testing::target_runs(run.where)) continue;
    source.name = std::string("shadow_density") + " (" + target + ")";
    const kernel_outputs gpu = run.run(source, inputs, run.where, resources);
    require_parity(compare(source.name, gpu.floats[0], cpu, inputs, {0.0f, 0.0f, 0, 0.0, "exact count"}, 1));
  }
}

TEST_CASE("parity: the slope-scaled, normal-offset bias (footprint, normal offset, slope bias), on every target") {
  // float input 0: (position, eye depth), input 1: (unit normal, -), input 2: (unit direction to
  // the light, -). Outputs: (offset position, footprint), (slope bias, -).
  kernel_inputs inputs = grid_of(64, 64, 3);
  std::mt19937 random(25);
  std::uniform_real_distribution<float> uniform(-1.0f, 1.0f);
  const auto unit = [&]() {
    glm::vec3 v(uniform(random), uniform(random), uniform(random));
    return glm::length(v) > 1e-3f ? glm::normalize(v) : glm::vec3(0.0f, 1.0f, 0.0f);
  };
  for (std::size_t i = 0; i < inputs.size(); ++i) {
    inputs.floats[0][i] = glm::vec4(10.0f * uniform(random), 10.0f * uniform(random), 10.0f * uniform(random), -0.1f - 50.0f * (uniform(random) + 1.0f));
    inputs.floats[1][i] = glm::vec4(unit(), 0.0f);
    inputs.floats[2][i] = glm::vec4(unit(), 0.0f);
  }
  shadow_density_settings<float> settings;
  settings.normal_offset = 1.5f;
  settings.slope_scale = 2.0f;
  for (const bool spot : {true, false}) {
    CAPTURE(spot);
    const glm::mat4 projection = spot ? glm::perspective(glm::radians(70.0f), 1.0f, 0.05f, 200.0f) : glm::ortho(-8.0f, 8.0f, -8.0f, 8.0f, 0.5f, 60.0f);
    kernel_source source;
    source.name = "shadow_bias";
    source.includes = {"lib/shadow.glsl"};
    // The settings as a std140 block and the projection as a table of its columns (read exactly):
    // Vulkan has no default-block uniforms. shadow.glsl needs an rsm_depth_fetch for
    // shadow_density, which this case does not call: its value is never read.
    source.declarations = "float rsm_depth_fetch(ivec2 texel) { return 0.0; }\n";
    source.body = "mat4 projection = mat4(projection_columns(ivec2(0, 0)), projection_columns(ivec2(1, 0)), projection_columns(ivec2(2, 0)),\n"
                  "                       projection_columns(ivec2(3, 0)));\n"
                  "float footprint = shadow_texel_footprint(projection, fin0.w, 512);\n"
                  "fout0 = vec4(shadow_normal_offset(fin0.xyz, fin1.xyz, fin2.xyz, footprint, settings), footprint);\n"
                  "fout1 = vec4(shadow_slope_bias(dot(fin1.xyz, fin2.xyz), footprint, settings), 0.0, 0.0, 0.0);";
    source.float_outputs = 2;
    kernel_resources resources;
    resources.tables = {{"projection_columns", 4, 1, {projection[0], projection[1], projection[2], projection[3]}}};
    resources.blocks = {settings_block("settings", settings)};
    std::vector<glm::vec4> offset(inputs.size()), bias(inputs.size());
    for (std::size_t i = 0; i < inputs.size(); ++i) {
      const glm::vec4 p = inputs.floats[0][i];
      const float footprint = shadow_texel_footprint(projection, p.w, 512);
      offset[i] = glm::vec4(shadow_normal_offset(glm::vec3(p), glm::vec3(inputs.floats[1][i]), glm::vec3(inputs.floats[2][i]), footprint, settings), footprint);
      bias[i] = glm::vec4(shadow_slope_bias(glm::dot(glm::vec3(inputs.floats[1][i]), glm::vec3(inputs.floats[2][i])), footprint, settings), 0.0f, 0.0f, 0.0f);
    }
    // A dot product, a sqrt and a divide: a few roundings; the offset is added to a position up
    // to 10, so its error is absolute; tan = sqrt(1 - c^2) / c grows as c -> 0 (until max_slope).
    for (const testing::target_run& run : testing::every_target()) {
      const std::string target = run.name();
      CAPTURE(target);
      if (!testing::target_runs(run.where)) continue;
      source.name = "shadow_bias (" + target + ")";
      const kernel_outputs gpu = run.run(source, inputs, run.where, resources);
      require_parity(compare("shadow_normal_offset (" + target + ")", gpu.floats[0], offset, inputs,
                             {1e-5f, 1e-5f, 16, 0.0, "a few roundings added to positions up to 10"}, 4));
      require_parity(compare("shadow_slope_bias (" + target + ")", gpu.floats[1], bias, inputs,
                             {1e-6f, 1e-4f, 64, 0.0, "tan from sqrt(1 - c^2) / c amplifies c's rounding near grazing"}, 1));
    }
  }
}
