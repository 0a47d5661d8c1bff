// CPU/GPU parity of include/vplkit/polynomial_math.hpp against shaders/lib/polynomial_math.glsl: direction_from_angle, texel by
// texel (vplkit/parity/parity.hpp).
#include <doctest/doctest.h>

#include <array>
#include <cstring>
#include <random>

#include <glm/gtc/matrix_transform.hpp>

#include <vplkit/polynomial_math.hpp>

#include <vplkit/gl/settings_uniforms.hpp>
#include <vplkit/parity/doctest.hpp>

#include "tests/parity/targets.hpp"

using namespace vplkit;
using namespace vplkit::parity;

TEST_CASE("parity: direction_from_angle and direction_from_turns, on every target") {
  kernel_inputs inputs = grid_of(64, 64, 1);
  std::mt19937 random(20);
  std::uniform_real_distribution<float> angle(-20.0f, 20.0f);
  for (std::size_t i = 0; i < inputs.size(); ++i) inputs.floats[0][i] = glm::vec4(angle(random), angle(random) * 0.2f, 0.0f, 0.0f);
  inputs.floats[0][0].x = 0.0f;
  inputs.floats[0][1].x = 3.14159265f;
  kernel_source source;
  source.name = "direction_from_angle";
  source.includes = {"lib/polynomial_math.glsl"};
  source.body = "fout0 = vec4(direction_from_angle(fin0.x), direction_from_turns(fin0.y));";
  source.float_outputs = 1;
  std::vector<glm::vec4> cpu(inputs.size());
  for (std::size_t i = 0; i < inputs.size(); ++i)
    cpu[i] = glm::vec4(direction_from_angle(inputs.floats[0][i].x), direction_from_turns(inputs.floats[0][i].y));
  // Multiplies, adds and one floor: exact on both sides unless llvmpipe contracts a multiply-add
  // into an FMA (one rounding less per step), which would show as a few ulp.
  for (const testing::target_run& run : testing::every_target()) {
    const std::string target = run.name();
    CAPTURE(target);
    if (!testing::target_runs(run.where)) continue;
    source.name = std::string("direction_from_angle, direction_from_turns") + " (" + target + ")";
    const kernel_outputs gpu = run.run(source, inputs, run.where, {});
    require_parity(compare(source.name, gpu.floats[0], cpu, inputs, {0.0f, 0.0f, 4, 0.0, "+,*,floor only; FMA at most"}, 4));
  }
}
