// Materials (frontend/scene/material.hpp): the mip chain keeps a texture's mean, sample_texture
// follows GL's wrap modes and filters, and a mesh's albedo and alpha test read the texture.
#include <doctest/doctest.h>

#include <cmath>
#include <memory>

#include "frontend/image/image.hpp"
#include "frontend/scene/material.hpp"
#include "frontend/scene/scene.hpp"

using namespace vplkit;

namespace {

// A 4x2 texture: codes 0, 60, 120, 180 along x on row 0; row 1 all 255; alpha 255 - red code.
texture ramp_texture() {
  texture_level level{4, 2, {}};
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 4; ++x) {
      const auto code = static_cast<std::uint8_t>(y == 0 ? 60 * x : 255);
      level.rgba8.insert(level.rgba8.end(), {code, code, code, static_cast<std::uint8_t>(255 - code)});
    }
  return make_texture("ramp", level);
}

}  // namespace

TEST_CASE("material: the mip chain halves each side down to 1x1 and keeps the mean in linear light") {
  const texture t = ramp_texture();
  REQUIRE(t.levels.size() == 3);
  CHECK(t.levels[1].width == 2);
  CHECK(t.levels[1].height == 1);
  CHECK(t.levels[2].width == 1);
  double mean = 0.0;
  for (int x = 0; x < 4; ++x) mean += (srgb8_to_linear(static_cast<std::uint8_t>(60 * x)) + srgb8_to_linear(255)) / 8.0;
  CHECK(srgb8_to_linear(t.levels[2].rgba8[0]) == doctest::Approx(mean).epsilon(0.01));
  CHECK(srgb8_to_linear(0) == 0.0f);
  CHECK(srgb8_to_linear(255) == 1.0f);
  CHECK(srgb8_to_linear(128) == doctest::Approx(srgb_to_linear(128.0f / 255.0f)));
}

TEST_CASE("material: sample_texture with GL's wrap modes and filters") {
  const texture t = ramp_texture();
  texture_sampler nearest;
  nearest.mag = nearest.min = texture_filter::nearest;
  const float texel1 = srgb8_to_linear(60), texel3 = srgb8_to_linear(180);
  // Texel centres are at (i + 0.5) / side; v = 0.25 is row 0 (the image's top).
  CHECK(sample_texture(t, nearest, {1.5f / 4.0f, 0.25f}, 0.0f).r == texel1);
  CHECK(sample_texture(t, nearest, {1.5f / 4.0f, 0.25f}, 0.0f).a == doctest::Approx(195.0f / 255.0f));
  CHECK(sample_texture(t, nearest, {1.0f + 1.5f / 4.0f, 2.25f}, 0.0f).r == texel1);  // repeat
  nearest.wrap_s = texture_wrap::clamp_to_edge;
  CHECK(sample_texture(t, nearest, {7.0f, 0.25f}, 0.0f).r == texel3);
  nearest.wrap_s = texture_wrap::mirrored_repeat;
  CHECK(sample_texture(t, nearest, {1.0f + 0.5f / 4.0f, 0.25f}, 0.0f).r == texel3);  // mirrored: the last texel first
  // Linear: halfway between the centres of texels 1 and 2, the mean of their linear values.
  texture_sampler linear;
  linear.wrap_t = texture_wrap::clamp_to_edge;
  CHECK(sample_texture(t, linear, {0.5f, 0.25f}, 0.0f).r == doctest::Approx(0.5f * (texel1 + srgb8_to_linear(120))));
  // Minified far past the last level: the 1x1 level's value everywhere.
  CHECK(sample_texture(t, linear, {0.3f, 0.7f}, 20.0f).r == doctest::Approx(srgb8_to_linear(t.levels[2].rgba8[0])));
}

TEST_CASE("material: a mesh's albedo is its factor times the texture, and MASK cuts out below the cutoff") {
  mesh m;
  m.vertices = {{{0, 0, 0}, {0, 1, 0}, {0.5f, 1.0f, 1.0f}, {0.375f, 0.25f}},
                {{1, 0, 0}, {0, 1, 0}, {0.5f, 1.0f, 1.0f}, {0.375f, 0.25f}},
                {{0, 0, 1}, {0, 1, 0}, {0.5f, 1.0f, 1.0f}, {0.375f, 0.25f}}};
  m.indices = {0, 1, 2, 0, 2, 1};
  auto library = std::make_shared<material_library>();
  library->textures.push_back(ramp_texture());
  surface_material textured;
  textured.texture = 0;
  textured.sampler.mag = texture_filter::nearest;
  textured.alpha_mask = true;
  textured.alpha_cutoff = 0.9f;
  library->materials.push_back(textured);
  m.materials = library;
  m.material_ranges = {{3, 3, 0}};  // the second triangle only
  check_mesh(m, "test mesh");
  CHECK(material_of_triangle(m, 0) == nullptr);
  CHECK(surface_albedo_alpha(m, 0, {0.2f, 0.3f}) == glm::vec4(0.5f, 1.0f, 1.0f, 1.0f));
  const glm::vec4 textured_point = surface_albedo_alpha(m, 1, {0.2f, 0.3f});
  CHECK(textured_point.g == doctest::Approx(srgb8_to_linear(60)));
  CHECK(textured_point.r == doctest::Approx(0.5f * srgb8_to_linear(60)));
  CHECK(surface_cut_out(m, 1, {0.2f, 0.3f}));  // alpha 195/255 < 0.9
  CHECK_FALSE(surface_cut_out(m, 0, {0.2f, 0.3f}));
  m.material_ranges = {{3, 3, 1}};
  CHECK_THROWS_WITH(check_mesh(m, "test mesh"), doctest::Contains("names material 1"));
}
