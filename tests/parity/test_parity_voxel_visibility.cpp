// CPU/GPU parity of include/vplkit/voxel_visibility.hpp against shaders/lib/voxel_visibility.glsl:
// the march (voxel_light_visible, offsets and DDA; voxel_coarse_light_visible, the coverage's coarse
// lights with normals shorter than 1, through voxel_cells_from's matrix) over a grid built on the CPU and read by the
// shader from its packed RGBA32UI texture, for random receivers and pixel lights in a closed room
// cluttered with random triangles, and from outside the grid, on every target
// (tests/parity/targets.hpp). The harness's tables are float (RGBA32F textures or std430 buffers),
// so the packed words travel as two tables of their 16-bit halves, integers a float holds
// exactly, and the shader's voxel_fetch puts them back together bit for bit. And the gather that
// marches it (lib/rsm_gather.glsl with VPLKIT_VISIBILITY 8: one march per group of consecutive
// samples of a path, rsm_sample_group) against gather_rsm_with and voxel_rsm_visibility. And the
// word march itself (voxel_segment_visible) on a grid longer than a texel along every axis, with
// segments inside a word, across word boundaries and along an axis: each reads the copy along its
// major axis.
#include <doctest/doctest.h>

#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include <vplkit/voxel_visibility.hpp>

#include <vplkit/parity/doctest.hpp>

#include "tests/kernels/synthetic_rsm.hpp"
#include "tests/parity/targets.hpp"

using namespace vplkit;
using namespace vplkit::parity;

namespace {

// The packed grid as the harness's float tables (see the top comment): voxels_low and
// voxels_high, its words' 16-bit halves, which the shader's voxel_fetch puts back together.
std::vector<kernel_table> packed_grid_tables(const voxel_grid& grid) {
  const glm::ivec2 texture_size = voxel_texture_size(grid.shape.cells);
  std::vector<glm::vec4> low_halves, high_halves;
  for (const glm::uvec4& word : grid.texels) {
    low_halves.push_back(glm::vec4(word & 0xffffu));
    high_halves.push_back(glm::vec4(word >> 16u));
  }
  return {{"voxels_low", texture_size.x, texture_size.y, low_halves}, {"voxels_high", texture_size.x, texture_size.y, high_halves}};
}

}  // namespace

TEST_CASE("parity: voxel_light_visible over a packed grid of a cluttered closed room, on every target") {
  std::mt19937 random(41);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  std::normal_distribution<float> gaussian;
  // A room of zero-thickness quads, 10 x 6 x 4 units, and 60 random triangles in it; a grid of
  // 96 cells along its longest side (z spans one packed texel, x and y several rows).
  const glm::vec3 low(-5.0f, -3.0f, 0.0f), high(5.0f, 3.0f, 4.0f);
  voxel_grid_settings<float> grid_settings;
  grid_settings.resolution = 96;
  voxel_grid grid = make_voxel_grid(make_voxel_grid_shape(low, high, grid_settings));
  glm::vec3 corner[8];
  for (int i = 0; i < 8; ++i) corner[i] = glm::vec3(i & 1 ? high.x : low.x, i & 2 ? high.y : low.y, i & 4 ? high.z : low.z);
  const int faces[6][4] = {{0, 1, 3, 2}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 3, 7, 6}, {0, 2, 6, 4}, {1, 3, 7, 5}};
  for (const auto& f : faces) {
    voxel_grid_add_triangle(grid, corner[f[0]], corner[f[1]], corner[f[2]]);
    voxel_grid_add_triangle(grid, corner[f[0]], corner[f[2]], corner[f[3]]);
  }
  const auto inside = [&] { return low + (high - low) * glm::vec3(unit(random), unit(random), unit(random)); };
  for (int t = 0; t < 60; ++t) {
    const glm::vec3 a = inside();
    voxel_grid_add_triangle(grid, a, a + 0.6f * glm::vec3(gaussian(random), gaussian(random), gaussian(random)),
                            a + 0.6f * glm::vec3(gaussian(random), gaussian(random), gaussian(random)));
  }
  // Receivers and lights in the room, a tenth of the lights outside it (behind the walls, some
  // beyond the grid); random unit normals, flipped to face each other where the pair allows.
  kernel_inputs inputs = grid_of(64, 64, 4);
  for (std::size_t i = 0; i < inputs.size(); ++i) {
    const glm::vec3 x = inside();
    const glm::vec3 xp = unit(random) < 0.1f ? glm::vec3(14.0f * (unit(random) - 0.5f), 10.0f * (unit(random) - 0.5f), 8.0f * unit(random) - 2.0f) : inside();
    glm::vec3 n = glm::normalize(glm::vec3(gaussian(random), gaussian(random), gaussian(random)));
    glm::vec3 np = glm::normalize(glm::vec3(gaussian(random), gaussian(random), gaussian(random)));
    if (i % 8 != 0) {  // most pairs face each other, so that the march decides
      if (glm::dot(n, xp - x) < 0.0f) n = -n;
      if (glm::dot(np, x - xp) < 0.0f) np = -np;
    }
    inputs.floats[0][i] = glm::vec4(x, 0.0f);
    inputs.floats[1][i] = glm::vec4(n, 0.0f);
    inputs.floats[2][i] = glm::vec4(xp, 0.0f);
    // A coarse light's normal is a mean of unit normals: 0.2-1 long (and, once, 0: no direction).
    inputs.floats[3][i] = glm::vec4(np, i == 5 ? 0.0f : 0.2f + 0.8f * unit(random));
  }
  const voxel_march_settings<float> march;
  kernel_resources resources;
  resources.tables = packed_grid_tables(grid);
  resources.blocks = {settings_block("shape", grid.shape), settings_block("march", march)};
  std::vector<glm::vec4> cpu(inputs.size()), cpu_coarse(inputs.size());
  int hidden = 0, coarse_hidden = 0;
  const glm::mat4 to_cells = voxel_cells_from(grid.shape, glm::mat4(1.0f));
  for (std::size_t i = 0; i < inputs.size(); ++i) {
    const glm::vec3 x(inputs.floats[0][i]), n(inputs.floats[1][i]), xp(inputs.floats[2][i]), np(inputs.floats[3][i]);
    cpu[i] = glm::vec4(voxel_light_visible(voxel_grid_fetch{&grid}, grid.shape, march, x, n, xp, np), 0.0f, 0.0f, 0.0f);
    cpu_coarse[i] = glm::vec4(voxel_coarse_light_visible(voxel_grid_fetch{&grid}, grid.shape, march, to_cells, x, n, xp, np * inputs.floats[3][i].w), 0.0f,
                              0.0f, 0.0f);
    hidden += cpu[i].x == 0.0f ? 1 : 0;
    coarse_hidden += cpu_coarse[i].x == 0.0f ? 1 : 0;
  }
  // Both answers are exercised (the clutter hides some pairs, the walls every outside light).
  CHECK(hidden > 400);
  CHECK(hidden < 3600);
  CHECK(coarse_hidden > 400);
  CHECK(coarse_hidden < 3600);
  // A yes/no per pair: the same arithmetic in the same order, but a driver may fuse a multiply-add
  // in the DDA's boundary distances, which flips the cell order where a segment passes within a
  // rounding of a cell's edge, and then the answer where one of the two cells is occupied.
  for (const testing::target_run& run : testing::every_target()) {
    kernel_source source;
    source.name = "voxel_light_visible (" + run.name() + ")";
    CAPTURE(source.name);
    if (!testing::target_runs(run.where)) continue;
    source.includes = {"lib/voxel_visibility.glsl"};
    source.declarations = "uvec4 voxel_fetch(ivec2 t) { return uvec4(voxels_low(t)) | (uvec4(voxels_high(t)) << 16u); }\n";
    source.body =
        "fout0 = vec4(voxel_light_visible(shape, march, fin0.xyz, fin1.xyz, fin2.xyz, fin3.xyz), 0.0, 0.0, 0.0);\n"
        "fout1 = vec4(voxel_coarse_light_visible(shape, march, voxel_cells_from(shape, mat4(1.0)), fin0.xyz, fin1.xyz, fin2.xyz, fin3.xyz * fin3.w), "
        "0.0, 0.0, 0.0);";
    source.float_outputs = 2;
    const kernel_outputs gpu = run.run(source, inputs, run.where, resources);
    require_parity(compare(source.name, gpu.floats[0], cpu, inputs, {0.0f, 0.0f, 0, 0.002, "a discrete answer; near-ties at cell edges"}, 1));
    require_parity(compare(source.name + ", coarse light", gpu.floats[1], cpu_coarse, inputs,
                           {0.0f, 0.0f, 0, 0.002, "a discrete answer; near-ties at cell edges"}, 1));
  }
}

namespace {

// A mat4 as a GLSL constant, each float printed so that it reads back exactly.
std::string glsl_mat4(const glm::mat4& m) {
  std::string out = "mat4(";
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) {
      char number[32];
      std::snprintf(number, sizeof number, "%.9g", static_cast<double>(m[c][r]));
      out += std::string(number) + (c == 3 && r == 3 ? ")" : ", ");
    }
  return out;
}

}  // namespace

TEST_CASE("parity: the voxel gather, one march per group of samples, on the synthetic RSM with walls the RSM cannot see, on every target") {
  namespace t = vplkit::testing;
  constexpr int size = t::rsm_size;
  // The kernel tests' floor with a block on it, the flux varied per texel (so a group's largest
  // member is not its first), seen from the orthographic light.
  t::synthetic_rsm synthetic;
  synthetic.block_x0 = 0.3;
  synthetic.block_x1 = 0.9;
  synthetic.block_height = 0.8;
  std::vector<rsm_texel<float>> texels;
  std::vector<glm::vec4> position, normal, flux;
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      const rsm_texel<double> d = synthetic(glm::ivec2(x, y));
      texels.push_back({glm::vec3(d.position), glm::vec3(d.normal),
                        glm::vec3(1.0f, 0.25f + 0.25f * static_cast<float>(x % 4), 0.5f + 0.125f * static_cast<float>(y % 5))});
      position.push_back(glm::vec4(texels.back().position, 0.0f));
      normal.push_back(glm::vec4(texels.back().normal, 0.0f));
      flux.push_back(glm::vec4(texels.back().flux, 0.0f));
    }
  const auto rsm = [&](glm::ivec2 texel) { return texels[static_cast<std::size_t>(texel.y * size + texel.x)]; };
  // The grid: the floor, the block and 12 random walls standing on the floor (zero-thickness quads
  // the light sees edge-on or not at all), 96 cells along the 5.2-unit side.
  voxel_grid_settings<float> grid_settings;
  grid_settings.resolution = 96;
  voxel_grid grid = make_voxel_grid(make_voxel_grid_shape(glm::vec3(-2.6f, 0.0f, -2.6f), glm::vec3(2.6f, 2.0f, 2.6f), grid_settings));
  const auto quad = [&](glm::vec3 a, glm::vec3 b, glm::vec3 c, glm::vec3 d) {
    voxel_grid_add_triangle(grid, a, b, c);
    voxel_grid_add_triangle(grid, a, c, d);
  };
  quad({-2.56f, 0.0f, -2.56f}, {2.56f, 0.0f, -2.56f}, {2.56f, 0.0f, 2.56f}, {-2.56f, 0.0f, 2.56f});
  quad({0.3f, 0.8f, -2.56f}, {0.9f, 0.8f, -2.56f}, {0.9f, 0.8f, 2.56f}, {0.3f, 0.8f, 2.56f});
  quad({0.3f, 0.0f, -2.56f}, {0.3f, 0.8f, -2.56f}, {0.3f, 0.8f, 2.56f}, {0.3f, 0.0f, 2.56f});
  quad({0.9f, 0.0f, -2.56f}, {0.9f, 0.8f, -2.56f}, {0.9f, 0.8f, 2.56f}, {0.9f, 0.0f, 2.56f});
  std::mt19937 random(43);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  for (int w = 0; w < 12; ++w) {
    const glm::vec3 a(-2.4f + 4.8f * unit(random), 0.0f, -2.4f + 4.8f * unit(random));
    const float angle = 6.2831853f * unit(random), length = 0.4f + 0.8f * unit(random), height = 0.3f + 1.0f * unit(random);
    const glm::vec3 b = a + length * glm::vec3(std::cos(angle), 0.0f, std::sin(angle));
    quad(a, b, b + glm::vec3(0.0f, height, 0.0f), a + glm::vec3(0.0f, height, 0.0f));
  }
  // Receivers above the floor (some under the walls' tops, none off the map), random normals,
  // half of them turned to face the floor.
  constexpr int side = 32;
  kernel_inputs inputs = grid_of(side, side, 3, 1);
  std::normal_distribution<double> gaussian;
  for (std::size_t i = 0; i < inputs.size(); ++i) {
    const glm::dvec3 world(2.3 * (2.0 * unit(random) - 1.0), 0.05 + 1.2 * unit(random), 2.3 * (2.0 * unit(random) - 1.0));
    glm::dvec3 n = glm::normalize(glm::dvec3(gaussian(random), gaussian(random), gaussian(random)));
    if (i % 2 == 0 && n.y > 0.0) n.y = -n.y;
    const glm::uvec2 pixel(static_cast<unsigned>(i % side), static_cast<unsigned>(i / side));
    const gather_receiver<double> r = t::receiver_at(world, pixel, n);
    inputs.floats[0][i] = glm::vec4(glm::vec3(r.position), 0.0f);
    inputs.floats[1][i] = glm::vec4(glm::vec3(r.normal), 0.0f);
    inputs.floats[2][i] = glm::vec4(glm::vec2(r.rsm_coordinate), 0.0f, 0.0f);
    inputs.uints[0][i] = glm::uvec4(pixel, 0u, 0u);
  }
  radial_pattern_settings<float> radial;
  radial.paths = 12;
  radial.samples_per_path = 10;
  const rsm_gather_settings<float> settings = make_rsm_gather_settings(radial, disk_pattern_settings<float>{}, 0.4f, 8, glm::ivec2(size));
  const glm::mat4 light_to_cells = voxel_cells_from(grid.shape, glm::inverse(glm::mat4(t::light_view())));
  const auto gather_on_cpu = [&](const voxel_march_settings<float>& march) {
    std::vector<glm::vec4> out(inputs.size());
    for (std::size_t i = 0; i < inputs.size(); ++i) {
      const gather_receiver<float> receiver{glm::vec3(inputs.floats[0][i]), glm::vec3(inputs.floats[1][i]), glm::vec2(inputs.floats[2][i]),
                                            glm::uvec2(inputs.uints[0][i])};
      voxel_rsm_visibility<float, voxel_grid_fetch> visibility{voxel_grid_fetch{&grid}, grid.shape, march, light_to_cells};
      out[i] = glm::vec4(gather_rsm_with<rsm_pattern::radial>(receiver, rsm, settings, visibility), 0.0f);
    }
    return out;
  };
  voxel_march_settings<float> per_sample, grouped;
  per_sample.group = 1;
  grouped.group = 4;  // 10 samples a path: groups of 4, 4 and a shorter last one of 2
  const std::vector<glm::vec4> cpu_per_sample = gather_on_cpu(per_sample);
  const std::vector<glm::vec4> cpu = gather_on_cpu(grouped);
  // What the comparison needs: light at most receivers, the walls hiding some of it, and the
  // groups changing the result at many receivers (a twin that ignored them would fail).
  std::size_t lit = 0, changed = 0;
  for (std::size_t i = 0; i < cpu.size(); ++i) {
    lit += cpu[i].x > 0.0f;
    changed += cpu[i] != cpu_per_sample[i];
  }
  MESSAGE("the voxel gather: " << lit << " of " << cpu.size() << " receivers lit, " << changed << " changed by the groups");
  CHECK(lit > inputs.size() / 3);
  CHECK(changed > inputs.size() / 10);

  kernel_resources resources;
  resources.tables = packed_grid_tables(grid);
  resources.tables.insert(resources.tables.begin(), {{"rsm_position", size, size, position}, {"rsm_normal", size, size, normal}, {"rsm_flux", size, size, flux}});
  resources.blocks = {settings_block("settings", settings), settings_block("shape", grid.shape), settings_block("march", grouped)};
  // Eq. 3.2 per term and the sums' roundings as in test_parity_rsm_gather (120 terms), and the
  // verdicts: a yes/no per group whose march may flip where a segment passes within a rounding
  // of a cell's edge (see above), which moves that receiver's light by a whole group's: 2 % of the
  // receivers allowed (measured: none on llvmpipe's gl33, gl45 and gles3, Vulkan bit for bit).
  const float relative = static_cast<float>(2.0 * radial.paths * radial.samples_per_path * 0x1p-24 + 2e-6);
  for (const testing::target_run& run : testing::every_target()) {
    kernel_source source;
    source.name = "gather_rsm, voxel visibility, groups of 4 (" + run.name() + ")";
    CAPTURE(source.name);
    if (!testing::target_runs(run.where)) continue;
    source.defines = {{"VPLKIT_RSM_PATTERN", "0"}, {"VPLKIT_VISIBILITY", "8"}, {"VPLKIT_RSM_COVERAGE", "0"}};
    source.includes = {"lib/rsm_gather.glsl", "lib/voxel_visibility.glsl"};
    source.declarations =
        "rsm_texel rsm_fetch(ivec2 t) { return rsm_texel(rsm_position(t).xyz, rsm_normal(t).xyz, rsm_flux(t).xyz); }\n"
        "uvec4 voxel_fetch(ivec2 t) { return uvec4(voxels_low(t)) | (uvec4(voxels_high(t)) << 16u); }\n"
        "float rsm_voxel_visibility(vec3 x, vec3 n, vec3 xp, vec3 np) {\n"
        "  return voxel_light_visible(shape, march, " + glsl_mat4(light_to_cells) + ", x, n, xp, np);\n"
        "}\n"
        "int rsm_voxel_group() { return march.group; }\n";
    source.body = "fout0 = vec4(gather_rsm(gather_receiver(fin0.xyz, fin1.xyz, fin2.xy, uin0.xy), settings), 0.0);";
    source.float_outputs = 1;
    const kernel_outputs gpu = run.run(source, inputs, run.where, resources);
    require_parity(compare(source.name, gpu.floats[0], cpu, inputs,
                           {1e-6f, relative, 16, 0.02, "Eq. 3.2's error per term, the sums' roundings; a group's verdict may flip at a cell's edge"}, 3));
  }
}

TEST_CASE("parity: voxel_segment_visible across words and texels along every axis of a cluttered grid, on every target") {
  // 200 x 170 x 150 unit cells (every axis longer than a texel's 128 cells), 0.4 % occupied at
  // random; segments anywhere, short ones inside a word, ones across a word boundary, along an axis.
  voxel_grid_shape<float> shape;
  shape.cells = glm::ivec3(200, 170, 150);
  voxel_grid grid = make_voxel_grid(shape);
  std::mt19937 random(47);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  for (int z = 0; z < shape.cells.z; ++z)
    for (int y = 0; y < shape.cells.y; ++y)
      for (int x = 0; x < shape.cells.x; ++x)
        if (unit(random) < 0.004f) grid.mark(glm::ivec3(x, y, z));
  const glm::vec3 size(shape.cells);
  kernel_inputs inputs = grid_of(64, 64, 2);
  std::vector<glm::vec4> cpu(inputs.size());
  int hidden = 0;
  for (std::size_t i = 0; i < inputs.size(); ++i) {
    glm::vec3 a = glm::vec3(unit(random), unit(random), unit(random)) * (size + 8.0f) - 4.0f;
    glm::vec3 b = glm::vec3(unit(random), unit(random), unit(random)) * (size + 8.0f) - 4.0f;
    const int axis = static_cast<int>(i / 4) % 3;
    if (i % 4 == 1) {  // within one word along `axis`
      const float start = 32.0f * std::floor(unit(random) * 4.0f);
      b = a + 6.0f * (glm::vec3(unit(random), unit(random), unit(random)) - 0.5f);
      a[axis] = start + 0.5f + 31.0f * unit(random);
      b[axis] = start + 0.5f + 31.0f * unit(random);
    } else if (i % 4 == 2) {  // across a word boundary along `axis`
      const float boundary = 32.0f * (1.0f + std::floor(unit(random) * 3.0f));
      a[axis] = boundary - 40.0f * unit(random);
      b[axis] = boundary + 40.0f * unit(random);
    } else if (i % 4 == 3) {  // along `axis`
      b = a;
      b[axis] = unit(random) * size[axis];
    }
    inputs.floats[0][i] = glm::vec4(a, 0.0f);
    inputs.floats[1][i] = glm::vec4(b, 0.0f);
    cpu[i] = glm::vec4(voxel_segment_visible(voxel_grid_fetch{&grid}, grid.shape, a, b), 0.0f, 0.0f, 0.0f);
    hidden += cpu[i].x == 0.0f ? 1 : 0;
  }
  // Both answers are exercised.
  CHECK(hidden > 800);
  CHECK(hidden < 3300);
  kernel_resources resources;
  resources.tables = packed_grid_tables(grid);
  resources.blocks = {settings_block("shape", grid.shape)};
  for (const testing::target_run& run : testing::every_target()) {
    kernel_source source;
    source.name = "voxel_segment_visible, words (" + run.name() + ")";
    CAPTURE(source.name);
    if (!testing::target_runs(run.where)) continue;
    source.includes = {"lib/voxel_visibility.glsl"};
    source.declarations = "uvec4 voxel_fetch(ivec2 t) { return uvec4(voxels_low(t)) | (uvec4(voxels_high(t)) << 16u); }\n";
    source.body = "fout0 = vec4(voxel_segment_visible(shape, fin0.xyz, fin1.xyz), 0.0, 0.0, 0.0);";
    source.float_outputs = 1;
    const kernel_outputs gpu = run.run(source, inputs, run.where, resources);
    require_parity(compare(source.name, gpu.floats[0], cpu, inputs, {0.0f, 0.0f, 0, 0.002, "a discrete answer; near-ties at cell edges"}, 1));
  }
}
