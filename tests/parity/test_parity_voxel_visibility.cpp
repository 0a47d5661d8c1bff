// CPU/GPU parity of include/vplkit/voxel_visibility.hpp against shaders/lib/voxel_visibility.glsl:
// the march (voxel_light_visible, offsets and DDA; voxel_coarse_light_visible, the coverage's coarse
// lights with normals shorter than 1, through voxel_cells_from's matrix) over a grid built on the CPU and read by the
// shader from its packed RGBA32UI texture, for random receivers and pixel lights in a closed room
// cluttered with random triangles, and from outside the grid, on every target
// (tests/parity/targets.hpp). The harness's tables are float (RGBA32F textures or std430 buffers),
// so the packed words travel as two tables of their 16-bit halves, integers a float holds
// exactly, and the shader's voxel_fetch puts them back together bit for bit.
#include <doctest/doctest.h>

#include <random>
#include <vector>

#include <vplkit/voxel_visibility.hpp>

#include <vplkit/parity/doctest.hpp>

#include "tests/parity/targets.hpp"

using namespace vplkit;
using namespace vplkit::parity;

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
  const glm::ivec2 texture_size = voxel_texture_size(grid.shape.cells);
  std::vector<glm::vec4> low_halves, high_halves;
  for (const glm::uvec4& word : grid.texels) {
    low_halves.push_back(glm::vec4(word & 0xffffu));
    high_halves.push_back(glm::vec4(word >> 16u));
  }
  kernel_resources resources;
  resources.tables = {{"voxels_low", texture_size.x, texture_size.y, low_halves}, {"voxels_high", texture_size.x, texture_size.y, high_halves}};
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
