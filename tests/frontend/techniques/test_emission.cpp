// Emissive materials drawn as seen (issue 38 item 4; frontend/scene_gl/emission_pass.hpp): in
// every family's final image (the RSM techniques, Light Wave, final gathering) and in the Monte
// Carlo reference's, an emitter the camera sees adds its closed-form emission (factor x its
// texture, sRGB decoded; a stronger one more), one hidden behind an opaque box or seen from its
// back adds nothing, the direct and indirect outputs stay the same bit for bit, and a scene
// without emission draws no emission pass.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <vplkit/parity/doctest.hpp>

#include "frontend/reference/monte_carlo.hpp"
#include "frontend/scene/camera.hpp"
#include "frontend/techniques/final_gather/final_gather_pipeline.hpp"
#include "frontend/techniques/final_gather/final_gather_scene.hpp"
#include "frontend/techniques/lightwave/lightwave_pipeline.hpp"
#include "frontend/techniques/rsm/rsm_pipeline.hpp"

using namespace vplkit;

namespace {

constexpr int width = 64, height = 48;

// A quad of half-sides |u| and |v| around `centre`, facing u x v (counter-clockwise seen from
// there), its texture coordinates the unit square; `material` >= 0 adds a material range.
void add_quad(mesh& target, glm::vec3 centre, glm::vec3 u, glm::vec3 v, glm::vec3 albedo, int material = -1) {
  const glm::vec3 n = glm::normalize(glm::cross(u, v));
  const auto first = static_cast<std::uint32_t>(target.vertices.size());
  target.vertices.push_back({centre - u - v, n, albedo, {0.0f, 0.0f}});
  target.vertices.push_back({centre + u - v, n, albedo, {1.0f, 0.0f}});
  target.vertices.push_back({centre + u + v, n, albedo, {1.0f, 1.0f}});
  target.vertices.push_back({centre - u + v, n, albedo, {0.0f, 1.0f}});
  if (material >= 0)
    target.material_ranges.push_back({static_cast<std::uint32_t>(target.indices.size()), 6, static_cast<std::uint32_t>(material)});
  for (std::uint32_t k : {0u, 1u, 2u, 0u, 2u, 3u}) target.indices.push_back(first + k);
}

const glm::vec3 factor(0.9f, 0.6f, 0.3f);
const glm::u8vec3 glow_code(200, 120, 40);  // the emission texture's one sRGB colour
// Emitter A: factor x its texture. Emitter B: the factor at strength 3, no texture; its right part
// is behind a box. Emitter C: B's material, its back to the camera.
const glm::vec3 point_a(-0.8f, 1.0f, -1.0f), point_b(0.45f, 1.0f, -1.0f), point_hidden(1.25f, 1.0f, -1.0f), point_back(-0.8f, 1.8f, -1.0f);

// How near GL's images come to the closed forms: rgba16f rounding (2^-11) for a factor alone; a
// texture adds the GL driver's sRGB decode, which llvmpipe approximates (0.25 % and 0.4 % off
// GL's exact table in two channels of this one colour): 1 %.
constexpr float factor_tolerance = 2e-3f, texture_tolerance = 1e-2f;

glm::vec3 emission_a() { return factor * glm::vec3(srgb8_to_linear(glow_code.r), srgb8_to_linear(glow_code.g), srgb8_to_linear(glow_code.b)); }
glm::vec3 emission_b() { return 3.0f * factor; }

// A room, the three emitters (albedo 0: what the camera sees of them is their
// emission alone) and an opaque box in front of B's right part, lit by a spot; `emitting` false:
// the same materials without emission.
scene emitter_scene(bool emitting) {
  mesh geometry;
  // A closed room (final gathering's cube map must see a wall in every direction), its faces inwards.
  add_quad(geometry, {0, 0, 1.5f}, {2.5f, 0, 0}, {0, 0, -3.5f}, glm::vec3(0.6f));     // floor
  add_quad(geometry, {0, 3, 1.5f}, {0, 0, -3.5f}, {2.5f, 0, 0}, glm::vec3(0.6f));     // ceiling
  add_quad(geometry, {0, 1.5f, -2}, {2.5f, 0, 0}, {0, 1.5f, 0}, glm::vec3(0.6f));     // back
  add_quad(geometry, {0, 1.5f, 5}, {0, 1.5f, 0}, {2.5f, 0, 0}, glm::vec3(0.6f));      // front, behind the camera
  add_quad(geometry, {-2.5f, 1.5f, 1.5f}, {0, 1.5f, 0}, {0, 0, 3.5f}, glm::vec3(0.6f));  // left
  add_quad(geometry, {2.5f, 1.5f, 1.5f}, {0, 0, 3.5f}, {0, 1.5f, 0}, glm::vec3(0.6f));   // right
  const glm::vec3 box(1.2f, 1.0f, 0.0f), half(0.5f, 0.6f, 0.3f);
  add_quad(geometry, box + glm::vec3(0, 0, half.z), {half.x, 0, 0}, {0, half.y, 0}, glm::vec3(0.5f));     // front
  add_quad(geometry, box - glm::vec3(0, 0, half.z), {0, half.y, 0}, {half.x, 0, 0}, glm::vec3(0.5f));     // back
  add_quad(geometry, box + glm::vec3(half.x, 0, 0), {0, 0, -half.z}, {0, half.y, 0}, glm::vec3(0.5f));    // right
  add_quad(geometry, box - glm::vec3(half.x, 0, 0), {0, half.y, 0}, {0, 0, -half.z}, glm::vec3(0.5f));    // left
  add_quad(geometry, box + glm::vec3(0, half.y, 0), {half.x, 0, 0}, {0, 0, -half.z}, glm::vec3(0.5f));    // top
  add_quad(geometry, point_a, {0.6f, 0, 0}, {0, 0.4f, 0}, glm::vec3(0.0f), 0);
  add_quad(geometry, {0.8f, 1.0f, -1.0f}, {0.6f, 0, 0}, {0, 0.4f, 0}, glm::vec3(0.0f), 1);
  add_quad(geometry, point_back, {0, 0.2f, 0}, {0.6f, 0, 0}, glm::vec3(0.0f), 1);
  auto library = std::make_shared<material_library>();
  std::vector<std::uint8_t> texels;
  for (int i = 0; i < 16; ++i) texels.insert(texels.end(), {glow_code.r, glow_code.g, glow_code.b, 255});
  library->textures.push_back(make_texture("glow", texture_level{4, 4, texels}));
  surface_material a, b;
  if (emitting) {
    a.emission = factor;
    a.emission_texture = 0;
    b.emission = emission_b();
  }
  library->materials = {a, b};
  geometry.materials = library;
  scene s;
  s.name = emitting ? "emitters" : "emitters-dark";
  s.geometry = std::move(geometry);
  s.view.position = {0, 1, 4};
  s.view.target = {0, 1, -1};
  scene_light spot;
  spot.spot.position = {0, 2.8f, 1.5f};
  spot.spot.direction = glm::normalize(glm::vec3(0, 0.5f, -1) - spot.spot.position);
  spot.spot.intensity = glm::vec3(5.0f);
  spot.spot.cos_inner = std::cos(glm::radians(50.0f));
  spot.spot.cos_outer = std::cos(glm::radians(70.0f));
  s.lights = {spot};
  check_scene(s);
  return s;
}

// The pixel (column, row from the bottom) that the scene's camera sees `p` in.
glm::ivec2 pixel_of(const scene& s, glm::vec3 p) {
  const glm::vec4 clip = camera_projection_matrix(s.view, static_cast<float>(width) / height) * camera_view_matrix(s.view) * glm::vec4(p, 1.0f);
  const glm::vec2 ndc = glm::vec2(clip) / clip.w;
  return glm::ivec2(glm::floor((ndc * 0.5f + 0.5f) * glm::vec2(width, height)));
}

glm::vec3 rgb_at(const image& picture, glm::ivec2 pixel) { return glm::vec3(picture.at(pixel.x, pixel.y)); }

void check_colour_close(glm::vec3 seen, glm::vec3 expected, float relative) {
  for (int c = 0; c < 3; ++c) {
    CAPTURE(c);
    CAPTURE(seen[c]);
    CAPTURE(expected[c]);
    CHECK(std::abs(seen[c] - expected[c]) <= relative * expected[c] + 1e-4f);
  }
}

struct drawn {
  image radiance, indirect, direct;
  bool emission_pass = false;  ///< whether a pass named "emission" ran
};

drawn draw_with(pipeline& p) {
  p.draw();
  drawn out{p.output().read_image(), p.indirect_output().read_image(), p.direct_output().read_image()};
  for (const pass_time& t : p.collect_pass_times()) out.emission_pass = out.emission_pass || t.pass == "emission";
  return out;
}

// Each family's pipeline over a scene.
struct family {
  std::string name;
  std::function<std::unique_ptr<pipeline>(const scene&)> make;
};

std::vector<family> families() {
  return {
      {"rsm-alg6",
       [](const scene& s) {
         rsm_pipeline_settings settings;
         settings.width = width;
         settings.height = height;
         settings.rsm_size = 128;
         return std::unique_ptr<pipeline>(new rsm_pipeline(parity::test_shaders(), s, settings));
       }},
      {"lightwave-accurate",
       [](const scene& s) {
         lightwave_settings settings;
         settings.width = width;
         settings.height = height;
         settings.shadow_map_scale = 4.0f;
         return std::unique_ptr<pipeline>(new lightwave_pipeline(parity::test_shaders(), s, settings));
       }},
      {"finalgather-polygon",
       [](const scene& s) {
         final_gather_settings settings;
         settings.width = width;
         settings.height = height;
         settings.face_size = 32;
         settings.resolution = 4;
         settings.environment_resolution = 8;
         // The object low in the left corner, away from every pixel the test reads.
         return std::unique_ptr<pipeline>(
             new final_gather_pipeline(parity::test_shaders(), make_final_gather_scene(s, "sphere", glm::vec3(-1.6f, 0.3f, 0.8f), 0.4f), settings));
       }},
  };
}

}  // namespace

TEST_CASE("emission: every family's final image adds factor x texture where an emitter is seen, nothing where it is hidden or turned away; direct and indirect unchanged") {
  const scene lit = emitter_scene(true), dark = emitter_scene(false);
  const glm::ivec2 at_a = pixel_of(lit, point_a), at_b = pixel_of(lit, point_b), hidden = pixel_of(lit, point_hidden), back = pixel_of(lit, point_back);
  for (const family& f : families()) {
    CAPTURE(f.name);
    const drawn with = draw_with(*f.make(lit));
    const drawn without = draw_with(*f.make(dark));
    // Only a scene with emission draws the pass.
    CHECK(with.emission_pass);
    CHECK_FALSE(without.emission_pass);
    // The emitters' albedo is 0: what the camera sees of them is their emission, in closed form.
    check_colour_close(rgb_at(with.radiance, at_a), emission_a(), texture_tolerance);
    check_colour_close(rgb_at(with.radiance, at_b), emission_b(), factor_tolerance);  // strength 3: three times the factor
    check_colour_close(rgb_at(without.radiance, at_a), glm::vec3(0.0f), 0.0f);
    // Behind the box and on an emitter's back: the image without emission, to the bit.
    CHECK(rgb_at(with.radiance, hidden) == rgb_at(without.radiance, hidden));
    CHECK(rgb_at(with.radiance, back) == rgb_at(without.radiance, back));
    CHECK(rgb_at(with.radiance, hidden).r < 0.5f * emission_b().r);  // the box's lit face, not the emitter
    // Every pixel: unchanged, or the emission of A or of B added; no emitter pixel elsewhere.
    int added_a = 0, added_b = 0, other = 0;
    for (int y = 0; y < height; ++y)
      for (int x = 0; x < width; ++x) {
        const glm::vec3 added = rgb_at(with.radiance, {x, y}) - rgb_at(without.radiance, {x, y});
        if (added == glm::vec3(0.0f)) continue;
        const auto near = [&](glm::vec3 e, float tolerance) { return glm::all(glm::lessThanEqual(glm::abs(added - e), tolerance * e + 1e-4f)); };
        if (near(emission_a(), texture_tolerance)) ++added_a;
        else if (near(emission_b(), factor_tolerance)) ++added_b;
        else ++other;
      }
    CAPTURE(added_a);
    CAPTURE(added_b);
    CHECK(other == 0);
    CHECK(added_a > 40);  // A spans about 15 x 6 pixels
    CHECK(added_b > 20);  // B's visible part, about half of it
    CHECK(added_b < added_a);
    // Only the final image gets it: the light the surfaces receive is the same to the bit.
    CHECK(with.indirect.texels == without.indirect.texels);
    CHECK(with.direct.texels == without.direct.texels);
  }
}

TEST_CASE("emission: the Monte Carlo reference adds it where the camera ray's first hit emits, and agrees with every family there") {
  const scene lit = emitter_scene(true), dark = emitter_scene(false);
  // A few bounce samples, the same seed for both scenes: the bounce rays are the same, and many
  // of them hit the emitters, so the indirect images are equal to the bit only if the emission
  // lights nothing (with 0 samples the indirect image is 0 in both and that check could not fail).
  // The emitters' albedo is 0, so their pixels' radiance is still their emission alone.
  const one_bounce_images with = reference_one_bounce(lit, width, height, 8, 1, 2);
  const one_bounce_images without = reference_one_bounce(dark, width, height, 8, 1, 2);
  REQUIRE(std::any_of(with.indirect.texels.begin(), with.indirect.texels.end(), [](const glm::vec4& v) { return v.r > 0.0f; }));
  const glm::ivec2 at_a = pixel_of(lit, point_a), at_b = pixel_of(lit, point_b), hidden = pixel_of(lit, point_hidden), back = pixel_of(lit, point_back);
  check_colour_close(rgb_at(with.radiance, at_a), emission_a(), 1e-5f);
  check_colour_close(rgb_at(with.radiance, at_b), emission_b(), 1e-5f);
  CHECK(rgb_at(with.radiance, hidden) == rgb_at(without.radiance, hidden));
  CHECK(rgb_at(with.radiance, back) == rgb_at(without.radiance, back));
  CHECK(with.direct.texels == without.direct.texels);
  CHECK(with.indirect.texels == without.indirect.texels);
  // The emitters' pixels away from their edges (all 8 neighbours added the same emission, to
  // float rounding, in the reference): each family's final image there is the reference's within 0.2 %.
  for (const family& f : families()) {
    CAPTURE(f.name);
    const drawn technique = draw_with(*f.make(lit));
    int compared = 0;
    for (int y = 1; y + 1 < height; ++y)
      for (int x = 1; x + 1 < width; ++x) {
        const glm::vec3 added = rgb_at(with.radiance, {x, y}) - rgb_at(without.radiance, {x, y});
        if (added == glm::vec3(0.0f)) continue;
        bool interior = true;
        for (int dy = -1; dy <= 1; ++dy)
          for (int dx = -1; dx <= 1; ++dx)
            interior = interior && glm::all(glm::lessThanEqual(glm::abs(rgb_at(with.radiance, {x + dx, y + dy}) - rgb_at(without.radiance, {x + dx, y + dy}) - added),
                                                               1e-5f * added + 1e-6f));
        if (!interior) continue;
        ++compared;
        const bool textured = glm::all(glm::lessThanEqual(glm::abs(added - emission_a()), 1e-5f * emission_a()));
        check_colour_close(rgb_at(technique.radiance, {x, y}), rgb_at(with.radiance, {x, y}), textured ? texture_tolerance : factor_tolerance);
      }
    CHECK(compared > 30);
  }
}
