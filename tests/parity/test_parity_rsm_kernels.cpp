// CPU/GPU parity of the paper-000 kernels: polynomial trigonometry, the two sampling patterns,
// the point transforms, Alg. 4, the bilateral filter and the whole gather on a synthetic RSM.
#include <doctest/doctest.h>

#include <cstring>
#include <random>

#include <glm/gtc/matrix_transform.hpp>

#include <vplkit/bilateral.hpp>
#include <vplkit/polynomial_math.hpp>
#include <vplkit/rsm_gather.hpp>
#include <vplkit/rsm_pattern.hpp>
#include <vplkit/shadow.hpp>
#include <vplkit/transform.hpp>

#include "frontend/gl/settings_uniforms.hpp"
#include "tests/parity/parity_harness.hpp"

using namespace vplkit;
using namespace vplkit::parity;

namespace {

kernel_inputs grid_of(int width, int height, int float_inputs, int uint_inputs = 0) {
  kernel_inputs inputs;
  inputs.width = width;
  inputs.height = height;
  inputs.floats.assign(static_cast<std::size_t>(float_inputs), std::vector<glm::vec4>(inputs.size()));
  inputs.uints.assign(static_cast<std::size_t>(uint_inputs), std::vector<glm::uvec4>(inputs.size()));
  return inputs;
}

}  // namespace

TEST_CASE("parity: direction_from_angle") {
  kernel_inputs inputs = grid_of(64, 64, 1);
  std::mt19937 random(20);
  std::uniform_real_distribution<float> angle(-20.0f, 20.0f);
  for (std::size_t i = 0; i < inputs.size(); ++i) inputs.floats[0][i] = glm::vec4(angle(random), angle(random) * 0.2f, 0.0f, 0.0f);
  inputs.floats[0][0].x = 0.0f;
  inputs.floats[0][1].x = 3.14159265f;
  kernel_source source;
  source.name = "direction_from_angle";
  source.includes = {"lib/polynomial_math.glsl"};
  source.body = "fout0 = vec4(direction_from_angle(fin0.x), direction_from_turns(fin0.y));";
  source.float_outputs = 1;
  const kernel_outputs gpu = run_fragment(source, inputs);
  std::vector<glm::vec4> cpu(inputs.size());
  for (std::size_t i = 0; i < inputs.size(); ++i)
    cpu[i] = glm::vec4(direction_from_angle(inputs.floats[0][i].x), direction_from_turns(inputs.floats[0][i].y));
  // Multiplies, adds and one floor: exact on both sides unless llvmpipe contracts a multiply-add
  // into an FMA (one rounding less per step), which would show as a few ulp.
  require_parity(compare("direction_from_angle, direction_from_turns", gpu.floats[0], cpu, inputs,
                         {0.0f, 0.0f, 4, 0.0, "+,*,floor only; FMA at most"}, 4));
}

TEST_CASE("parity: radial_pattern_sample and rsm_disk_sample, offsets and weights") {
  // Texel (x, y) evaluates path x % 16, sample y % 16 for receiver pixel (x, y): 4096 samples.
  const kernel_inputs inputs = grid_of(64, 64, 0, 1);
  kernel_inputs indexed = inputs;
  for (std::size_t i = 0; i < indexed.size(); ++i)
    indexed.uints[0][i] = glm::uvec4(static_cast<unsigned>(i % 64), static_cast<unsigned>(i / 64), 0u, 0u);
  radial_pattern_settings<float> settings;
  settings.paths = 16;
  settings.samples_per_path = 16;
  settings.seed = 99;
  const radial_pattern_constants<float> constants = make_radial_pattern_constants(settings);
  disk_pattern_settings<float> disk;
  disk.seed = 5;
  kernel_source source;
  source.name = "patterns";
  source.includes = {"lib/rsm_pattern.glsl"};
  source.declarations = "uniform radial_pattern_constants radial;\nuniform disk_pattern_settings disk;\n";
  source.body = R"(
    pattern_sample r = radial_pattern_sample(int(uin0.x % 16u), int(uin0.y % 16u), uin0.xy, radial);
    pattern_sample d = rsm_disk_sample(int(uin0.x + 64u * uin0.y), disk);
    fout0 = vec4(r.offset, r.weight, 0.0);
    fout1 = vec4(d.offset, d.weight, 0.0);)";
  source.float_outputs = 2;
  const kernel_outputs gpu = run_fragment(source, indexed, [&](const program& p) {
    set_uniforms(p, "radial", constants);
    set_uniforms(p, "disk", disk);
  });
  std::vector<glm::vec4> cpu_radial(indexed.size()), cpu_disk(indexed.size());
  for (std::size_t i = 0; i < indexed.size(); ++i) {
    const glm::uvec2 pixel(indexed.uints[0][i]);
    const auto r = radial_pattern_sample(static_cast<int>(pixel.x % 16), static_cast<int>(pixel.y % 16), pixel, constants);
    const auto d = rsm_disk_sample(static_cast<int>(pixel.x + 64 * pixel.y), disk);
    cpu_radial[i] = glm::vec4(r.offset, r.weight, 0.0f);
    cpu_disk[i] = glm::vec4(d.offset, d.weight, 0.0f);
  }
  // Hash bits, exact float-from-bits, +,* and the polynomial: bit-identical unless llvmpipe
  // contracts multiply-adds; offsets decide which texel is fetched, so allow 2 ulp at most.
  require_parity(compare("radial_pattern_sample", gpu.floats[0], cpu_radial, indexed, {0.0f, 0.0f, 2, 0.0, "+,* only"}, 3));
  // The disk weight divides by N (llvmpipe's divide need not be correctly rounded): 4 ulp.
  require_parity(compare("rsm_disk_sample", gpu.floats[1], cpu_disk, indexed, {0.0f, 0.0f, 4, 0.0, "+,*, one divide"}, 3));
}

TEST_CASE("parity: transform_point and map_coordinate") {
  kernel_inputs inputs = grid_of(64, 64, 1);
  std::mt19937 random(21);
  std::uniform_real_distribution<float> uniform(-3.0f, 3.0f);
  for (auto& p : inputs.floats[0]) p = glm::vec4(uniform(random), uniform(random), uniform(random), 0.0f);
  const glm::mat4 view = glm::lookAt(glm::vec3(0.3f, 4.0f, 1.0f), glm::vec3(0.0f), glm::vec3(0, 0, -1));
  const glm::mat4 view_projection = glm::perspective(1.2f, 1.0f, 0.1f, 20.0f) * view;
  kernel_source source;
  source.name = "transforms";
  source.includes = {"lib/transform.glsl"};
  source.declarations = "uniform mat4 view;\nuniform mat4 view_projection;\n";
  source.body = "fout0 = vec4(transform_point(view, fin0.xyz), 0.0);\n"
                "fout1 = vec4(map_coordinate(view_projection, fin0.xyz, ivec2(512)), 0.0, 0.0);";
  source.float_outputs = 2;
  const kernel_outputs gpu = run_fragment(source, inputs, [&](const program& p) {
    p.set("view", view);
    p.set("view_projection", view_projection);
  });
  std::vector<glm::vec4> eye(inputs.size()), map(inputs.size());
  for (std::size_t i = 0; i < inputs.size(); ++i) {
    eye[i] = glm::vec4(transform_point(view, glm::vec3(inputs.floats[0][i])), 0.0f);
    map[i] = glm::vec4(map_coordinate(view_projection, glm::vec3(inputs.floats[0][i]), glm::ivec2(512)), 0.0f, 0.0f);
  }
  // A 3-term sum of products can cancel to near 0 (points near the eye's axes): 1e-6 absolute.
  require_parity(compare("transform_point", gpu.floats[0], eye, inputs, {1e-6f, 0.0f, 4, 0.0, "sums of products, cancellation"}, 3));
  // The perspective divide: llvmpipe's is not correctly rounded: 1e-5 relative.
  require_parity(compare("map_coordinate", gpu.floats[1], map, inputs, {1e-4f, 1e-5f, 8, 0.0, "perspective divide"}, 2));
}

TEST_CASE("parity: shadow_density (Alg. 4) over a synthetic depth map") {
  // float input 0 is the depth map (x), a slope with steps, and float input 1 the receivers:
  // (rsm coordinate, receiver depth, gradient x); gradient y is 0.
  kernel_inputs inputs = grid_of(64, 64, 2);
  std::mt19937 random(22);
  std::uniform_real_distribution<float> uniform(0.0f, 1.0f);
  for (std::size_t i = 0; i < inputs.size(); ++i) {
    const float x = static_cast<float>(i % 64), y = static_cast<float>(i / 64);
    const float step = (static_cast<int>(x) / 9 + static_cast<int>(y) / 13) % 3 == 0 ? 0.5f : 0.0f;
    inputs.floats[0][i] = glm::vec4(-10.0f + 0.01f * x + step, 0, 0, 0);
    if (i % 97 == 0) inputs.floats[0][i].x = 0.0f;  // empty texels
    const glm::vec2 coordinate(uniform(random) * 70.0f - 3.0f, uniform(random) * 70.0f - 3.0f);
    inputs.floats[1][i] = glm::vec4(coordinate, -10.0f + 0.01f * coordinate.x + 0.3f * (uniform(random) - 0.5f),
                                    0.01f * (uniform(random) - 0.5f));
  }
  shadow_density_settings<float> settings;
  settings.kernel_size = 5;
  kernel_source source;
  source.name = "shadow_density";
  source.includes = {"lib/shadow.glsl"};
  source.declarations = "uniform shadow_density_settings settings;\n"
                        "float rsm_depth_fetch(ivec2 texel) { return texelFetch(float_input0, texel, 0).x; }\n";
  source.body = "fout0 = vec4(shadow_density(fin1.xy, fin1.z, vec2(fin1.w, 0.0), ivec2(64), settings), 0.0, 0.0, 0.0);";
  source.float_outputs = 1;
  const kernel_outputs gpu = run_fragment(source, inputs, [&](const program& p) { set_uniforms(p, "settings", settings); });
  std::vector<glm::vec4> cpu(inputs.size());
  for (std::size_t i = 0; i < inputs.size(); ++i) {
    const glm::vec4 r = inputs.floats[1][i];
    cpu[i] = glm::vec4(shadow_density(glm::vec2(r), r.z, glm::vec2(r.w, 0.0f),
                                      [&](glm::ivec2 t) { return inputs.floats[0][static_cast<std::size_t>(t.y * 64 + t.x)].x; },
                                      glm::ivec2(64), settings),
                       0.0f, 0.0f, 0.0f);
  }
  // A count of depth tests over exactly the same floats (the plane depth is +,* only): the
  // result is a multiple of 1/25 and must match exactly.
  require_parity(compare("shadow_density", gpu.floats[0], cpu, inputs, {0.0f, 0.0f, 0, 0.0, "exact count"}, 1));
}

TEST_CASE("parity: bilateral_filter and bilateral_filter_axis over a synthetic indirect buffer") {
  // float input 0: tap values and depth (two planes at depth -4 and -6 with a noisy value),
  // float input 1: tap normals, float input 2: the centre to filter (coordinate, depth).
  kernel_inputs inputs = grid_of(48, 48, 3);
  std::mt19937 random(23);
  std::uniform_real_distribution<float> uniform(0.0f, 1.0f);
  for (std::size_t i = 0; i < inputs.size(); ++i) {
    const bool near = (i % 48) < 20;
    inputs.floats[0][i] = glm::vec4(uniform(random), uniform(random), uniform(random), near ? -4.0f : -6.0f);
    if (i % 61 == 0) inputs.floats[0][i].w = 0.0f;  // no surface
    inputs.floats[1][i] = near ? glm::vec4(0, 0, 1, 0) : glm::vec4(glm::normalize(glm::vec3(0.3f, 0.0f, 1.0f)), 0.0f);
    inputs.floats[2][i] = glm::vec4(uniform(random) * 48.0f, uniform(random) * 48.0f, near ? -4.0f : -6.0f, 0.0f);
  }
  bilateral_settings<float> settings;
  settings.kernel_size = 9;
  kernel_source source;
  source.name = "bilateral";
  source.includes = {"lib/bilateral.glsl"};
  source.declarations = "uniform bilateral_settings settings;\n"
                        "bilateral_tap bilateral_fetch(ivec2 t) {\n"
                        "  vec4 v = texelFetch(float_input0, t, 0);\n"
                        "  return bilateral_tap(v.xyz, v.w, texelFetch(float_input1, t, 0).xyz);\n}\n";
  source.body = "fout0 = vec4(bilateral_filter(fin2.xy, fin2.z, vec3(0.0, 0.0, 1.0), ivec2(48), settings), 0.0);\n"
                "fout1 = vec4(bilateral_filter_axis(fin2.xy, fin2.z, vec3(0.0, 0.0, 1.0), ivec2(48), 1, settings), 0.0);";
  source.float_outputs = 2;
  const kernel_outputs gpu = run_fragment(source, inputs, [&](const program& p) { set_uniforms(p, "settings", settings); });
  const auto fetch = [&](glm::ivec2 t) {
    const std::size_t i = static_cast<std::size_t>(t.y * 48 + t.x);
    return bilateral_tap<float>{glm::vec3(inputs.floats[0][i]), inputs.floats[0][i].w, glm::vec3(inputs.floats[1][i])};
  };
  std::vector<glm::vec4> full(inputs.size()), axis(inputs.size());
  for (std::size_t i = 0; i < inputs.size(); ++i) {
    const glm::vec4 c = inputs.floats[2][i];
    full[i] = glm::vec4(bilateral_filter(glm::vec2(c), c.z, glm::vec3(0, 0, 1), fetch, glm::ivec2(48), settings), 0.0f);
    axis[i] = glm::vec4(bilateral_filter_axis(glm::vec2(c), c.z, glm::vec3(0, 0, 1), fetch, glm::ivec2(48), 1, settings), 0.0f);
  }
  // exp() differs between llvmpipe and the C library by a few ulp, and 81 weighted terms are
  // summed and divided by the weight sum: a normalised average of values in [0, 1], so 1e-5
  // absolute.
  require_parity(compare("bilateral_filter", gpu.floats[0], full, inputs, {1e-5f, 0.0f, 0, 0.0, "exp ulps over 81 taps"}, 3));
  require_parity(compare("bilateral_filter_axis", gpu.floats[1], axis, inputs, {1e-5f, 0.0f, 0, 0.0, "exp ulps over 9 taps"}, 3));
}
