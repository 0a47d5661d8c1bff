// CPU/GPU parity of include/vplkit/transform.hpp against shaders/lib/transform.glsl: transform_point, transform_direction and map_coordinate, texel by
// texel (vplkit/parity/parity.hpp).
#include <doctest/doctest.h>

#include <array>
#include <cstring>
#include <random>

#include <glm/gtc/matrix_transform.hpp>

#include <vplkit/transform.hpp>

#include <vplkit/gl/settings_uniforms.hpp>
#include <vplkit/parity/doctest.hpp>

#include "tests/parity/targets.hpp"

using namespace vplkit;
using namespace vplkit::parity;

TEST_CASE("parity: transform_point, transform_direction and map_coordinate, on every target") {
  kernel_inputs inputs = grid_of(64, 64, 1);
  std::mt19937 random(21);
  std::uniform_real_distribution<float> uniform(-3.0f, 3.0f);
  for (auto& p : inputs.floats[0]) p = glm::vec4(uniform(random), uniform(random), uniform(random), 0.0f);
  const glm::mat4 view = glm::lookAt(glm::vec3(0.3f, 4.0f, 1.0f), glm::vec3(0.0f), glm::vec3(0, 0, -1));
  const glm::mat4 view_projection = glm::perspective(1.2f, 1.0f, 0.1f, 20.0f) * view;
  kernel_source source;
  source.name = "transforms";
  source.includes = {"lib/transform.glsl"};
  // The matrices as a table, a column per texel (read exactly), since Vulkan has no default-block
  // uniforms: row 0 is view, row 1 view_projection.
  source.declarations = "mat4 table_matrix(int row) {\n"
                        "  return mat4(matrices(ivec2(0, row)), matrices(ivec2(1, row)), matrices(ivec2(2, row)), matrices(ivec2(3, row)));\n}\n";
  source.body = "mat4 view = table_matrix(0);\nmat4 view_projection = table_matrix(1);\n"
                "fout0 = vec4(transform_point(view, fin0.xyz), 0.0);\n"
                "fout1 = vec4(map_coordinate(view_projection, fin0.xyz, ivec2(512)), 0.0, 0.0);\n"
                "fout2 = vec4(transform_direction(view, fin0.xyz), 0.0);";
  source.float_outputs = 3;
  kernel_resources resources;
  resources.tables = {{"matrices", 4, 2, {view[0], view[1], view[2], view[3], view_projection[0], view_projection[1], view_projection[2], view_projection[3]}}};
  std::vector<glm::vec4> eye(inputs.size()), map(inputs.size()), turned(inputs.size());
  for (std::size_t i = 0; i < inputs.size(); ++i) {
    eye[i] = glm::vec4(transform_point(view, glm::vec3(inputs.floats[0][i])), 0.0f);
    map[i] = glm::vec4(map_coordinate(view_projection, glm::vec3(inputs.floats[0][i]), glm::ivec2(512)), 0.0f, 0.0f);
    turned[i] = glm::vec4(transform_direction(view, glm::vec3(inputs.floats[0][i])), 0.0f);
  }
  // A 3-term sum of products can cancel to near 0 (points near the eye's axes): 1e-6 absolute.
  for (const testing::target_run& run : testing::every_target()) {
    const std::string target = run.name();
    CAPTURE(target);
    if (!testing::target_runs(run.where)) continue;
    source.name = "transforms (" + target + ")";
    const kernel_outputs gpu = run.run(source, inputs, run.where, resources);
    require_parity(compare("transform_point (" + target + ")", gpu.floats[0], eye, inputs, {1e-6f, 0.0f, 4, 0.0, "sums of products, cancellation"}, 3));
    require_parity(compare("transform_direction (" + target + ")", gpu.floats[2], turned, inputs, {1e-6f, 0.0f, 4, 0.0, "sums of products, cancellation"}, 3));
    // The perspective divide: llvmpipe's is not correctly rounded: 1e-5 relative.
    require_parity(compare("map_coordinate (" + target + ")", gpu.floats[1], map, inputs, {1e-4f, 1e-5f, 8, 0.0, "perspective divide"}, 2));
  }
}
