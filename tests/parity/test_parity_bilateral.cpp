// CPU/GPU parity of include/vplkit/bilateral.hpp against shaders/lib/bilateral.glsl: bilateral_filter and bilateral_filter_axis, texel by
// texel (vplkit/parity/parity.hpp).
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
