// Render targets: several float and integer attachments at once, readback, and the RGBA16F
// rounding (frontend/gl/render_target.hpp).
#include <doctest/doctest.h>

#include <cmath>

#include <glm/gtc/packing.hpp>

#include <vplkit/parity/parity.hpp>

#include "frontend/core/error.hpp"
#include "frontend/gl/render_target.hpp"

using namespace vplkit;

TEST_CASE("two RGBA32F and one RGBA32UI attachments are written in one pass and read back") {
  const shader_library& shaders = parity::test_shaders();
  parity::kernel_source source;
  source.name = "write three targets";
  // The fragment's own coordinates, a value that half floats cannot hold exactly, and integers.
  source.body = "fout0 = vec4(gl_FragCoord.xy, 1.0 / 3.0, -2.5e7);\n"
                "fout1 = vec4(1.0 / 3.0, 65504.0, 1e-3, -0.0);\n"
                "uout0 = uvec4(uint(texel.x), uint(texel.y), 0xdeadbeefu, 7u);";
  source.float_outputs = 2;
  source.uint_outputs = 1;
  (void)shaders;
  parity::kernel_inputs inputs;
  inputs.width = 13;  // odd sizes catch row-stride mistakes
  inputs.height = 7;
  inputs.floats.assign(1, std::vector<glm::vec4>(inputs.size()));  // unused input, exercises binding
  const parity::kernel_outputs out = parity::run_fragment(source, inputs);
  for (int y = 0; y < inputs.height; ++y) {
    for (int x = 0; x < inputs.width; ++x) {
      const std::size_t i = static_cast<std::size_t>(y * inputs.width + x);
      REQUIRE(out.floats[0][i] == glm::vec4(static_cast<float>(x) + 0.5f, static_cast<float>(y) + 0.5f, 1.0f / 3.0f, -2.5e7f));
      REQUIRE(out.floats[1][i] == glm::vec4(1.0f / 3.0f, 65504.0f, 1e-3f, -0.0f));  // 32-bit: exact
      REQUIRE(out.uints[0][i] == glm::uvec4(x, y, 0xdeadbeefu, 7u));
    }
  }
}

TEST_CASE("an RGBA16F target stores a neighbouring half float") {
  // GL lets the float -> half conversion round to nearest or toward zero (llvmpipe truncates
  // some values: 1e-3 becomes 0.000999451, not the nearer 0.0010004), so the property is: the
  // stored value is a half float, and one of the two halves around the input.
  parity::test_shaders();
  framebuffer target(4, 4, {texel_format::rgba16f}, false);
  target.bind();
  const glm::vec4 value(1.0f / 3.0f, 65504.0f, 1e-3f, 2.0f);
  glClearColor(value.x, value.y, value.z, value.w);
  glClear(GL_COLOR_BUFFER_BIT);
  const image texels = target.read_image(0);
  for (int c = 0; c < 4; ++c) {
    CAPTURE(c);
    const float stored = texels.texels[0][c];
    CHECK(glm::unpackHalf1x16(glm::packHalf1x16(stored)) == stored);  // representable as a half
    // Half floats have 11 significant bits: neighbours are 2^(exponent - 10) apart.
    const float spacing = std::ldexp(1.0f, std::ilogb(value[c]) - 10);
    CHECK(std::fabs(stored - value[c]) < spacing);
  }
  CHECK(texels.texels[0].x != value.x);  // 1/3 is not a half: the target really is 16-bit
}

TEST_CASE("texture sizes beyond GL_MAX_TEXTURE_SIZE are refused with the limit in the message") {
  parity::test_shaders();
  GLint max_size = 0;
  glGetIntegerv(GL_MAX_TEXTURE_SIZE, &max_size);
  try {
    texture_2d too_big(max_size + 1, 4, texel_format::rgba32f);
    FAIL("no error for a texture wider than GL_MAX_TEXTURE_SIZE");
  } catch (const vplkit::error& failure) {
    CHECK(std::string(failure.what()).find("GL_MAX_TEXTURE_SIZE") != std::string::npos);
  }
}
