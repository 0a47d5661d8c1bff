// CPU/GPU parity of include/vplkit/final_gather.hpp against shaders/lib/final_gather.glsl: the
// whole final_gather_irradiance, receiver by receiver, with both form factors (VPLKIT_FORM_FACTOR
// 0 polygon, 1 point), on a synthetic distance cube map. The form factors have their own parity
// test (test_parity_form_factor.cpp); this one catches a twin whose cube-map geometry (faces,
// corners, the corner distances read across face edges), loop or sum differs. It runs on every
// target (tests/parity/targets.hpp): the cube map is a kernel_table, a texture or a storage buffer.
// And the small map's texels from a full one (final_gather_downsample.hpp against
// shaders/lib/final_gather_downsample.glsl): the solid-angle weights and the block loops.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include <vplkit/final_gather.hpp>
#include <vplkit/final_gather_downsample.hpp>

#include <vplkit/parity/doctest.hpp>

#include "tests/parity/targets.hpp"

using namespace vplkit;
using namespace vplkit::parity;

namespace {

constexpr int resolution = 6;  // M: 6 x 36 texels, each a quad light

// The cube map around o of the box [-1, 1]^3: each texel holds the radiance of the wall its
// centre ray hits, varied from texel to texel (so that a fetch of the wrong texel, face or corner
// shows), and that ray's distance, except a patch of face +y whose distance is doubled (a
// recess), which makes the quads around it non-planar and their corner distances means of unequal
// texels. Texel (face, i, j) is at (face * M + i, j) of the texture and of the vector.
struct synthetic_cube {
  glm::vec3 o{0.1f, -0.2f, 0.05f};
  std::vector<glm::vec4> texels;
  glm::vec4 operator()(int face, int i, int j) const { return texels[static_cast<std::size_t>(j * 6 * resolution + face * resolution + i)]; }
};

synthetic_cube make_cube() {
  synthetic_cube cube;
  cube.texels.resize(static_cast<std::size_t>(6 * resolution * resolution));
  const glm::vec3 wall[6] = {{0.9f, 0.1f, 0.1f}, {0.1f, 0.9f, 0.1f}, {0.8f, 0.8f, 0.8f}, {0.5f, 0.5f, 0.5f}, {0.2f, 0.2f, 0.9f}, {0.7f, 0.7f, 0.2f}};
  for (int face = 0; face < 6; ++face)
    for (int j = 0; j < resolution; ++j)
      for (int i = 0; i < resolution; ++i) {
        const glm::dvec3 d = glm::normalize(cube_texel_direction<double>(face, i, j, resolution));
        double distance = 1e30;
        int hit = 0;
        for (int axis = 0; axis < 3; ++axis) {
          if (d[axis] == 0.0) continue;
          const double t = ((d[axis] > 0.0 ? 1.0 : -1.0) - static_cast<double>(cube.o[axis])) / d[axis];
          if (t < distance) distance = t, hit = 2 * axis + (d[axis] > 0.0 ? 0 : 1);
        }
        if (face == 2 && i >= 2 && i <= 3 && j >= 1 && j <= 3) distance *= 2.0;
        const glm::vec3 radiance = wall[hit] * (0.75f + 0.125f * static_cast<float>((i + 2 * j) % 4));
        cube.texels[static_cast<std::size_t>(j * 6 * resolution + face * resolution + i)] = glm::vec4(radiance, static_cast<float>(distance));
      }
  return cube;
}

}  // namespace

TEST_CASE("parity: final_gather_irradiance with the polygon and the point form factor, on a synthetic distance cube map, on every target") {
  const synthetic_cube cube = make_cube();
  // Receivers within 0.5 of o (the walls are 0.8 or more from o), random normals.
  kernel_inputs inputs = grid_of(32, 32, 2);
  std::mt19937 random(41);
  std::uniform_real_distribution<float> uniform(-1.0f, 1.0f);
  std::normal_distribution<float> normal;
  for (std::size_t i = 0; i < inputs.size(); ++i) {
    glm::vec3 offset;
    do offset = glm::vec3(uniform(random), uniform(random), uniform(random));
    while (glm::dot(offset, offset) > 1.0f);
    inputs.floats[0][i] = glm::vec4(cube.o + 0.5f * offset, 0.0f);
    inputs.floats[1][i] = glm::vec4(glm::normalize(glm::vec3(normal(random), normal(random), normal(random))), 0.0f);
  }
  inputs.floats[0][0] = glm::vec4(cube.o, 0.0f);  // the reference point itself: the classic baseline
  kernel_resources resources;
  resources.tables = {{"cube", 6 * resolution, resolution, cube.texels}};
  const std::string o = "vec3(" + std::to_string(cube.o.x) + ", " + std::to_string(cube.o.y) + ", " + std::to_string(cube.o.z) + ")";
  REQUIRE(glm::vec3(std::stof(std::to_string(cube.o.x)), std::stof(std::to_string(cube.o.y)), std::stof(std::to_string(cube.o.z))) == cube.o);

  for (int form_factor = 0; form_factor <= 1; ++form_factor) {
    std::vector<glm::vec4> cpu(inputs.size());
    for (std::size_t i = 0; i < inputs.size(); ++i) {
      const glm::vec3 x(inputs.floats[0][i]), n(inputs.floats[1][i]);
      cpu[i] = glm::vec4(form_factor == 0 ? final_gather_irradiance<gather_form_factor::polygon>(x, n, cube.o, resolution, cube)
                                          : final_gather_irradiance<gather_form_factor::point>(x, n, cube.o, resolution, cube),
                         0.0f);
    }
    std::size_t lit = 0;
    for (const glm::vec4& e : cpu) lit += e.x > 0.0f;
    CHECK(lit == inputs.size());  // every receiver sees half the box: none is 0 on both sides
    for (const testing::target_run& run : testing::every_target()) {
      const std::string name = std::string(form_factor == 0 ? "final_gather_irradiance (polygon" : "final_gather_irradiance (point") + ", " +
                               run.name() + ")";
      CAPTURE(name);
      if (!testing::target_runs(run.where)) continue;
      kernel_source source;
      source.name = name;
      source.defines = {{"VPLKIT_FORM_FACTOR", std::to_string(form_factor)}};
      source.includes = {"lib/final_gather.glsl"};
      source.declarations = "vec4 small_cube_fetch(int face, int i, int j) { return cube(ivec2(face * " + std::to_string(resolution) + " + i, j)); }\n";
      source.body = "fout0 = vec4(final_gather_irradiance(fin0.xyz, fin1.xyz, " + o + ", " + std::to_string(resolution) + "), 0.0);";
      source.float_outputs = 1;
      const kernel_outputs gpu = run.run(source, inputs, run.where, resources);
      // The tolerance: each of the N = 6 M^2 terms is a form factor (the polygon's within the few
      // ulp of atan2 that test_parity_form_factor allows, of the angles it sums; the point's about 8
      // roundings) of corners a few ulp apart on the two sides (llvmpipe's normalize is an inverse
      // square root, not correctly rounded), about 4e-6 relative; the texels each corner reads are
      // exact decisions, no flip allowed (a division in cube_corner_distance once flipped them: see
      // its comment). The terms are positive and summed in the same order, so the sums part by at
      // most 2 (N - 1) roundings of the sum: relative 2 N 2^-24 + 4e-6 = 3.0e-5. Measured on
      // llvmpipe: polygon 7.5e-6, point 4e-7.
      const int terms = 6 * resolution * resolution;
      const float relative = static_cast<float>(2.0 * terms * 0x1p-24 + 4e-6);
      require_parity(compare(name, gpu.floats[0], cpu, inputs,
                             {1e-6f, relative, 16, 0.0, "form factors of corners a few ulp apart, 2 N roundings of a sum of N positive terms"}, 3));
    }
  }
}

TEST_CASE("parity: cube_downsample_texel (the small map's solid-angle-weighted means), on every target") {
  // A full map of S = 24 with random [radiance | distance] per texel, so that a wrong weight,
  // block or face shows; every texel of the small map at M = 3 and M = 4 (blocks of 8 and 6).
  const int face_size = 24;
  std::vector<glm::vec4> full(static_cast<std::size_t>(6 * face_size * face_size));
  std::mt19937 random(45);
  std::uniform_real_distribution<float> uniform(0.0f, 1.0f);
  for (glm::vec4& texel : full) texel = glm::vec4(uniform(random), uniform(random), 4.0f * uniform(random), 0.5f + 3.0f * uniform(random));
  const auto fetch = [&](int face, int i, int j) { return full[static_cast<std::size_t>(j * 6 * face_size + face * face_size + i)]; };
  kernel_resources resources;
  resources.tables = {{"full", 6 * face_size, face_size, full}};
  for (int m : {3, 4}) {
    kernel_inputs inputs = grid_of(6 * m, m, 1);
    std::vector<glm::vec4> cpu(inputs.size());
    for (int j = 0; j < m; ++j)
      for (int column = 0; column < 6 * m; ++column) {
        const std::size_t k = static_cast<std::size_t>(j * 6 * m + column);
        inputs.floats[0][k] = glm::vec4(static_cast<float>(column / m), static_cast<float>(column % m), static_cast<float>(j), 0.0f);
        cpu[k] = cube_downsample_texel<float>(column / m, column % m, j, face_size, m, fetch);
      }
    for (const testing::target_run& run : testing::every_target()) {
      const std::string name = "cube_downsample_texel (M = " + std::to_string(m) + ", " + run.name() + ")";
      CAPTURE(name);
      if (!testing::target_runs(run.where)) continue;
      kernel_source source;
      source.name = name;
      source.includes = {"lib/final_gather_downsample.glsl"};
      source.declarations = "vec4 full_cube_fetch(int face, int i, int j) { return full(ivec2(face * " + std::to_string(face_size) + " + i, j)); }\n";
      source.body = "ivec3 t = ivec3(fin0.xyz); fout0 = cube_downsample_texel(t.x, t.y, t.z, " + std::to_string(face_size) + ", " + std::to_string(m) + ");";
      source.float_outputs = 1;
      const kernel_outputs gpu = run.run(source, inputs, run.where, resources);
      // Each weight is a few roundings (GLSL's division and square root need not be correctly
      // rounded: a few ulp, 1e-6 relative at most); the block's b^2 positive terms are summed in
      // the same order on both sides, which part by at most 2 b^2 roundings: 2 b^2 2^-24 + 2e-6.
      const int block = face_size / m;
      const float relative = static_cast<float>(2.0 * block * block * 0x1p-24 + 2e-6);
      require_parity(compare(name, gpu.floats[0], cpu, inputs, {1e-6f, relative, 16, 0.0, "weights a few ulp apart, 2 b^2 roundings of a sum of b^2 positive terms"}, 3));
    }
  }
}
