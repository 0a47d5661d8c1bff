// CPU/GPU parity of include/vplkit/rsm_coverage.hpp against shaders/lib/rsm_coverage.glsl: a
// coarse light's irradiance on random geometry, and the reduction of RSM blocks read from a packed
// RSM (a uint table: a usampler2D, or a uvec4 storage buffer), on every target
// (vplkit/parity/parity.hpp). The gather's use of the coarse lights is compared
// pass by pass in tests/frontend/techniques/test_rsm_pipeline.cpp.
#include <doctest/doctest.h>

#include <random>

#include <vplkit/rsm_coverage.hpp>
#include <vplkit/rsm_packing.hpp>

#include <vplkit/parity/doctest.hpp>

#include "tests/parity/targets.hpp"


using namespace vplkit;
using namespace vplkit::parity;

TEST_CASE("parity: coarse_light_irradiance on random geometry, extents and unnormalised normals, on every target") {
  kernel_inputs inputs = geometry_inputs(23);
  std::mt19937 random(29);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  inputs.floats.push_back(std::vector<glm::vec4>(inputs.size()));
  for (std::size_t i = 0; i < inputs.size(); ++i) {
    inputs.floats[3][i] *= unit(random);                                                  // a mean normal, length <= 1
    inputs.floats[4][i] = glm::vec4(unit(random), 0.5f * unit(random), 2.0f * unit(random), unit(random) * unit(random));  // flux | extent
  }
  const irradiance_settings<float> settings{0.01f};
  kernel_source source;
  source.name = "coarse_light_irradiance";
  source.includes = {"lib/rsm_coverage.glsl"};
  source.body = "fout0 = vec4(coarse_light_irradiance(fin0.xyz, fin1.xyz, coarse_light(fin2.xyz, fin3.xyz, fin4.xyz, fin4.w), settings), 0.0);";
  source.float_outputs = 1;
  // The settings in a std140 block, which every target has (Vulkan has no default-block uniforms).
  kernel_resources resources;
  resources.blocks = {settings_block("settings", settings)};
  std::vector<glm::vec4> cpu(inputs.size());
  for (std::size_t i = 0; i < inputs.size(); ++i) {
    const coarse_light<float> light{glm::vec3(inputs.floats[2][i]), glm::vec3(inputs.floats[3][i]), glm::vec3(inputs.floats[4][i]),
                                    inputs.floats[4][i].w};
    cpu[i] = glm::vec4(coarse_light_irradiance(glm::vec3(inputs.floats[0][i]), glm::vec3(inputs.floats[1][i]), light, settings), 0.0f);
  }
  // Eq. 3.2's arithmetic (test_parity_irradiance.cpp's tolerance and its reasoning) and one more add.
  for (const testing::target_run& run : testing::every_target()) {
    const std::string target = run.name();
    CAPTURE(target);
    if (!testing::target_runs(run.where)) continue;
    source.name = std::string("coarse_light_irradiance") + " (" + target + ")";
    const kernel_outputs gpu = run.run(source, inputs, run.where, resources);
    require_parity(compare(source.name, gpu.floats[0], cpu, inputs,
                           {1e-6f, 1e-5f, 16, 0.0, "about 8 roundings, FMA contraction on llvmpipe, cancellation near tangency"}, 3));
  }
}

TEST_CASE("parity: reduce_rsm_block over a packed RSM, 8 x 8 blocks of 64^2 texels, empty texels among them, on every target") {
  // A random packed RSM as the gather reads it: depths, unit normals, flux; a fifth of the texels
  // empty. Each fragment of an 8 x 8 grid reduces its block of 8 x 8 texels.
  constexpr int size = 64, blocks = 8;
  std::mt19937 random(31);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  std::normal_distribution<float> normal;
  std::vector<glm::uvec4> packed(static_cast<std::size_t>(size * size));
  for (glm::uvec4& texel : packed) {
    if (unit(random) < 0.2f) continue;  // empty: all bits 0
    const glm::vec3 n = glm::normalize(glm::vec3(normal(random), normal(random), normal(random)));
    texel = pack_rsm_texel(-0.5f - 4.0f * unit(random), n, glm::vec3(unit(random), unit(random), 0.3f * unit(random)));
  }
  const rsm_unprojection<float> light = make_rsm_unprojection(1.2f, true, glm::ivec2(size));
  kernel_inputs inputs;
  inputs.width = inputs.height = blocks;
  kernel_source source;
  source.name = "reduce_rsm_block";
  source.defines = {{"VPLKIT_RSM_COVERAGE_REDUCE", "1"}};
  source.includes = {"lib/rsm_coverage.glsl", "lib/rsm_packing.glsl"};
  // The packed words as a uint table, the unprojection as a std140 block: every target has both.
  source.declarations = "rsm_texel rsm_fetch(ivec2 t) { return unpack_rsm_texel(rsm_packed(t), t, light); }\n";
  source.body =
      "coarse_light c = reduce_rsm_block(texel, 8, ivec2(64));\n"
      "fout0 = vec4(c.position, c.extent);\nfout1 = vec4(c.normal, 0.0);\nfout2 = vec4(c.flux, 0.0);";
  source.float_outputs = 3;
  kernel_resources resources;
  resources.uint_tables = {{"rsm_packed", size, size, packed}};
  resources.blocks = {settings_block("light", light)};
  std::vector<glm::vec4> position_extent(inputs.size()), normals(inputs.size()), flux(inputs.size());
  const auto fetch = [&](glm::ivec2 t) { return unpack_rsm_texel(packed[static_cast<std::size_t>(t.y * size + t.x)], t, light); };
  for (int y = 0; y < blocks; ++y)
    for (int x = 0; x < blocks; ++x) {
      const coarse_light<float> c = reduce_rsm_block<float>(glm::ivec2(x, y), blocks, glm::ivec2(size), fetch);
      const std::size_t i = static_cast<std::size_t>(y * blocks + x);
      position_extent[i] = glm::vec4(c.position, c.extent);
      normals[i] = glm::vec4(c.normal, 0.0f);
      flux[i] = glm::vec4(c.flux, 0.0f);
    }
  // Sums of about 50 products in the same order on both sides; llvmpipe may fuse a multiply-add
  // (one rounding fewer per term). The extent is a difference of two such sums (a mean square less
  // a squared mean, relative to the block's first light), so its error is relative to the mean
  // square of the block's offsets.
  for (const testing::target_run& run : testing::every_target()) {
    const std::string target = run.name();
    CAPTURE(target);
    if (!testing::target_runs(run.where)) continue;
    source.name = "reduce_rsm_block (" + target + ")";
    const kernel_outputs gpu = run.run(source, inputs, run.where, resources);
    require_parity(compare("reduce_rsm_block flux (" + target + ")", gpu.floats[2], flux, inputs, {0.0f, 1e-6f, 8, 0.0, "~50-term sums"}, 3));
    require_parity(compare("reduce_rsm_block normal (" + target + ")", gpu.floats[1], normals, inputs, {1e-6f, 1e-5f, 16, 0.0, "~50-term weighted sums"}, 3));
    require_parity(compare("reduce_rsm_block position and extent (" + target + ")", gpu.floats[0], position_extent, inputs,
                           {1e-5f, 1e-5f, 16, 0.0, "~50-term weighted sums; the extent a difference of two"}, 4));
  }
}

// Issue 38: include/vplkit/rsm_coarse_visibility.hpp against lib/rsm_coarse_visibility.glsl.
#include <vplkit/rsm_coarse_visibility.hpp>

#include <glm/gtc/matrix_transform.hpp>

namespace {

glm::mat4 cube_face_view(int face) { return glm::lookAt(glm::vec3(0.0f), cube_face_axis<float>(face), cube_face_up<float>(face)); }

// A room around the light at the origin (walls at x = -2.5 and 2, y = -1.9 and 1, z = +-2.2) with a
// partition x = 0.8, |y| < 0.5 and |z| < 0.6: the eye-space z of the nearest surface along each
// texel's centre ray of each face.
float room_depth(int face, glm::ivec2 texel, const rsm_unprojection<float>& unprojection) {
  const glm::vec2 ray = unprojection.ray_origin + glm::vec2(texel) * unprojection.ray_step;
  const glm::vec3 d = glm::mat3(glm::inverse(cube_face_view(face))) * glm::vec3(ray, -1.0f);
  float nearest = 1e30f;
  const glm::vec3 low(-2.5f, -1.9f, -2.2f), high(2.0f, 1.0f, 2.2f);
  for (int axis = 0; axis < 3; ++axis)
    if (d[axis] != 0.0f) nearest = std::min(nearest, ((d[axis] > 0.0f ? high : low)[axis]) / d[axis]);
  if (d.x > 0.0f) {
    const float s = 0.8f / d.x;
    if (std::abs(d.y * s) < 0.5f && std::abs(d.z * s) < 0.6f) nearest = std::min(nearest, s);
  }
  return -nearest;
}

}  // namespace

TEST_CASE("parity: coarse_light_cube_visibility in a room with a partition, from two gathering faces, on every target") {
  constexpr int size = 64;
  const rsm_unprojection<float> light = make_rsm_unprojection(1.0f, true, glm::ivec2(size));
  // The six faces' depths stacked (face g in rows 64 g to 64 g + 63), the depth in the first word.
  std::vector<glm::uvec4> depths(static_cast<std::size_t>(size * size * 6));
  std::vector<float> depth_values(depths.size());
  for (int face = 0; face < 6; ++face)
    for (int y = 0; y < size; ++y)
      for (int x = 0; x < size; ++x) {
        const std::size_t i = static_cast<std::size_t>((face * size + y) * size + x);
        depth_values[i] = room_depth(face, glm::ivec2(x, y), light);
        depths[i] = glm::uvec4(float_bits(depth_values[i]), 0u, 0u, 0u);
      }
  const auto face_depth = [&](int face, glm::ivec2 t) { return depth_values[static_cast<std::size_t>((face * size + t.y) * size + t.x)]; };
  std::mt19937 random(37);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  const auto in_room = [&] { return glm::vec3(-2.4f + 4.3f * unit(random), -1.8f + 2.7f * unit(random), -2.1f + 4.2f * unit(random)); };
  for (int gathering : {0, 3}) {
    CAPTURE(gathering);
    const glm::mat4 view = cube_face_view(gathering), light_from_view = glm::inverse(view);
    cube_depth_frames<float> frames;
    frames.cube_from_light = light_from_view;
    // cube_from_light as a uint table: one row, a column per texel.
    std::vector<glm::uvec4> frame_bits;
    for (int c = 0; c < 4; ++c) {
      const glm::vec4 column = frames.cube_from_light[c];
      frame_bits.push_back(glm::uvec4(float_bits(column.x), float_bits(column.y), float_bits(column.z), float_bits(column.w)));
    }
    kernel_inputs inputs = grid_of(64, 64, 2);
    std::vector<glm::vec4> cpu(inputs.size());
    int hidden = 0;
    for (std::size_t i = 0; i < inputs.size(); ++i) {
      const glm::vec3 x = transform_point(view, in_room()), x_c = transform_point(view, in_room());
      inputs.floats[0][i] = glm::vec4(x, 0.0f);
      inputs.floats[1][i] = glm::vec4(x_c, 0.0f);
      cpu[i] = glm::vec4(coarse_light_cube_visibility(x, x_c, frames, light, glm::ivec2(size), face_depth), 0.0f, 0.0f, 0.0f);
      hidden += cpu[i].x == 0.0f;
    }
    // Both answers occur (160 to 185 of 4096 hidden: the partition): the test compares decisions, not one constant.
    CHECK(hidden > 100);
    CHECK(hidden < 4096 - 100);
    kernel_source source;
    source.includes = {"lib/rsm_coarse_visibility.glsl"};
    source.declarations =
        "float rsm_face_depth(int face, ivec2 t) { return uintBitsToFloat(faces(ivec2(t.x, t.y + 64 * face)).x); }\n"
        "mat4 frame_matrix(int m) {\n"
        "  return mat4(uintBitsToFloat(frames(ivec2(0, m))), uintBitsToFloat(frames(ivec2(1, m))), uintBitsToFloat(frames(ivec2(2, m))),\n"
        "              uintBitsToFloat(frames(ivec2(3, m))));\n"
        "}\n";
    source.body =
        "cube_depth_frames f;\n"
        "f.cube_from_light = frame_matrix(0);\n"
        "fout0 = vec4(coarse_light_cube_visibility(fin0.xyz, fin1.xyz, f, light, ivec2(64)), 0.0, 0.0, 0.0);";
    source.float_outputs = 1;
    kernel_resources resources;
    resources.uint_tables = {{"faces", size, size * 6, depths}, {"frames", 4, 1, frame_bits}};
    resources.blocks = {settings_block("light", light)};
    for (const testing::target_run& run : testing::every_target()) {
      const std::string target = run.name();
      CAPTURE(target);
      if (!testing::target_runs(run.where)) continue;
      source.name = "coarse_light_cube_visibility (" + target + ")";
      const kernel_outputs gpu = run.run(source, inputs, run.where, resources);
      // 0 or 1 from texel floors and slab comparisons: a point within a rounding of a texel's edge
      // or of the slab's bounds may flip (FMA contraction on llvmpipe).
      require_parity(compare(source.name, gpu.floats[0], cpu, inputs, {0.0f, 0.0f, 0, 0.002, "decisions that flip on near-ties"}, 3));
    }
  }
}
