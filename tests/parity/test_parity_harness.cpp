// The harness itself must be able to fail: a deliberately wrong CPU twin is caught, the worst
// texel is located, the tolerance bounds and the allowed flip fraction work as documented.
#include <doctest/doctest.h>

#include <cstdlib>
#include <string>

#include <cmath>
#include <limits>

#include "tests/parity/parity_harness.hpp"

using namespace vplkit::parity;

namespace {
kernel_inputs ramp(int width, int height) {
  kernel_inputs inputs;
  inputs.width = width;
  inputs.height = height;
  inputs.floats.assign(1, std::vector<glm::vec4>(inputs.size()));
  for (std::size_t i = 0; i < inputs.size(); ++i) inputs.floats[0][i] = glm::vec4(static_cast<float>(i), 1.0f, -2.0f, 0.5f);
  return inputs;
}
}  // namespace

TEST_CASE("ulp_distance counts representable floats between two values") {
  CHECK(ulp_distance(1.0f, 1.0f) == 0);
  CHECK(ulp_distance(0.0f, -0.0f) == 0);
  CHECK(ulp_distance(1.0f, std::nextafter(1.0f, 2.0f)) == 1);
  CHECK(ulp_distance(-std::numeric_limits<float>::denorm_min(), std::numeric_limits<float>::denorm_min()) == 2);
}

TEST_CASE("the harness finds a wrong texel, names its coordinates and inputs") {
  const kernel_inputs inputs = ramp(8, 4);
  kernel_source source;
  source.name = "copy";
  source.body = "fout0 = fin0 * 2.0;";
  source.float_outputs = 1;
  const kernel_outputs gpu = run_fragment(source, inputs);
  std::vector<glm::vec4> cpu(inputs.size());
  for (std::size_t i = 0; i < inputs.size(); ++i) cpu[i] = inputs.floats[0][i] * 2.0f;
  CHECK(compare("copy", gpu.floats[0], cpu, inputs, {}).passed());

  cpu[13].y += 1e-3f;  // texel (5, 1)
  const comparison wrong = compare("copy", gpu.floats[0], cpu, inputs, {0.0f, 1e-6f, 2, 0.0, "exact copy"});
  CHECK(!wrong.passed());
  CHECK(wrong.mismatches == 1);
  CHECK(wrong.worst.find("texel (5, 1).y") == 0);
  CHECK(wrong.worst.find("fin0=(13, 1, -2, 0.5)") != std::string::npos);
  // One flip among 128 values passes with an allowed fraction of 1%, not with 0.5%.
  CHECK(compare("copy", gpu.floats[0], cpu, inputs, {0.0f, 0.0f, 0, 0.01, "flip"}).passed());
  CHECK(!compare("copy", gpu.floats[0], cpu, inputs, {0.0f, 0.0f, 0, 0.005, "flip"}).passed());

  cpu[13].y = std::numeric_limits<float>::quiet_NaN();  // a NaN never passes
  CHECK(!compare("copy", gpu.floats[0], cpu, inputs, {1e30f, 1e30f, 1 << 30, 0.0, "loose"}).passed());
}

TEST_CASE("the vertex-stage path returns one value per input, in order") {
  const kernel_inputs inputs = ramp(16, 3);
  kernel_source source;
  source.name = "vertex copy";
  source.body = "fout0 = fin0 + vec4(1.0);";
  source.float_outputs = 1;
  const kernel_outputs gpu = run_vertex(source, inputs);
  REQUIRE(gpu.floats[0].size() == inputs.size());
  for (std::size_t i = 0; i < inputs.size(); ++i) REQUIRE(gpu.floats[0][i] == inputs.floats[0][i] + glm::vec4(1.0f));
}

TEST_CASE("the harness runs on the headless context VPLKIT_CONTEXT asks for (EGL by default)") {
  const char* requested = std::getenv("VPLKIT_CONTEXT");
  const std::string kind = test_context_kind();
  MESSAGE("parity context: " << kind);
  if (requested && std::string(requested) == "osmesa") CHECK(kind == "OSMesa");
  else CHECK(kind.rfind("EGL", 0) == 0);
}
