// CPU/GPU parity of include/vplkit/cube_map.hpp against shaders/lib/cube_map.glsl: cube_face_of,
// cube_face_axis and cube_face_up, texel by texel (vplkit/parity/parity.hpp). Exact: the face is
// an integer decided by comparisons, the axis and up vector are constants.
#include <doctest/doctest.h>

#include <vplkit/cube_map.hpp>

#include <vplkit/parity/doctest.hpp>

#include "tests/parity/targets.hpp"

using namespace vplkit;
using namespace vplkit::parity;

TEST_CASE("parity: cube_face_of, cube_face_axis and cube_face_up are identical, on every target") {
  // Unit vectors and points: every face, and (the points' grid) directions with tied components.
  kernel_inputs inputs = geometry_inputs(38);
  for (std::size_t i = 0; i < inputs.size(); i += 7) inputs.floats[0][i] = glm::vec4(glm::vec3(static_cast<float>(i % 3) - 1.0f), 0.0f);
  kernel_source source;
  source.includes = {"lib/cube_map.glsl"};
  source.body =
      "int f = cube_face_of(fin1.xyz);\n"
      "int g = cube_face_of(fin0.xyz);\n"
      "fout0 = vec4(float(f), float(g), dot(cube_face_axis(f), vec3(1.0, 2.0, 3.0)), dot(cube_face_up(g), vec3(1.0, 2.0, 3.0)));";
  source.float_outputs = 1;
  std::vector<glm::vec4> cpu(inputs.size());
  for (std::size_t i = 0; i < inputs.size(); ++i) {
    const int f = cube_face_of(glm::vec3(inputs.floats[1][i])), g = cube_face_of(glm::vec3(inputs.floats[0][i]));
    cpu[i] = glm::vec4(static_cast<float>(f), static_cast<float>(g), glm::dot(cube_face_axis<float>(f), glm::vec3(1, 2, 3)),
                       glm::dot(cube_face_up<float>(g), glm::vec3(1, 2, 3)));
  }
  for (const testing::target_run& run : testing::every_target()) {
    const std::string target = run.name();
    CAPTURE(target);
    if (!testing::target_runs(run.where)) continue;
    source.name = std::string("cube_map") + " (" + target + ")";
    const kernel_outputs gpu = run.run(source, inputs, run.where, {});
    require_parity(compare(source.name, gpu.floats[0], cpu, inputs, {0.0f, 0.0f, 0, 0.0, "integers and constants: exact"}, 4));
  }
}
