// The direct-light pipeline on the built-in Cornell box, at a small size: the image is finite,
// lit where the spot light reaches, coloured by the walls, and matches the CPU light term.
#include <doctest/doctest.h>

#include <cmath>

#include <vplkit/direct_light.hpp>

#include "frontend/direct_renderer.hpp"
#include "frontend/error.hpp"
#include "tests/parity/parity_harness.hpp"

using namespace vplkit;

namespace {

glm::vec3 pixel(const frame& image, int x, int y) {
  const std::size_t i = (static_cast<std::size_t>(y) * image.width + x) * 4;
  return {image.radiance[i], image.radiance[i + 1], image.radiance[i + 2]};
}

// Mean colour over a rectangle [x0, x1) x [y0, y1) in pixels (y up).
glm::vec3 mean(const frame& image, int x0, int x1, int y0, int y1) {
  glm::vec3 sum(0.0f);
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x) sum += pixel(image, x, y);
  return sum / static_cast<float>((x1 - x0) * (y1 - y0));
}

}  // namespace

TEST_CASE("direct light on the Cornell box: finite, lit, coloured by the walls") {
  const shader_library& shaders = parity::test_shaders();
  direct_settings settings;
  settings.width = settings.height = 64;
  settings.shadow_map_size = 256;
  settings.target_format = texel_format::rgba32f;
  direct_renderer renderer(shaders, make_cornell_box(), settings);
  const frame image = renderer.render();
  REQUIRE(image.radiance.size() == 64u * 64u * 4u);
  for (float value : image.radiance) REQUIRE(std::isfinite(value));
  // Left wall strip red, right wall strip green (rows in the lower middle of the image).
  const glm::vec3 left = mean(image, 1, 5, 20, 40), right = mean(image, 59, 63, 20, 40);
  INFO("left wall mean " << left.x << " " << left.y << " " << left.z << ", right wall mean " << right.x << " " << right.y << " " << right.z);
  CHECK(left.x > 2.0f * left.y);
  CHECK(right.y > 2.0f * right.x);
  // The ceiling is behind the downward spot light: unlit.
  CHECK(mean(image, 20, 44, 61, 64) == glm::vec3(0.0f));
  REQUIRE(image.pass_times.size() == 2);
}

TEST_CASE("direct light equals albedo / pi * spot_light_irradiance at an unshadowed floor point") {
  // The floor point straight below the light, seen from the camera: find the pixel by
  // projecting the point, then compare with the CPU kernel (floor albedo 0.73, unshadowed).
  const shader_library& shaders = parity::test_shaders();
  const scene box = make_cornell_box();
  direct_settings settings;
  settings.width = settings.height = 96;
  settings.target_format = texel_format::rgba32f;
  direct_renderer renderer(shaders, box, settings);
  const frame image = renderer.render();
  const glm::vec3 floor_point(-0.5f, 0.0f, 0.5f);  // in front of the tall block: lit, seen, not shadowed
  const glm::vec4 clip = camera_view_projection(box.view, 1.0f) * glm::vec4(floor_point, 1.0f);
  const glm::vec2 ndc = glm::vec2(clip) / clip.w;
  const int px = static_cast<int>((ndc.x * 0.5f + 0.5f) * 96.0f), py = static_cast<int>((ndc.y * 0.5f + 0.5f) * 96.0f);
  const float expected = 0.73f / 3.14159265f * spot_light_irradiance(floor_point, glm::vec3(0, 1, 0), box.light).x;
  // The pixel centre is not exactly the point: the light varies slowly there (cos^3 falloff),
  // within 2% over a pixel of this size.
  CHECK(pixel(image, px, py).x == doctest::Approx(expected).epsilon(0.02));
}

TEST_CASE("direct renderer settings are validated") {
  const shader_library& shaders = parity::test_shaders();
  direct_settings settings;
  settings.width = 0;
  CHECK_THROWS_WITH_AS(direct_renderer(shaders, make_cornell_box(), settings), doctest::Contains("image size"), vplkit::error);
  settings = {};
  settings.irradiance.min_distance = 0.0f;
  CHECK_THROWS_WITH_AS(direct_renderer(shaders, make_cornell_box(), settings), doctest::Contains("min_distance"), vplkit::error);
  settings = {};
  settings.shadow_map_size = 1 << 20;
  CHECK_THROWS_WITH_AS(direct_renderer(shaders, make_cornell_box(), settings), doctest::Contains("GL_MAX_TEXTURE_SIZE"), vplkit::error);
  CHECK_THROWS_WITH_AS(built_in_scene("nope"), doctest::Contains("cornell-box"), vplkit::error);
}
