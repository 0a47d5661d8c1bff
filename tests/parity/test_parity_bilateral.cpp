// CPU/GPU parity of include/vplkit/bilateral.hpp against shaders/lib/bilateral.glsl: bilateral_filter, bilateral_filter_axis and
// bilateral_filter_axis_quad, texel by texel (vplkit/parity/parity.hpp).
#include <doctest/doctest.h>

#include <array>
#include <cstring>
#include <random>

#include <glm/gtc/matrix_transform.hpp>

#include <vplkit/bilateral.hpp>

#include <vplkit/gl/settings_uniforms.hpp>
#include <vplkit/parity/doctest.hpp>

#include "tests/parity/targets.hpp"

using namespace vplkit;
using namespace vplkit::parity;

TEST_CASE("parity: bilateral_filter and bilateral_filter_axis over a synthetic indirect buffer, on every target") {
  // float input 0: tap values and depth (two planes at depth -4 and -6 with a noisy value),
  // float input 1: tap normals, float input 2: the centre to filter (coordinate, depth).
  kernel_inputs inputs = grid_of(48, 48, 3);
  std::mt19937 random(23);
  std::uniform_real_distribution<float> uniform(0.0f, 1.0f);
  for (std::size_t i = 0; i < inputs.size(); ++i) {
    const bool near = (i % 48) < 20;
    inputs.floats[0][i] = glm::vec4(uniform(random), uniform(random), uniform(random), near ? -4.0f : -6.0f);
    if (i % 61 == 0) inputs.floats[0][i].w = 0.0f;  // no surface
    inputs.floats[1][i] = near ? glm::vec4(0, 0, 1, 0) : glm::vec4(glm::normalize(glm::vec3(0.3f, 0.0f, 1.0f)), 0.0f);
    inputs.floats[2][i] = glm::vec4(uniform(random) * 48.0f, uniform(random) * 48.0f, near ? -4.0f : -6.0f, 0.0f);
  }
  bilateral_settings<float> settings;
  settings.kernel_size = 9;
  kernel_source source;
  source.name = "bilateral";
  source.includes = {"lib/bilateral.glsl"};
  // The taps as tables and the settings as a std140 block: both exist on every target.
  source.declarations = "bilateral_tap bilateral_fetch(ivec2 t) {\n"
                        "  vec4 v = taps(t);\n"
                        "  return bilateral_tap(v.xyz, v.w, tap_normals(t).xyz);\n}\n";
  source.body = "fout0 = vec4(bilateral_filter(fin2.xy, fin2.z, vec3(0.0, 0.0, 1.0), ivec2(48), settings), 0.0);\n"
                "fout1 = vec4(bilateral_filter_axis(fin2.xy, fin2.z, vec3(0.0, 0.0, 1.0), ivec2(48), 1, settings), 0.0);";
  source.float_outputs = 2;
  kernel_resources resources;
  resources.tables = {{"taps", 48, 48, inputs.floats[0]}, {"tap_normals", 48, 48, inputs.floats[1]}};
  resources.blocks = {settings_block("settings", settings)};
  const auto fetch = [&](glm::ivec2 t) {
    const std::size_t i = static_cast<std::size_t>(t.y * 48 + t.x);
    return bilateral_tap<float>{glm::vec3(inputs.floats[0][i]), inputs.floats[0][i].w, glm::vec3(inputs.floats[1][i])};
  };
  std::vector<glm::vec4> full(inputs.size()), axis(inputs.size());
  for (std::size_t i = 0; i < inputs.size(); ++i) {
    const glm::vec4 c = inputs.floats[2][i];
    full[i] = glm::vec4(bilateral_filter(glm::vec2(c), c.z, glm::vec3(0, 0, 1), fetch, glm::ivec2(48), settings), 0.0f);
    axis[i] = glm::vec4(bilateral_filter_axis(glm::vec2(c), c.z, glm::vec3(0, 0, 1), fetch, glm::ivec2(48), 1, settings), 0.0f);
  }
  // exp() differs between llvmpipe and the C library by a few ulp, and 81 weighted terms are
  // summed and divided by the weight sum: a normalised average of values in [0, 1], so 1e-5
  // absolute.
  for (const testing::target_run& run : testing::every_target()) {
    const std::string target = run.name();
    CAPTURE(target);
    if (!testing::target_runs(run.where)) continue;
    source.name = std::string("bilateral") + " (" + target + ")";
    const kernel_outputs gpu = run.run(source, inputs, run.where, resources);
    require_parity(compare("bilateral_filter (" + target + ")", gpu.floats[0], full, inputs, {1e-5f, 0.0f, 0, 0.0, "exp ulps over 81 taps"}, 3));
    require_parity(compare("bilateral_filter_axis (" + target + ")", gpu.floats[1], axis, inputs, {1e-5f, 0.0f, 0, 0.0, "exp ulps over 9 taps"}, 3));
  }
}

TEST_CASE("parity: bilateral_filter_axis_quad (the y pass for 2 x 2 pixels at once) over a synthetic indirect buffer, on every target") {
  // float input 0: tap values and depth (two planes, holes), input 1: tap normals, input 2: the
  // four pixels' depths, inputs 3 and 4: pixel 0's and pixel 3's normals (pixels 1 and 2 take the
  // taps' (0, 0, 1)). Each texel of the 24 x 24 grid filters its own quad; outputs 0-3 the four
  // pixels, along y; output 4 pixel 0 along x.
  kernel_inputs inputs = grid_of(24, 24, 5);
  std::mt19937 random(29);
  std::uniform_real_distribution<float> uniform(0.0f, 1.0f);
  for (std::size_t i = 0; i < inputs.size(); ++i) {
    const bool near = (i / 24) < 10;
    inputs.floats[0][i] = glm::vec4(uniform(random), uniform(random), uniform(random), near ? -4.0f : -6.0f);
    if (i % 37 == 0) inputs.floats[0][i].w = 0.0f;  // no surface
    inputs.floats[1][i] = near ? glm::vec4(0, 0, 1, 0) : glm::vec4(glm::normalize(glm::vec3(0.0f, 0.3f, 1.0f)), 0.0f);
    const float base = near ? -4.0f : -6.0f;
    inputs.floats[2][i] = glm::vec4(base, base * (1.0f + 0.05f * uniform(random)), base * (1.0f - 0.05f * uniform(random)), i % 41 == 0 ? 0.0f : base);
    inputs.floats[3][i] = glm::vec4(glm::normalize(glm::vec3(uniform(random) - 0.5f, 0.0f, 1.0f)), 0.0f);
    inputs.floats[4][i] = glm::vec4(glm::normalize(glm::vec3(0.0f, uniform(random) - 0.5f, 1.0f)), 0.0f);
  }
  bilateral_settings<float> settings;
  settings.kernel_size = 9;
  settings.normal_power = 5;
  kernel_source source;
  source.includes = {"lib/bilateral.glsl"};
  source.declarations = "bilateral_tap bilateral_fetch(ivec2 t) {\n"
                        "  vec4 v = taps(t);\n"
                        "  return bilateral_tap(v.xyz, v.w, tap_normals(t).xyz);\n}\n";
  source.body = "vec3 f0, f1, f2, f3, g0, g1, g2, g3;\n"
                "bilateral_filter_axis_quad(texel, fin2, fin3.xyz, vec3(0.0, 0.0, 1.0), vec3(0.0, 0.0, 1.0), fin4.xyz, ivec2(24), 1, settings, f0, f1, f2, f3);\n"
                "bilateral_filter_axis_quad(texel, fin2, fin3.xyz, vec3(0.0, 0.0, 1.0), vec3(0.0, 0.0, 1.0), fin4.xyz, ivec2(24), 0, settings, g0, g1, g2, g3);\n"
                "fout0 = vec4(f0, 0.0);\nfout1 = vec4(f1, 0.0);\nfout2 = vec4(f2, 0.0);\nfout3 = vec4(f3, 0.0);\nfout4 = vec4(g0, 0.0);";
  source.float_outputs = 5;
  kernel_resources resources;
  resources.tables = {{"taps", 24, 24, inputs.floats[0]}, {"tap_normals", 24, 24, inputs.floats[1]}};
  resources.blocks = {settings_block("settings", settings)};
  const auto fetch = [&](glm::ivec2 t) {
    const std::size_t i = static_cast<std::size_t>(t.y * 24 + t.x);
    return bilateral_tap<float>{glm::vec3(inputs.floats[0][i]), inputs.floats[0][i].w, glm::vec3(inputs.floats[1][i])};
  };
  std::array<std::vector<glm::vec4>, 5> expected;
  for (std::vector<glm::vec4>& e : expected) e.resize(inputs.size());
  for (std::size_t i = 0; i < inputs.size(); ++i) {
    const glm::ivec2 texel(static_cast<int>(i % 24), static_cast<int>(i / 24));
    const glm::vec4 d = inputs.floats[2][i];
    const std::array<float, 4> depth{d.x, d.y, d.z, d.w};
    const std::array<glm::vec3, 4> normal{glm::vec3(inputs.floats[3][i]), glm::vec3(0, 0, 1), glm::vec3(0, 0, 1), glm::vec3(inputs.floats[4][i])};
    const std::array<glm::vec3, 4> y = bilateral_filter_axis_quad(texel, depth, normal, fetch, glm::ivec2(24), 1, settings);
    for (std::size_t s = 0; s < 4; ++s) expected[s][i] = glm::vec4(y[s], 0.0f);
    expected[4][i] = glm::vec4(bilateral_filter_axis_quad(texel, depth, normal, fetch, glm::ivec2(24), 0, settings)[0], 0.0f);
  }
  for (const testing::target_run& run : testing::every_target()) {
    const std::string target = run.name();
    CAPTURE(target);
    if (!testing::target_runs(run.where)) continue;
    source.name = std::string("bilateral quad") + " (" + target + ")";
    const kernel_outputs gpu = run.run(source, inputs, run.where, resources);
    for (std::size_t s = 0; s < 5; ++s)
      require_parity(compare("bilateral_filter_axis_quad output " + std::to_string(s) + " (" + target + ")", gpu.floats[s], expected[s], inputs,
                             {1e-5f, 0.0f, 0, 0.0, "exp ulps over 9 taps"}, 3));
  }
}
