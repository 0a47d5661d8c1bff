// CPU/GPU parity of the form factors of [FG]: shaders/lib/form_factor.glsl against
// include/vplkit/form_factor.hpp, texel by texel, clipped and unclipped quads.
#include <doctest/doctest.h>

#include <random>

#include <vplkit/form_factor.hpp>

#include <vplkit/parity/doctest.hpp>

#include "tests/parity/targets.hpp"

using namespace vplkit;
using namespace vplkit::parity;

TEST_CASE("parity: polygon_form_factor (clipped, unclipped and exact) and point_form_factor, on every target") {
  kernel_inputs inputs;
  inputs.width = 64;
  inputs.height = 64;
  inputs.floats.assign(5, std::vector<glm::vec4>(inputs.size()));
  int straddling = 0;
  std::mt19937 random(50);
  std::uniform_real_distribution<float> uniform(-1.0f, 1.0f);
  for (std::size_t i = 0; i < inputs.size(); ++i) {
    const glm::vec3 n = glm::normalize(glm::vec3(uniform(random), uniform(random), uniform(random)));
    const glm::vec3 origin(uniform(random), uniform(random), uniform(random) + 0.5f), e1(uniform(random), uniform(random), 0.2f * uniform(random)),
        e2(uniform(random), uniform(random), 0.2f * uniform(random));
    inputs.floats[0][i] = glm::vec4(n, 0.0f);
    inputs.floats[1][i] = glm::vec4(origin, 0.0f);
    inputs.floats[2][i] = glm::vec4(origin + e1, 0.0f);
    inputs.floats[3][i] = glm::vec4(origin + e1 + e2, 0.0f);
    inputs.floats[4][i] = glm::vec4(origin + e2, 0.0f);
    const float h[4] = {glm::dot(n, origin), glm::dot(n, origin + e1), glm::dot(n, origin + e1 + e2), glm::dot(n, origin + e2)};
    straddling += (h[0] >= 0.0f) != (h[1] >= 0.0f) || (h[1] >= 0.0f) != (h[2] >= 0.0f) || (h[2] >= 0.0f) != (h[3] >= 0.0f) ? 1 : 0;
  }
  REQUIRE(straddling > 500);  // the clipped path (crossing points, closing edges) is compared, not only whole quads
  kernel_source source;
  source.name = "form factors";
  source.includes = {"lib/form_factor.glsl"};
  source.body = "vec3 x = vec3(0.0);\n"
                "fout0 = vec4(polygon_form_factor(x, fin0.xyz, fin1.xyz, fin2.xyz, fin3.xyz, fin4.xyz),\n"
                "             polygon_form_factor_unclipped(x, fin0.xyz, fin1.xyz, fin2.xyz, fin3.xyz, fin4.xyz),\n"
                "             point_form_factor(x, fin0.xyz, fin1.xyz, normalize(cross(fin2.xyz - fin1.xyz, fin4.xyz - fin1.xyz))),\n"
                "             polygon_form_factor_exact(x, fin0.xyz, fin1.xyz, fin2.xyz, fin3.xyz, fin4.xyz));";
  source.float_outputs = 1;
  std::vector<glm::vec4> cpu(inputs.size());
  for (std::size_t i = 0; i < inputs.size(); ++i) {
    const glm::vec3 n(inputs.floats[0][i]), c0(inputs.floats[1][i]), c1(inputs.floats[2][i]), c2(inputs.floats[3][i]), c3(inputs.floats[4][i]);
    const glm::vec3 x(0.0f);
    cpu[i] = glm::vec4(polygon_form_factor(x, n, c0, c1, c2, c3), polygon_form_factor_unclipped(x, n, c0, c1, c2, c3),
                       point_form_factor(x, n, c0, glm::normalize(glm::cross(c1 - c0, c3 - c0))), polygon_form_factor_exact(x, n, c0, c1, c2, c3));
  }
  // Lambert's formula sums up to 6 signed edge terms of size O(1) (angles up to pi) that cancel
  // to a small F: a few ulp of each term (the polynomial's square roots on both sides; atan2 in
  // the exact form, llvmpipe's and the C library's differing by a few ulp) give an absolute error
  // of a few ulp of pi whatever F is: 2e-6 absolute, or 1e-5 relative.
  for (const testing::target_run& run : testing::every_target()) {
    const std::string target = run.name();
    CAPTURE(target);
    if (!testing::target_runs(run.where)) continue;
    source.name = std::string("form factors") + " (" + target + ")";
    const kernel_outputs gpu = run.run(source, inputs, run.where, {});
    require_parity(compare(source.name, gpu.floats[0], cpu, inputs, {2e-6f, 1e-5f, 32, 0.0, "ulps of O(1) edge terms that cancel"}, 4));
  }
}

