// The RSM pipeline of [RSMV] (frontend/techniques/rsm/rsm_pipeline.hpp): its gather and post passes against
// the CPU mirror (frontend/techniques/rsm/rsm_cpu_mirror.hpp) texel by texel, at small resolutions, for every
// technique, both lights, both filters and both float formats; and properties of its output.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstring>

#include "frontend/core/error.hpp"
#include "frontend/techniques/rsm/rsm_cpu_mirror.hpp"
#include "frontend/techniques/rsm/rsm_pipeline.hpp"
#include "tests/frontend/techniques/pass_parity.hpp"

using namespace vplkit;
using namespace vplkit::parity;

namespace {

rsm_pipeline_settings small_settings(const std::string& technique) {
  rsm_pipeline_settings settings;
  settings.width = settings.height = 64;
  settings.rsm_size = 64;
  settings.format = texel_format::rgba32f;
  settings.technique = technique;
  settings.radius = 0.25f;  // 16 texels of the 64^2 RSM
  settings.bilateral.kernel_size = 9;
  return settings;
}


struct pass_parity {
  comparison gather;
  comparison post_radiance;
  comparison post_indirect;
};

// Renders, reads back, runs the CPU mirror on the read-back inputs, compares.
pass_parity check_pipeline(const scene& source, const rsm_pipeline_settings& settings, const tolerance& gather_bounds,
                           const tolerance& post_bounds, const tolerance& coarse_bounds) {
  const shader_library& shaders = test_shaders();
  rsm_pipeline pipeline(shaders, source, settings);
  const rsm_frame frame = pipeline.render();
  const rsm_pass_buffers buffers = pipeline.read_buffers();
  const rsm_frame_constants& constants = pipeline.constants();
  pass_parity result;
  const std::string name = source.name + " " + settings.technique + (settings.filter == post_filter::separable ? " separable" : " full") +
                           (settings.format == texel_format::rgba16f ? " rgba16f" : "");
  if (constants.technique.indirect && constants.gather.coverage_blocks > 0) {
    // The coverage's coarse lights: sums of a block's texels in the same order on both sides.
    const std::array<image, 3> coarse = cpu_coarse_pass(buffers, constants, 2);
    const char* names[3] = {"coarse lights position | extent, ", "coarse lights normal, ", "coarse lights flux, "};
    for (std::size_t i = 0; i < 3; ++i)
      require_parity(compare(names[i] + name, buffers.coarse[i].texels, coarse[i].texels, coordinates_of(coarse[i]), coarse_bounds));
  }
  if (constants.technique.indirect) {
    const image gathered = cpu_gather_pass(buffers, constants, 2);
    result.gather = compare("gather pass, " + name, buffers.indirect.texels, gathered.texels, coordinates_of(gathered), gather_bounds);
  }
  image filter_input = buffers.indirect;
  if (constants.technique.indirect && settings.filter == post_filter::separable) {
    const image blurred = cpu_blur_x_pass(buffers.indirect, buffers, constants, 2);
    require_parity(compare("blur x pass, " + name, buffers.blurred_x.texels, blurred.texels, coordinates_of(blurred), post_bounds));
    filter_input = buffers.blurred_x;
  }
  const post_images post = cpu_post_pass(filter_input, buffers, constants, 2);
  result.post_radiance = compare("post pass radiance, " + name, frame.radiance.texels, post.radiance.texels, coordinates_of(post.radiance), post_bounds);
  result.post_indirect = compare("post pass indirect, " + name, frame.indirect.texels, post.indirect.texels, coordinates_of(post.indirect), post_bounds);
  return result;
}

// The gather sums 150 (radial) or 400 (disk) terms of Eq. 3.2 in the same order on both sides;
// the sample positions, buckets and visibility are bit-identical (the kernel parity tests), and
// Eq. 3.2 differs by a few ulp per term: measured at most 3.3e-7 relative; bound 4e-6, or 1e-7
// absolute where the sum itself is tiny. No texel may differ in which samples it took.
const tolerance gather_rgba32f{1e-7f, 4e-6f, 16, 0.0, "150-400 terms of a few-ulp Eq. 3.2; same samples"};
// The coverage's coarse lights: weighted sums over a block of the RSM (16 texels in these frames,
// 1024 at the defaults) in the same order; llvmpipe may fuse a multiply-add per term. The extent
// is a mean square less a squared mean, so its error is relative to the mean square.
const tolerance coarse_rgba32f{1e-6f, 1e-5f, 16, 0.0, "block sums in the same order; the extent a difference of two"};
// The post pass: up to 81 bilateral taps with llvmpipe's exp, and the spot light term (sqrt, divides):
// measured at most 1.3e-5 relative on values under 1e-6 and 3.4e-7 absolute; bound 1e-6
// absolute or 2e-5 relative.
const tolerance post_rgba32f{1e-6f, 2e-5f, 64, 0.0, "exp over 81 taps, spot light term"};

}  // namespace

TEST_CASE("RSM pipeline matches the CPU mirror for every technique (Cornell box, spot light, rgba32f)") {
  for (const rsm_technique& technique : rsm_techniques()) {
    const std::string technique_name = technique.name;
    CAPTURE(technique_name);
    const pass_parity result = check_pipeline(make_cornell_box(), small_settings(technique.name), gather_rgba32f, post_rgba32f, coarse_rgba32f);
    if (technique.indirect) require_parity(result.gather);
    require_parity(result.post_radiance);
    require_parity(result.post_indirect);
  }
}

TEST_CASE("RSM pipeline with the coverage interleaved: the gather matches the CPU mirror, and the post filter restores the coverage's light") {
  // The Cornell box's ceiling lies behind the spot: the coverage alone lights it. A side of 3 (not
  // a divisor of the 16 blocks: the lattices differ in size) must match the mirror texel by texel,
  // differ from the whole sum at the raw gather, and come back to it after the post filter.
  rsm_pipeline_settings settings = small_settings("rsm-alg6");
  settings.coverage_interleave = 3;
  const pass_parity result = check_pipeline(make_cornell_box(), settings, gather_rgba32f, post_rgba32f, coarse_rgba32f);
  require_parity(result.gather);
  require_parity(result.post_radiance);
  require_parity(result.post_indirect);
  const shader_library& shaders = test_shaders();
  rsm_pipeline_settings whole_settings = small_settings("rsm-alg6");
  whole_settings.coverage_interleave = 1;
  require_parity(check_pipeline(make_cornell_box(), whole_settings, gather_rgba32f, post_rgba32f, coarse_rgba32f).gather);
  rsm_pipeline whole(shaders, make_cornell_box(), whole_settings);
  rsm_pipeline interleaved(shaders, make_cornell_box(), settings);
  const rsm_frame whole_frame = whole.render(), interleaved_frame = interleaved.render();
  const image whole_raw = whole.read_buffers().indirect, interleaved_raw = interleaved.read_buffers().indirect;
  double raw_difference = 0.0, raw_sum = 0.0, whole_sum = 0.0, interleaved_sum = 0.0;
  for (std::size_t i = 0; i < whole_raw.texels.size(); ++i) {
    raw_difference += std::abs(double(interleaved_raw.texels[i].x) - double(whole_raw.texels[i].x));
    raw_sum += double(whole_raw.texels[i].x);
  }
  for (std::size_t i = 0; i < whole_frame.indirect.texels.size(); ++i) {
    whole_sum += double(whole_frame.indirect.texels[i].x);
    interleaved_sum += double(interleaved_frame.indirect.texels[i].x);
  }
  REQUIRE(raw_sum > 0.0);
  CHECK(raw_difference / raw_sum > 0.05);  // each receiver gathers a ninth of the blocks
  CHECK(interleaved_sum == doctest::Approx(whole_sum).epsilon(0.03));
}

TEST_CASE("RSM pipeline matches the CPU mirror with a directional light and the full 2D filter") {
  rsm_pipeline_settings settings = small_settings("rsm-alg6");
  settings.filter = post_filter::full;
  const pass_parity result = check_pipeline(make_indirect_shadow_scene(), settings, gather_rgba32f, post_rgba32f, coarse_rgba32f);
  require_parity(result.gather);
  require_parity(result.post_radiance);
  require_parity(result.post_indirect);
}

TEST_CASE("RSM pipeline matches the CPU mirror in rgba16f, to half precision") {
  rsm_pipeline_settings settings = small_settings("rsm-alg3");
  settings.format = texel_format::rgba16f;
  // The GL passes store their results as half floats (11 significant bits), and llvmpipe
  // rounds toward zero when it does (see test_render_target): one half ulp, 2^-10 = 9.8e-4
  // relative, or 1e-4 absolute for values near 0 (half denormals).
  const tolerance half{1e-4f, 1e-3f, 0, 0.0, "outputs truncated to half floats"};
  const pass_parity result = check_pipeline(make_cornell_box(), settings, half, half, coarse_rgba32f);
  require_parity(result.gather);
  require_parity(result.post_radiance);
  require_parity(result.post_indirect);
}

TEST_CASE("RSM pipeline: visibility never adds light, texel by texel, and Alg. 6 equals Alg. 3") {
  const shader_library& shaders = test_shaders();
  const scene box = make_cornell_box();
  const auto indirect_of = [&](const char* technique) {
    rsm_pipeline pipeline(shaders, box, small_settings(technique));
    pipeline.render();
    return pipeline.read_buffers().indirect.texels;
  };
  const std::vector<glm::vec4> none = indirect_of("rsm-radial"), alg3 = indirect_of("rsm-alg3"), alg6 = indirect_of("rsm-alg6");
  std::size_t darker = 0;
  for (std::size_t i = 0; i < none.size(); ++i) {
    for (int c = 0; c < 3; ++c) {
      REQUIRE(alg6[i][c] <= none[i][c]);
      REQUIRE(alg3[i][c] == alg6[i][c]);
    }
    darker += alg6[i].x < none[i].x;
  }
  CHECK(darker > none.size() / 10);  // and it does remove light somewhere
}

TEST_CASE("RSM pipeline: direct light equals albedo / pi * E * shadow density; indirect light is added on top") {
  const shader_library& shaders = test_shaders();
  rsm_pipeline direct_only(shaders, make_cornell_box(), small_settings("direct"));
  const rsm_frame direct = direct_only.render();
  rsm_pipeline with_indirect(shaders, make_cornell_box(), small_settings("rsm-alg6"));
  const rsm_frame full = with_indirect.render();
  std::size_t lit = 0, brighter = 0;
  for (std::size_t i = 0; i < direct.radiance.texels.size(); ++i) {
    const float with = full.radiance.texels[i].r, without = direct.radiance.texels[i].r;
    REQUIRE(std::isfinite(with));
    REQUIRE(with >= without);
    lit += without > 0.0f;
    brighter += with > without * 1.01f;
  }
  CHECK(lit > 64 * 64 / 3);
  CHECK(brighter > 64 * 64 / 3);
  // The ceiling (top rows) is unlit by the downward spot light but gets indirect light.
  CHECK(direct.radiance.at(32, 62).r == 0.0f);
  REQUIRE(direct.pass_times.size() == 3);  // no RSM sampling pass for direct light
  REQUIRE(full.pass_times.size() == 5);  // the RSM, the coverage's coarse lights, the G-buffer, the gather, the post filter
  CHECK(full.pass_times[1].pass == "coverage lights");
  CHECK(full.pass_times[3].pass == "RSM sampling");
}

TEST_CASE("RSM pipeline sequences: render_next's first frame is render()'s, pass 3b matches its CPU mirror, render() starts over") {
  const shader_library& shaders = test_shaders();
  const scene box = make_cornell_box();
  rsm_pipeline_settings settings = small_settings("rsm-alg6");
  settings.temporal.blend = 0.3f;
  rsm_pipeline sequence(shaders, box, settings), single(shaders, box, settings);
  REQUIRE(sequence.accumulates());
  const rsm_frame first = sequence.render_next();
  CHECK_FALSE(sequence.last_temporal_inputs().history_valid);
  CHECK(first.indirect.texels == single.render().indirect.texels);  // no history, the settings' own pattern
  // The second frame: the camera and the light moved a little; the history is reprojected.
  camera moved = box.view;
  moved.position += glm::vec3(0.05f, 0.02f, 0.0f);
  scene_light light = box.lights[0];
  light.spot.position += glm::vec3(0.03f, 0.0f, 0.0f);
  sequence.set_camera(moved);
  sequence.set_light(0, light);
  sequence.render_next();
  const rsm_pass_buffers buffers = sequence.read_buffers();
  REQUIRE(sequence.last_temporal_inputs().history_valid);
  const image mirrored = cpu_temporal_pass(buffers.indirect, buffers.history, sequence.last_temporal_inputs(), buffers, sequence.constants(), 2);
  // The same arithmetic on the same read-back inputs; a reprojection that lands within an ulp of
  // a texel edge may pick the neighbouring history texel on one side: at most 0.5 % of the texels.
  require_parity(compare("temporal pass, cornell-box rsm-alg6", buffers.accumulated.texels, mirrored.texels, coordinates_of(mirrored),
                         {1e-6f, 1e-5f, 16, 0.005, "sums, a square root, a blend; reprojection near-ties"}));
  std::size_t blended = 0, surfaces = 0;
  for (std::size_t i = 0; i < buffers.indirect.texels.size(); ++i) {
    surfaces += buffers.indirect.texels[i].w < 0.0f;
    blended += buffers.accumulated.texels[i] != buffers.indirect.texels[i];
  }
  CHECK(blended > surfaces / 2);  // most receivers found their history
  // The pattern turned: the raw gather is not a fresh render's at these poses; render() is again.
  rsm_pipeline fresh(shaders, box, settings);
  fresh.set_camera(moved);
  fresh.set_light(0, light);
  const rsm_frame reference = fresh.render();
  fresh.read_buffers();
  CHECK(buffers.indirect.texels != fresh.read_buffers().indirect.texels);
  CHECK(sequence.render().indirect.texels == reference.indirect.texels);
}

TEST_CASE("RSM pipeline settings are validated with the setting's name") {
  const shader_library& shaders = test_shaders();
  rsm_pipeline_settings settings = small_settings("rsm-alg6");
  settings.slots = 0;
  CHECK_THROWS_WITH_AS(rsm_pipeline(shaders, make_cornell_box(), settings), doctest::Contains("slots must be a whole number in [1, 16]"), vplkit::error);
  settings = small_settings("rsm-alg7");
  CHECK_THROWS_WITH_AS(rsm_pipeline(shaders, make_cornell_box(), settings), doctest::Contains("rsm-alg6"), vplkit::error);
  settings = small_settings("rsm-alg6");
  settings.radius = 0.5f / 64.0f;  // half a texel: inside r_min
  CHECK_THROWS_WITH_AS(rsm_pipeline(shaders, make_cornell_box(), settings), doctest::Contains("max_radius"), vplkit::error);
  settings = small_settings("rsm-alg6");
  settings.coverage_interleave = 0;
  CHECK_THROWS_WITH_AS(rsm_pipeline(shaders, make_cornell_box(), settings), doctest::Contains("coverage-interleave"), vplkit::error);
  settings.coverage_interleave = rsm_coverage_max_interleave + 1;
  CHECK_THROWS_WITH_AS(rsm_pipeline(shaders, make_cornell_box(), settings), doctest::Contains("coverage-interleave"), vplkit::error);
  settings = small_settings("rsm-alg6");  // a 9-tap filter
  settings.coverage_interleave = 5;
  CHECK_THROWS_WITH_AS(rsm_pipeline(shaders, make_cornell_box(), settings), doctest::Contains("needs a post filter of at least 11 taps"), vplkit::error);
  settings.coverage_interleave = 4;
  settings.coverage_blocks = 2;
  CHECK_THROWS_WITH_AS(rsm_pipeline(shaders, make_cornell_box(), settings), doctest::Contains("exceeds coverage-blocks 2"), vplkit::error);
  settings.coverage_blocks = 0;  // no coverage: nothing to interleave
  CHECK_NOTHROW(rsm_pipeline(shaders, make_cornell_box(), settings));
  settings = small_settings("rsm-alg6");
  settings.indirect_divisor = 3;
  CHECK_THROWS_WITH_AS(rsm_pipeline(shaders, make_cornell_box(), settings), doctest::Contains("divisor"), vplkit::error);
  settings = small_settings("rsm-alg6");
  settings.rsm_size = 1 << 15;
  CHECK_THROWS_WITH_AS(rsm_pipeline(shaders, make_cornell_box(), settings), doctest::Contains("rsm-size must be a whole number in [1, 16384]"), vplkit::error);
  // Within the limits, but more than llvmpipe will allocate: the GL error names the texture.
  settings.rsm_size = 1 << 14;
  settings.width = settings.height = 16;
  CHECK_THROWS_WITH_AS(rsm_pipeline(shaders, make_cornell_box(), settings), doctest::Contains("16384x16384 rgba32ui texture"), vplkit::error);
}

TEST_CASE("built-in scenes: the instanced scene reaches the thesis's scale, every scene renders" * doctest::test_suite("slow")) {
  CHECK(make_instanced_scene().geometry.triangle_count() >= 250000);
  const shader_library& shaders = test_shaders();
  // (The teapot scenes need the npm mesh: the mesh tests render them.)
  for (const char* name : {"cornell-box", "indirect-shadow", "instanced", "boxes"}) {
    CAPTURE(name);
    rsm_pipeline_settings settings = small_settings("rsm-alg6");
    settings.width = settings.height = 32;
    rsm_pipeline pipeline(shaders, built_in_scene(name), settings);
    const rsm_frame frame = pipeline.render();
    float total = 0.0f;
    for (const glm::vec4& texel : frame.radiance.texels)
      for (int c = 0; c < 4; ++c) {
        REQUIRE(std::isfinite(texel[c]));
        total += texel[c];
      }
    CHECK(total > 0.0f);
  }
}

TEST_CASE("the occlusion scenes: the atrium reaches the thesis's Sponza scale, the occluder variants differ only in the panel" * doctest::test_suite("slow")) {
  const scene atrium = built_in_scene("atrium");
  CHECK(atrium.geometry.triangle_count() >= 250000);
  CHECK(atrium.lights[0].kind == light_kind::directional);
  // The tessellation scales the count (columns, arches and curtains) and is range-checked.
  CHECK(make_atrium_scene(8).geometry.triangle_count() < atrium.geometry.triangle_count() / 20);
  CHECK_THROWS_WITH_AS(make_atrium_scene(3), doctest::Contains("tessellation must be in [4, 512]"), vplkit::error);
  for (const vertex& v : atrium.geometry.vertices) {
    REQUIRE(std::isfinite(v.position.x + v.position.y + v.position.z));
    REQUIRE(glm::length(v.normal) == doctest::Approx(1.0f).epsilon(1e-4));
  }
  const scene dark = built_in_scene("occluder"), white = built_in_scene("occluder-white");
  REQUIRE(dark.geometry.vertices.size() == white.geometry.vertices.size());
  std::size_t different = 0;
  for (std::size_t i = 0; i < dark.geometry.vertices.size(); ++i) {
    CHECK(dark.geometry.vertices[i].position == white.geometry.vertices[i].position);
    different += dark.geometry.vertices[i].albedo != white.geometry.vertices[i].albedo;
  }
  CHECK(different == 24);  // the panel: a box of 6 quads
}

TEST_CASE("a mesh whose vertices share one albedo draws it as a constant attribute, bit for bit the image of the same mesh drawn with per-vertex albedo") {
  // mesh_buffers leaves a shared albedo (and texture coordinates without a textured range) out of
  // the GPU's vertex buffer, to hold large meshes once in memory; the vertex shader then reads the
  // context's current attribute value. The same scene with one extra vertex of another albedo,
  // which no triangle uses, takes the per-vertex path: every buffer must be the same bit for bit.
  // (A constant left unset, or set for one pass and not another, would give black or a stale
  // albedo in the G-buffer and the RSM's flux.)
  scene shared = make_cornell_box();
  for (vertex& v : shared.geometry.vertices) v.albedo = glm::vec3(0.75f, 0.5f, 0.25f);
  scene per_vertex = shared;
  per_vertex.geometry.vertices.push_back({glm::vec3(0.0f), glm::vec3(0.0f, 1.0f, 0.0f), glm::vec3(0.1f, 0.9f, 0.3f)});

  const rsm_pipeline_settings settings = small_settings("rsm-alg6");
  const auto buffers_of = [&](const scene& source) {
    rsm_pipeline pipeline(test_shaders(), source, settings);
    const rsm_frame frame = pipeline.render();
    return std::make_pair(frame, pipeline.read_buffers());
  };
  const auto [shared_frame, shared_buffers] = buffers_of(shared);
  const auto [per_vertex_frame, per_vertex_buffers] = buffers_of(per_vertex);
  const auto same_texels = [](const image& a, const image& b) {
    return a.width == b.width && a.height == b.height &&
           std::equal(a.texels.begin(), a.texels.end(), b.texels.begin(), [](const glm::vec4& x, const glm::vec4& y) {
             return std::memcmp(&x, &y, sizeof x) == 0;
           });
  };
  // The albedo reached the G-buffer: not black, and the value set.
  const glm::vec4 centre = shared_buffers.gbuffer[1].at({settings.width / 2, settings.height / 2});
  CHECK(glm::vec3(centre) == glm::vec3(0.75f, 0.5f, 0.25f));
  for (int i = 0; i < 3; ++i) CHECK_MESSAGE(same_texels(shared_buffers.gbuffer[i], per_vertex_buffers.gbuffer[i]), "G-buffer " << i);
  CHECK(same_texels(shared_buffers.indirect, per_vertex_buffers.indirect));
  CHECK(same_texels(shared_frame.radiance, per_vertex_frame.radiance));
  CHECK(same_texels(shared_frame.indirect, per_vertex_frame.indirect));
}
