// The same property through the GoogleTest adapter: EXPECT_PARITY passes on the GLSL as written,
// and parity_holds fails, with the report, when the C++ side is off by 0.1 %.
#include <gtest/gtest.h>

#include <vplkit/parity/gtest.hpp>

#include "two_lights_test.hpp"

namespace parity = vplkit::parity;

TEST(TwoLights, GlslEqualsCppOn10000SeededInputs) {
  parity::add_shader_root(CONSUMER_SHADERS);
  const parity::kernel_inputs in = two_lights::inputs(4);
  const parity::kernel_outputs gpu = parity::run_fragment(two_lights::kernel(), in, two_lights::uniforms());
  EXPECT_PARITY(two_lights::compare(gpu.floats[0], in));
}

TEST(TwoLights, AnErrorOfOneTenthOfAPercentFailsWithTheReport) {
  parity::add_shader_root(CONSUMER_SHADERS);
  const parity::kernel_inputs in = two_lights::inputs(4);
  const parity::kernel_outputs gpu = parity::run_fragment(two_lights::kernel(), in, two_lights::uniforms());
  std::vector<glm::vec4> cpu = two_lights::on_cpu(in);
  for (glm::vec4& value : cpu) value *= 1.001f;
  const ::testing::AssertionResult holds = parity::parity_holds(parity::compare("two_lights_irradiance", gpu.floats[0], cpu, in, two_lights::tolerance(in), 3));
  EXPECT_FALSE(holds);
  EXPECT_NE(std::string(holds.message()).find("worst texel ("), std::string::npos) << holds.message();
  EXPECT_NE(std::string(holds.message()).find("mismatches:"), std::string::npos) << holds.message();
}
