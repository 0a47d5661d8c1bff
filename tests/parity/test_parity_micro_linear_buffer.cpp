// CPU/GPU parity of include/vplkit/micro_linear_buffer.hpp against shaders/lib/micro_linear_buffer.glsl: elevation_bucket and the verdicts of Alg. 2, 3 and 6, texel by
// texel (vplkit/parity/parity.hpp).
#include <doctest/doctest.h>

#include <array>
#include <cstring>
#include <random>

#include <glm/gtc/matrix_transform.hpp>

#include <vplkit/micro_linear_buffer.hpp>

#include <vplkit/gl/settings_uniforms.hpp>
#include <vplkit/parity/doctest.hpp>

#include "tests/parity/targets.hpp"

using namespace vplkit;
using namespace vplkit::parity;

TEST_CASE("parity: elevation_bucket makes the same decision on both sides, boundaries included, on every target") {
  random_inputs random(11);
  kernel_inputs inputs = grid_of(64, 64, 2);
  const int slots = 5;
  const elevation_slots<float> table = make_elevation_slots<float>(slots);
  for (std::size_t i = 0; i < inputs.size(); ++i) {
    inputs.floats[0][i] = glm::vec4(random.point(2.0f), 0.0f);
    inputs.floats[1][i] = glm::vec4(random.point(2.0f), 0.0f);
    if (i % 4 == 0) {
      // Exactly on a boundary: dz = tangent * |dxy| computed in float as the kernel does.
      const glm::vec3 x(inputs.floats[0][i]);
      const float dx = random.uniform(-2.0f, 2.0f), dy = random.uniform(-2.0f, 2.0f);
      const float horizontal = std::sqrt(dx * dx + dy * dy);
      const float tangent = table.boundary_tangent[static_cast<std::size_t>(i / 4) % (slots - 1)];
      inputs.floats[1][i] = glm::vec4(x.x + dx, x.y + dy, x.z + tangent * horizontal, 0.0f);
    }
  }
  inputs.floats[0][1] = inputs.floats[1][1] = glm::vec4(0.5f);  // coincident
  kernel_source source;
  source.name = "elevation_bucket";
  source.includes = {"lib/micro_linear_buffer.glsl"};
  source.body = "uout0 = uvec4(uint(elevation_bucket(fin0.xyz, fin1.xyz, slots)), 0u, 0u, 0u);";
  source.uint_outputs = 1;
  // The table as a std140 block (its float array at a 16-byte stride), which every target has.
  kernel_resources resources;
  resources.blocks = {settings_block("slots", table)};
  std::vector<glm::uvec4> cpu(inputs.size());
  for (std::size_t i = 0; i < inputs.size(); ++i)
    cpu[i] = glm::uvec4(static_cast<unsigned>(elevation_bucket(glm::vec3(inputs.floats[0][i]), glm::vec3(inputs.floats[1][i]), table)), 0u, 0u, 0u);
  // Subtractions, multiplies, one add, sqrt and compares are IEEE-exact on both sides, and the
  // tangents are the same floats: no flip is allowed, even on the boundaries.
  for (const testing::target_run& run : testing::every_target()) {
    const std::string target = run.name();
    CAPTURE(target);
    if (!testing::target_runs(run.where)) continue;
    source.name = std::string("elevation_bucket") + " (" + target + ")";
    const kernel_outputs gpu = run.run(source, inputs, run.where, resources);
    require_parity(compare_exact(source.name + " (exact)", gpu.uints[0], cpu, inputs, 0.0, 1));
  }
}

TEST_CASE("parity: elevation_bucket_about makes the same decision on both sides, boundaries included, on every target") {
  random_inputs random(12);
  kernel_inputs inputs = grid_of(64, 64, 3);
  const int slots = 8;
  const elevation_slots<float> table = make_elevation_slots<float>(slots);
  for (std::size_t i = 0; i < inputs.size(); ++i) {
    inputs.floats[0][i] = glm::vec4(random.point(2.0f), 0.0f);
    inputs.floats[1][i] = glm::vec4(random.point(2.0f), 0.0f);
    inputs.floats[2][i] = glm::vec4(random.unit_vector(), 0.0f);  // up
    if (i % 4 == 0) {
      // On the boundary at elevation 0 (8 slots have one there): a point in the plane across `up`.
      const glm::vec3 up(inputs.floats[2][i]), d(inputs.floats[1][i] - inputs.floats[0][i]);
      inputs.floats[1][i] = inputs.floats[0][i] + glm::vec4(d - glm::dot(d, up) * up, 0.0f);
    }
    if (i % 8 == 1) inputs.floats[2][i] = glm::vec4(0, 0, 1, 0);  // the thesis's axis
  }
  kernel_source source;
  source.name = "elevation_bucket_about";
  source.includes = {"lib/micro_linear_buffer.glsl"};
  source.body = "uout0 = uvec4(uint(elevation_bucket_about(fin0.xyz, fin1.xyz, fin2.xyz, slots)), 0u, 0u, 0u);";
  source.uint_outputs = 1;
  // The table as a std140 block (its float array at a 16-byte stride), which every target has.
  kernel_resources resources;
  resources.blocks = {settings_block("slots", table)};
  std::vector<glm::uvec4> cpu(inputs.size());
  for (std::size_t i = 0; i < inputs.size(); ++i)
    cpu[i] = glm::uvec4(static_cast<unsigned>(elevation_bucket_about(glm::vec3(inputs.floats[0][i]), glm::vec3(inputs.floats[1][i]),
                                                                     glm::vec3(inputs.floats[2][i]), table)),
                        0u, 0u, 0u);
  // A dot product and a vector less its projection: multiply-adds that llvmpipe may fuse, so a
  // point within an ulp of a boundary can fall on either side. None did in this grid (the
  // boundary points above included); allow none.
  for (const testing::target_run& run : testing::every_target()) {
    const std::string target = run.name();
    CAPTURE(target);
    if (!testing::target_runs(run.where)) continue;
    source.name = std::string("elevation_bucket_about") + " (" + target + ")";
    const kernel_outputs gpu = run.run(source, inputs, run.where, resources);
    require_parity(compare_exact(source.name, gpu.uints[0], cpu, inputs, 0.0, 1));
  }
}

TEST_CASE("parity: alg6_ray's verdicts on random three-sample paths, and alg6_ray_in_front, on every target") {
  // Each texel: a receiver (fin0) and three samples, position | slot (fin1..3) and normal (fin4..6),
  // on a few shared planes so that predecessors pass their verdicts on, or not, both ways.
  random_inputs random(13);
  kernel_inputs inputs = grid_of(64, 64, 7);
  const glm::vec3 normals[3] = {{0, 0, 1}, glm::normalize(glm::vec3(1, 0, 1)), {-1, 0, 0}};
  for (std::size_t i = 0; i < inputs.size(); ++i) {
    inputs.floats[0][i] = glm::vec4(random.point(2.0f), 0.0f);
    for (int k = 0; k < 3; ++k) {
      const glm::vec3 n = normals[random.uniform_uint(0, 2)] * (random.uniform_uint(0, 3) == 0 ? -1.0f : 1.0f);
      glm::vec3 p = random.point(2.0f);
      p -= glm::dot(p, n) * n;  // on the plane through the origin
      inputs.floats[static_cast<std::size_t>(1 + k)][i] = glm::vec4(p, static_cast<float>(random.uniform_uint(0, 4)));
      inputs.floats[static_cast<std::size_t>(4 + k)][i] = glm::vec4(n, 0.0f);
    }
  }
  kernel_source source;
  source.name = "micro_linear_buffer_alg6_ray";
  source.includes = {"lib/micro_linear_buffer.glsl"};
  source.body = R"(
    micro_linear_buffer b;
    micro_linear_buffer_reset(b, 5);
    float v0 = micro_linear_buffer_alg6_ray(b, int(fin1.w), fin0.xyz, fin1.xyz, fin4.xyz);
    float v1 = micro_linear_buffer_alg6_ray(b, int(fin2.w), fin0.xyz, fin2.xyz, fin5.xyz);
    float v2 = micro_linear_buffer_alg6_ray(b, int(fin3.w), fin0.xyz, fin3.xyz, fin6.xyz);
    fout0 = vec4(v0, v1, v2, alg6_ray_in_front(fin0.xyz, fin4.xyz, fin2.xyz, 0.01) ? 1.0 : 0.0);)";
  source.float_outputs = 1;
  std::vector<glm::vec4> cpu(inputs.size());
  for (std::size_t i = 0; i < inputs.size(); ++i) {
    micro_linear_buffer<float> b;
    micro_linear_buffer_reset(b, 5);
    glm::vec4 out(0.0f);
    for (int k = 0; k < 3; ++k) {
      const glm::vec4 sample = inputs.floats[static_cast<std::size_t>(1 + k)][i];
      out[k] = micro_linear_buffer_alg6_ray(b, static_cast<int>(sample.w), glm::vec3(inputs.floats[0][i]), glm::vec3(sample),
                                            glm::vec3(inputs.floats[static_cast<std::size_t>(4 + k)][i]));
    }
    out.w = alg6_ray_in_front(glm::vec3(inputs.floats[0][i]), glm::vec3(inputs.floats[4][i]), glm::vec3(inputs.floats[2][i]), 0.01f) ? 1.0f : 0.0f;
    cpu[i] = out;
  }
  // Verdicts are small integers decided by comparisons of dot products that llvmpipe may fuse: a
  // decision within an ulp of its threshold could flip; none did on this grid, and none is allowed.
  for (const testing::target_run& run : testing::every_target()) {
    const std::string target = run.name();
    CAPTURE(target);
    if (!testing::target_runs(run.where)) continue;
    source.name = std::string("micro_linear_buffer_alg6_ray") + " (" + target + ")";
    const kernel_outputs gpu = run.run(source, inputs, run.where, {});
    require_parity(compare(source.name, gpu.floats[0], cpu, inputs, {0.0f, 0.0f, 0, 0.0, "integer verdicts"}, 4));
  }
}

TEST_CASE("parity: micro_linear_buffer Alg. 2, 3 and 6 verdicts on random slot sequences, on every target") {
  // Each texel holds a path of 10 slot indices (4 bits each, packed into two words) and a slot
  // count; the outputs are the verdict bit masks of the three algorithms, and the sum of the
  // unclamped Alg. 6 values (which exercises the decrements).
  random_inputs random(12);
  kernel_inputs inputs = grid_of(64, 64, 0, 1);
  for (std::size_t i = 0; i < inputs.size(); ++i) {
    const unsigned slots = 1u + static_cast<unsigned>(i % micro_linear_buffer_max_slots);
    glm::uvec4 packed(0u, 0u, slots, 0u);
    for (unsigned sample_index = 0; sample_index < 10; ++sample_index) {
      const unsigned index = random.uniform_uint(0, slots - 1);
      if (sample_index < 5) packed.x |= index << (4 * sample_index);
      else packed.y |= index << (4 * (sample_index - 5));
    }
    inputs.uints[0][i] = packed;
  }
  kernel_source source;
  source.name = "micro_linear_buffer";
  source.includes = {"lib/micro_linear_buffer.glsl"};
  source.body = R"(
    int slots = int(uin0.z);
    micro_linear_buffer alg2; micro_linear_buffer alg3; micro_linear_buffer alg6;
    micro_linear_buffer_reset(alg2, slots);
    micro_linear_buffer_reset(alg3, slots);
    micro_linear_buffer_reset(alg6, slots);
    uint mask2 = 0u, mask3 = 0u, mask6 = 0u;
    float sum6 = 0.0;
    for (int sample_index = 0; sample_index < 10; ++sample_index) {
      uint word = sample_index < 5 ? uin0.x : uin0.y;
      int index = int((word >> uint(4 * (sample_index % 5))) & 15u);
      if (micro_linear_buffer_alg2(alg2, index) > 0.5) mask2 |= 1u << uint(sample_index);
      if (micro_linear_buffer_alg3(alg3, index) > 0.5) mask3 |= 1u << uint(sample_index);
      float nu = micro_linear_buffer_alg6(alg6, index);
      sum6 += nu;
      if (clamp(nu, 0.0, 1.0) > 0.5) mask6 |= 1u << uint(sample_index);
    }
    uout0 = uvec4(mask2, mask3, mask6, floatBitsToUint(sum6));)";
  source.uint_outputs = 1;
  std::vector<glm::uvec4> cpu(inputs.size());
  for (std::size_t i = 0; i < inputs.size(); ++i) {
    const glm::uvec4& in = inputs.uints[0][i];
    const int slots = static_cast<int>(in.z);
    micro_linear_buffer<float> alg2, alg3, alg6;
    micro_linear_buffer_reset(alg2, slots);
    micro_linear_buffer_reset(alg3, slots);
    micro_linear_buffer_reset(alg6, slots);
    unsigned mask2 = 0, mask3 = 0, mask6 = 0;
    float sum6 = 0.0f;
    for (int sample_index = 0; sample_index < 10; ++sample_index) {
      const unsigned word = sample_index < 5 ? in.x : in.y;
      const int index = static_cast<int>((word >> (4 * (sample_index % 5))) & 15u);
      if (micro_linear_buffer_alg2(alg2, index) > 0.5f) mask2 |= 1u << sample_index;
      if (micro_linear_buffer_alg3(alg3, index) > 0.5f) mask3 |= 1u << sample_index;
      const float nu = micro_linear_buffer_alg6(alg6, index);
      sum6 += nu;
      if (glm::clamp(nu, 0.0f, 1.0f) > 0.5f) mask6 |= 1u << sample_index;
    }
    std::uint32_t sum_bits;
    std::memcpy(&sum_bits, &sum6, sizeof sum_bits);
    cpu[i] = glm::uvec4(mask2, mask3, mask6, sum_bits);
  }
  // Small integers in float: every operation is exact, so everything must match to the bit.
  for (const testing::target_run& run : testing::every_target()) {
    const std::string target = run.name();
    CAPTURE(target);
    if (!testing::target_runs(run.where)) continue;
    source.name = std::string("micro_linear_buffer") + " (" + target + ")";
    const kernel_outputs gpu = run.run(source, inputs, run.where, {});
    require_parity(compare_exact(source.name + " (exact)", gpu.uints[0], cpu, inputs));
    // And on the GPU too, Alg. 6 agrees with Alg. 3.
    std::size_t alg6_differs = 0;
    for (const glm::uvec4& out : gpu.uints[0]) alg6_differs += out.y != out.z;
    CHECK(alg6_differs == 0);
  }
}
