// CPU/GPU parity of the Light Wave kernels ([LW]): the layout, the lobe and attenuation, the
// integrated-shadow stepping, Eq. 5.2, and Eq. 4.5 summed over a VPL table in the vertex stage
// (transform feedback), as the thesis evaluates it per vertex; every kernel on every target
// (tests/parity/targets.hpp), the per-vertex sums also as compute shaders on gl45 and vulkan.
#include <doctest/doctest.h>

#include <array>
#include <random>
#include <string>

#include <vplkit/lightwave.hpp>

#include <vplkit/parity/doctest.hpp>

#include "tests/parity/targets.hpp"

using namespace vplkit;
using namespace vplkit::parity;

namespace {

lightwave_layout_settings<float> test_layout() {
  lightwave_layout_settings<float> s;
  s.light_position = {0.2f, 1.9f, -0.3f};
  s.light_direction = glm::normalize(glm::vec3(0.1f, -1.0f, 0.2f));
  s.angle_deg = 5;
  s.per_ray = 5;
  s.max_distance = 2.5f;
  return s;
}

}  // namespace

TEST_CASE("parity: lightwave_layout_vpl for all 6485 VPLs of the thesis's layout, on every target") {
  const lightwave_layout_settings<float> layout = test_layout();
  kernel_inputs inputs;
  inputs.width = 128;
  inputs.height = 51;  // 6528 texels >= 6485
  inputs.uints.assign(1, std::vector<glm::uvec4>(inputs.size()));
  for (std::size_t i = 0; i < inputs.size(); ++i) inputs.uints[0][i] = glm::uvec4(static_cast<unsigned>(std::min<std::size_t>(i, 6484)), 0u, 0u, 0u);
  kernel_source source;
  source.name = "lightwave_layout_vpl";
  source.includes = {"lib/lightwave.glsl"};
  source.body = "lightwave_vpl vpl = lightwave_layout_vpl(int(uin0.x), layout_settings);\n"
                "fout0 = vec4(vpl.position, vpl.attenuation);\nfout1 = vec4(vpl.normal, float(lightwave_vpl_count(layout_settings.angle_deg, layout_settings.per_ray)));";
  source.float_outputs = 2;
  // The layout as a std140 block, which every target has.
  kernel_resources resources;
  resources.blocks = {settings_block("layout_settings", layout)};
  std::vector<glm::vec4> positions(inputs.size()), normals(inputs.size());
  for (std::size_t i = 0; i < inputs.size(); ++i) {
    const lightwave_vpl<float> vpl = lightwave_layout_vpl(static_cast<int>(inputs.uints[0][i].x), layout);
    positions[i] = glm::vec4(vpl.position, vpl.attenuation);
    normals[i] = glm::vec4(vpl.normal, static_cast<float>(lightwave_vpl_count(layout.angle_deg, layout.per_ray)));
  }
  // Integer layout arithmetic, the polynomial sin/cos, a normalise (sqrt and divide) and a cross
  // product: a few ulp, and values near 0 from cancelling terms: 1e-6 absolute.
  const tolerance bounds{1e-6f, 0.0f, 8, 0.0, "polynomial sin/cos, normalize, cross"};
  for (const testing::target_run& run : testing::every_target()) {
    const std::string target = run.name();
    CAPTURE(target);
    if (!testing::target_runs(run.where)) continue;
    source.name = "lightwave_layout_vpl (" + target + ")";
    const kernel_outputs gpu = run.run(source, inputs, run.where, resources);
    require_parity(compare("lightwave_layout_vpl position, attenuation (" + target + ")", gpu.floats[0], positions, inputs, bounds));
    require_parity(compare("lightwave_layout_vpl normal, count (" + target + ")", gpu.floats[1], normals, inputs, bounds));
  }
}

TEST_CASE("parity: lightwave_lobe, lightwave_attenuation, lightwave_integrated_step, lightwave_faked_indirect, on every target") {
  kernel_inputs inputs;
  inputs.width = 64;
  inputs.height = 64;
  inputs.floats.assign(2, std::vector<glm::vec4>(inputs.size()));
  std::mt19937 random(30);
  std::uniform_real_distribution<float> uniform(-1.0f, 1.0f);
  for (std::size_t i = 0; i < inputs.size(); ++i) {
    inputs.floats[0][i] = glm::vec4(uniform(random), uniform(random), uniform(random), uniform(random));
    inputs.floats[1][i] = glm::vec4(uniform(random), uniform(random), static_cast<float>(i % 8), static_cast<float>(i % 13));
  }
  kernel_source source;
  source.name = "lightwave small kernels";
  source.includes = {"lib/lightwave.glsl"};
  source.body = "int lookup = int(fin1.w), steps = int(fin1.z) + 1;\n"
                "fout0 = vec4(lightwave_lobe(fin0.x), lightwave_attenuation(int(fin1.z)), lightwave_faked_indirect(fin0.yzw, fin1.x, 1.3).xy);\n"
                "fout1 = lightwave_integrated_step(fin0.xyz, fin1.xyw, min(lookup, steps + 1), steps);";
  source.float_outputs = 2;
  std::vector<glm::vec4> first(inputs.size()), second(inputs.size());
  for (std::size_t i = 0; i < inputs.size(); ++i) {
    const glm::vec4 a = inputs.floats[0][i], b = inputs.floats[1][i];
    const int lookup = static_cast<int>(b.w), steps = static_cast<int>(b.z) + 1;
    first[i] = glm::vec4(lightwave_lobe(a.x), lightwave_attenuation<float>(static_cast<int>(b.z)),
                         glm::vec2(lightwave_faked_indirect(glm::vec3(a.y, a.z, a.w), b.x, 1.3f)));
    second[i] = lightwave_integrated_step(glm::vec3(a), glm::vec3(b.x, b.y, b.w), std::min(lookup, steps + 1), steps);
  }
  // One divide in the lobe and in the step (llvmpipe's divide need not be correctly rounded):
  // 4 ulp; the map choice (w) is an integer decision and must match.
  for (const testing::target_run& run : testing::every_target()) {
    const std::string target = run.name();
    CAPTURE(target);
    if (!testing::target_runs(run.where)) continue;
    source.name = std::string("lightwave small kernels") + " (" + target + ")";
    const kernel_outputs gpu = run.run(source, inputs, run.where, {});
    require_parity(compare("lobe, attenuation, faked indirect (" + target + ")", gpu.floats[0], first, inputs, {1e-7f, 0.0f, 4, 0.0, "one divide"}));
    require_parity(compare("lightwave_integrated_step (" + target + ")", gpu.floats[1], second, inputs, {1e-7f, 0.0f, 4, 0.0, "one divide"}));
  }
}

TEST_CASE("parity: lightwave_vpl_weight, lightwave_map_coordinate (behind, outside and inside a map) and lightwave_map_fade, on every target") {
  kernel_inputs inputs;
  inputs.width = 64;
  inputs.height = 64;
  inputs.floats.assign(4, std::vector<glm::vec4>(inputs.size()));
  std::mt19937 random(33);
  std::uniform_real_distribution<float> uniform(-1.0f, 1.0f);
  for (std::size_t i = 0; i < inputs.size(); ++i) {
    inputs.floats[0][i] = glm::vec4(uniform(random), uniform(random), uniform(random), 0.05f * static_cast<float>(1 << (i % 5)));  // x | attenuation
    inputs.floats[1][i] = glm::vec4(glm::normalize(glm::vec3(uniform(random), uniform(random), uniform(random))), 0.0f);         // n
    inputs.floats[2][i] = glm::vec4(uniform(random) * 2.0f, uniform(random) * 2.0f, uniform(random) * 2.0f, 0.0f);               // VPL position
    // A clip-space point: w from -1 to 3 (behind, at, in front of the camera), xyz past the frustum's edges too.
    inputs.floats[3][i] = glm::vec4(uniform(random) * 2.0f, uniform(random) * 2.0f, uniform(random) * 2.0f, i % 7 == 0 ? 0.0f : uniform(random) * 2.0f + 1.0f);
  }
  kernel_source source;
  source.name = "lightwave_vpl_weight, lightwave_map_coordinate";
  source.includes = {"lib/lightwave.glsl"};
  source.body = "lightwave_vpl vpl = lightwave_vpl(fin2.xyz, normalize(fin0.xyz - fin2.xyz + vec3(0.3, -0.2, 0.1)), fin0.w);\n"
                "fout0 = vec4(lightwave_vpl_weight(fin0.xyz, fin1.xyz, vpl), 0.0, 0.0, 0.0);\n"
                "fout1 = lightwave_map_coordinate(fin3);\n"
                "fout2 = vec4(lightwave_map_fade(fout1, 0.05), 0.0, 0.0, 0.0);";
  source.float_outputs = 3;
  std::vector<glm::vec4> weights(inputs.size()), coordinates(inputs.size()), fades(inputs.size());
  std::size_t behind = 0, outside = 0, inside = 0;
  for (std::size_t i = 0; i < inputs.size(); ++i) {
    const glm::vec4 a = inputs.floats[0][i], n = inputs.floats[1][i], p = inputs.floats[2][i], clip = inputs.floats[3][i];
    const lightwave_vpl<float> vpl{glm::vec3(p), glm::normalize(glm::vec3(a) - glm::vec3(p) + glm::vec3(0.3f, -0.2f, 0.1f)), a.w};
    weights[i] = glm::vec4(lightwave_vpl_weight(glm::vec3(a), glm::vec3(n), vpl), 0.0f, 0.0f, 0.0f);
    coordinates[i] = lightwave_map_coordinate(clip);
    fades[i] = glm::vec4(lightwave_map_fade(coordinates[i], 0.05f), 0.0f, 0.0f, 0.0f);
    behind += !(clip.w > 0.0f);
    outside += clip.w > 0.0f && coordinates[i].w == 0.0f;
    inside += coordinates[i].w == 1.0f;
  }
  CHECK(behind > 100);  // every case is exercised
  CHECK(outside > 100);
  CHECK(inside > 100);
  // Two normalisations and the lobe's divide: 8 ulp, 1e-7 absolute near 0. The coordinate: one
  // divide and a multiply-add (4 ulp); its validity (w) is a decision and must match exactly.
  for (const testing::target_run& run : testing::every_target()) {
    const std::string target = run.name();
    CAPTURE(target);
    if (!testing::target_runs(run.where)) continue;
    source.name = std::string("lightwave_vpl_weight, lightwave_map_coordinate") + " (" + target + ")";
    const kernel_outputs gpu = run.run(source, inputs, run.where, {});
    require_parity(compare("lightwave_vpl_weight (" + target + ")", gpu.floats[0], weights, inputs, {1e-7f, 0.0f, 8, 0.0, "two normalisations and a divide"}));
    require_parity(compare("lightwave_map_coordinate (" + target + ")", gpu.floats[1], coordinates, inputs, {1e-7f, 0.0f, 4, 0.0, "one divide"}));
    // The fade: a min, a divide and the smoothstep's polynomial of the coordinate above.
    require_parity(compare("lightwave_map_fade (" + target + ")", gpu.floats[2], fades, inputs,
                           {1e-6f, 0.0f, 16, 0.0, "a divide of a coordinate with its own error"}));
  }
}

TEST_CASE("parity: Eq. 4.5 summed over 1625 VPLs per vertex, in the vertex stage (transform feedback) on every GL target and in compute on gl45 and vulkan") {
  lightwave_layout_settings<float> layout = test_layout();
  layout.angle_deg = 10;  // 1625 VPLs: the thesis's loop, smaller
  const int count = lightwave_vpl_count(layout.angle_deg, layout.per_ray);
  std::vector<lightwave_vpl<float>> vpls;
  lightwave_layout(layout, std::back_inserter(vpls));
  // VPLs in a 2-texel-wide table: [position | attenuation], [normal | -].
  std::vector<glm::vec4> texels(static_cast<std::size_t>(count) * 2);
  for (int i = 0; i < count; ++i) {
    texels[static_cast<std::size_t>(i) * 2] = glm::vec4(vpls[static_cast<std::size_t>(i)].position, vpls[static_cast<std::size_t>(i)].attenuation);
    texels[static_cast<std::size_t>(i) * 2 + 1] = glm::vec4(vpls[static_cast<std::size_t>(i)].normal, 0.0f);
  }
  const lightwave_shading_settings<float> shading;
  const glm::vec3 eye(0.0f, 1.0f, 3.8f);
  kernel_inputs inputs;
  inputs.width = 32;
  inputs.height = 16;
  inputs.floats.assign(3, std::vector<glm::vec4>(inputs.size()));
  std::mt19937 random(31);
  std::uniform_real_distribution<float> uniform(-1.0f, 1.0f);
  for (std::size_t i = 0; i < inputs.size(); ++i) {
    inputs.floats[0][i] = glm::vec4(uniform(random), uniform(random) * 0.5f + 0.5f, uniform(random), 0.0f);
    inputs.floats[1][i] = glm::vec4(glm::normalize(glm::vec3(uniform(random), uniform(random), uniform(random))), 0.0f);
    inputs.floats[2][i] = glm::vec4(0.5f * (uniform(random) + 1.0f), 0.5f * (uniform(random) + 1.0f), 0.5f * (uniform(random) + 1.0f), 0.0f);
  }
  kernel_source source;
  source.name = "lightwave_vertex_indirect";
  // The lib's lightwave_vertex_indirect, the function lightwave.vert calls, with the VPLs from a
  // table as there from a float texture (the pipeline test runs lightwave.vert itself on a scene).
  // The count is a constant of the source; the eye a one-texel table (read exactly) and the shading a std140
  // block, which every target has (Vulkan has no default-block uniforms).
  source.defines = {{"VPLKIT_LIGHTWAVE_FETCH", "1"}};
  source.includes = {"lib/lightwave.glsl"};
  source.declarations = "const int vpl_count = " + std::to_string(count) + ";\n"
                        "lightwave_vpl lightwave_fetch_vpl(int index) {\n"
                        "  vec4 position_attenuation = vpls(ivec2(0, index));\n"
                        "  return lightwave_vpl(position_attenuation.xyz, vpls(ivec2(1, index)).xyz, position_attenuation.w);\n"
                        "}\n";
  source.body = "fout0 = vec4(lightwave_vertex_indirect(fin0.xyz, fin1.xyz, fin2.xyz, eye_position(ivec2(0)).xyz, vpl_count, shading), 0.0);";
  source.float_outputs = 1;
  kernel_resources resources;
  resources.tables = {{"vpls", 2, count, texels}, {"eye_position", 1, 1, {glm::vec4(eye, 0.0f)}}};
  resources.blocks = {settings_block("shading", shading)};
  std::vector<glm::vec4> cpu(inputs.size());
  for (std::size_t i = 0; i < inputs.size(); ++i)
    cpu[i] = glm::vec4(lightwave_vertex_indirect(glm::vec3(inputs.floats[0][i]), glm::vec3(inputs.floats[1][i]), glm::vec3(inputs.floats[2][i]),
                                                 eye, [&](int index) { return vpls[static_cast<std::size_t>(index)]; }, count, shading),
                       0.0f);
  // 1625 terms, each with two normalisations (sqrt, divide) and the lobe's divide, summed in the
  // same order and divided by the count: 1e-5 relative, or 1e-7 absolute near 0.
  for (const testing::target_run& run : testing::every_vertex_target()) {
    const std::string target = run.name();
    CAPTURE(target);
    if (!testing::target_runs(run.where)) continue;
    source.name = "lightwave_vertex_indirect (" + target + ")";
    const kernel_outputs gpu = run.run(source, inputs, run.where, resources);
    require_parity(compare(source.name, gpu.floats[0], cpu, inputs, {1e-7f, 1e-5f, 64, 0.0, "1625 terms of a few-ulp Eq. 4.5"}, 3));
  }
}

TEST_CASE("parity: lightwave_cone_sample for all 6485 samples of the flux layout, three cones, on every target") {
  for (float half_angle : {12.0f, 50.0f, 83.0f}) {
    lightwave_cone_settings<float> cone;
    cone.light_direction = glm::normalize(glm::vec3(0.1f, -1.0f, 0.2f));
    cone.angle_deg = 5;
    cone.per_ray = 5;
    cone.half_angle_deg = half_angle;
    kernel_inputs inputs;
    inputs.width = 128;
    inputs.height = 51;  // 6528 texels >= 6485
    inputs.uints.assign(1, std::vector<glm::uvec4>(inputs.size()));
    for (std::size_t i = 0; i < inputs.size(); ++i) inputs.uints[0][i] = glm::uvec4(static_cast<unsigned>(std::min<std::size_t>(i, 6484)), 0u, 0u, 0u);
    kernel_source source;
    source.name = "lightwave_cone_sample";
    source.includes = {"lib/lightwave.glsl"};
    source.body = "fout0 = lightwave_cone_sample(int(uin0.x), cone);";
    source.float_outputs = 1;
    // The cone as a std140 block, which every target has.
    kernel_resources resources;
    resources.blocks = {settings_block("cone", cone)};
    std::vector<glm::vec4> cpu(inputs.size());
    for (std::size_t i = 0; i < inputs.size(); ++i) cpu[i] = lightwave_cone_sample(static_cast<int>(inputs.uints[0][i].x), cone);
    // The polynomial cosine, a divide, a square root, a normalise and a cross product: a few ulp;
    // the solid angle is a difference of cosines (cancellation near the axis): 1e-6 relative.
    CAPTURE(half_angle);
    for (const testing::target_run& run : testing::every_target()) {
      const std::string target = run.name();
      CAPTURE(target);
      if (!testing::target_runs(run.where)) continue;
      source.name = "lightwave_cone_sample, half-angle " + std::to_string(static_cast<int>(half_angle)) + " (" + target + ")";
      const kernel_outputs gpu = run.run(source, inputs, run.where, resources);
      require_parity(compare(source.name, gpu.floats[0], cpu, inputs, {1e-6f, 1e-6f, 16, 0.0, "polynomial cos, sqrt, normalize, cross"}));
    }
  }
}

TEST_CASE("parity: lightwave_ray_flux, lightwave_patch_radius, lightwave_bounce_irradiance, lightwave_bounce_weight, lightwave_flux_vpl_faces and lightwave_group_confidence, on every target") {
  kernel_inputs inputs;
  inputs.width = 64;
  inputs.height = 64;
  inputs.floats.assign(4, std::vector<glm::vec4>(inputs.size()));
  std::mt19937 random(34);
  std::uniform_real_distribution<float> uniform(-1.0f, 1.0f);
  for (std::size_t i = 0; i < inputs.size(); ++i) {
    // x | solid angle, n | distance, VPL position | radius, VPL normal | cos of incidence.
    inputs.floats[0][i] = glm::vec4(uniform(random), uniform(random), uniform(random), 0.01f * (uniform(random) + 1.0f));
    inputs.floats[1][i] = glm::vec4(glm::normalize(glm::vec3(uniform(random), uniform(random), uniform(random))), 2.0f * (uniform(random) + 1.5f));
    // Every seventh VPL within its radius of the receiver (the clamp acts), every fifth of radius 0.
    const glm::vec3 near = glm::vec3(inputs.floats[0][i]) + 0.1f * glm::vec3(uniform(random), uniform(random), uniform(random));
    const glm::vec3 far(uniform(random) * 2.0f, uniform(random) * 2.0f, uniform(random) * 2.0f);
    inputs.floats[2][i] = glm::vec4(i % 7 == 0 ? near : far, i % 5 == 0 ? 0.0f : 0.2f * (uniform(random) + 1.0f));
    inputs.floats[3][i] = glm::vec4(glm::normalize(glm::vec3(uniform(random), uniform(random), uniform(random))), uniform(random));
  }
  spot_light<float> light;
  light.position = {0.2f, 2.0f, 0.1f};
  light.direction = glm::normalize(glm::vec3(0.2f, -1.0f, 0.1f));
  light.intensity = {3.0f, 2.0f, 1.0f};
  light.cos_inner = 0.8f;
  light.cos_outer = 0.3f;
  kernel_source source;
  source.name = "flux VPL kernels";
  source.includes = {"lib/lightwave.glsl"};
  source.body = "vec3 direction = normalize(fin2.xyz - light.position);\n"
                "vec3 flux = lightwave_ray_flux(light, direction, fin0.w, vec3(0.5, 0.7, 0.9), fin3.xyz);\n"
                "lightwave_flux_vpl vpl = lightwave_flux_vpl(fin2.xyz, fin3.xyz, vec3(1.0, 0.5, 0.25), fin2.w);\n"
                "fout0 = vec4(flux, lightwave_patch_radius(fin0.w, fin1.w, fin3.w));\n"
                "fout1 = vec4(lightwave_bounce_irradiance(fin0.xyz, fin1.xyz, vpl, 0.01), lightwave_bounce_weight(fin0.xyz, fin1.xyz, vpl, 0.01));\n"
                "fout2 = vec4(lightwave_group_confidence(fin0.xyz, fin2.xyz, fin2.w), lightwave_flux_vpl_faces(fin0.xyz, fin1.xyz, fin2.xyz, fin3.xyz) ? 1.0 : 0.0, 0.0, 0.0);";
  source.float_outputs = 3;
  // The light as a std140 block, which every target has.
  kernel_resources resources;
  resources.blocks = {settings_block("light", light)};
  std::vector<glm::vec4> first(inputs.size()), second(inputs.size()), third(inputs.size());
  std::size_t lit = 0, clamped = 0;
  for (std::size_t i = 0; i < inputs.size(); ++i) {
    const glm::vec4 a = inputs.floats[0][i], b = inputs.floats[1][i], c = inputs.floats[2][i], d = inputs.floats[3][i];
    const glm::vec3 direction = glm::normalize(glm::vec3(c) - light.position);
    const lightwave_flux_vpl<float> vpl{glm::vec3(c), glm::vec3(d), glm::vec3(1.0f, 0.5f, 0.25f), c.w};
    first[i] = glm::vec4(lightwave_ray_flux(light, direction, a.w, glm::vec3(0.5f, 0.7f, 0.9f), glm::vec3(d)), lightwave_patch_radius(a.w, b.w, d.w));
    second[i] = glm::vec4(lightwave_bounce_irradiance(glm::vec3(a), glm::vec3(b), vpl, 0.01f), lightwave_bounce_weight(glm::vec3(a), glm::vec3(b), vpl, 0.01f));
    third[i] = glm::vec4(lightwave_group_confidence(glm::vec3(a), glm::vec3(c), c.w),
                         lightwave_flux_vpl_faces(glm::vec3(a), glm::vec3(b), glm::vec3(c), glm::vec3(d)) ? 1.0f : 0.0f, 0.0f, 0.0f);
    lit += second[i].w > 0.0f;
    clamped += glm::length(glm::vec3(a) - glm::vec3(c)) < c.w && second[i].w > 0.0f;
  }
  CHECK(lit > 500);  // both branches are exercised: lit and unlit, clamped and not
  CHECK(clamped > 10);
  // A normalise, the cone's divide and a square root: a few ulp; the irradiance's two divides by a
  // squared distance (llvmpipe's divide is not correctly rounded, and a VPL within its clamp of the
  // receiver divides twice by 1e-4) and the 1/pi multiply: 5e-6 relative, 1e-7 absolute near 0.
  for (const testing::target_run& run : testing::every_target()) {
    const std::string target = run.name();
    CAPTURE(target);
    if (!testing::target_runs(run.where)) continue;
    source.name = "flux VPL kernels (" + target + ")";
    const kernel_outputs gpu = run.run(source, inputs, run.where, resources);
    require_parity(compare("lightwave_ray_flux, lightwave_patch_radius (" + target + ")", gpu.floats[0], first, inputs,
                           {1e-7f, 0.0f, 8, 0.0, "normalize, divide, sqrt"}));
    require_parity(compare("lightwave_bounce_irradiance, lightwave_bounce_weight (" + target + ")", gpu.floats[1], second, inputs,
                           {1e-7f, 5e-6f, 8, 0.0, "two divides"}));
    // The confidence: two divides; whether the VPL faces the receiver: a decision, exact.
    require_parity(compare("lightwave_group_confidence, lightwave_flux_vpl_faces (" + target + ")", gpu.floats[2], third, inputs,
                           {1e-7f, 0.0f, 4, 0.0, "two divides"}));
  }
}

TEST_CASE("parity: the flux VPLs' light summed per vertex (lightwave_vertex_bounce), in the vertex stage (transform feedback) on every GL target and in compute on gl45 and vulkan") {
  // 2000 flux VPLs scattered over a floor and a wall, as the pipeline makes them.
  std::mt19937 random(35);
  std::uniform_real_distribution<float> uniform(-1.0f, 1.0f);
  const int count = 2000;
  std::vector<lightwave_flux_vpl<float>> vpls;
  std::vector<glm::vec4> texels;
  for (int i = 0; i < count; ++i) {
    const bool floor = i % 3 != 0;
    const glm::vec3 position = floor ? glm::vec3(uniform(random), 0.0f, uniform(random)) : glm::vec3(-1.0f, uniform(random) + 1.0f, uniform(random));
    const glm::vec3 normal = floor ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0);
    vpls.push_back({position, normal, glm::vec3(0.002f, 0.001f, 0.0005f) * (uniform(random) + 1.5f), 0.02f * (uniform(random) + 1.5f)});
    texels.push_back(glm::vec4(vpls.back().position, vpls.back().radius));
    texels.push_back(glm::vec4(vpls.back().normal, 0.0f));
    texels.push_back(glm::vec4(vpls.back().flux, 0.0f));
  }
  irradiance_settings<float> irradiance;
  kernel_inputs inputs;
  inputs.width = 32;
  inputs.height = 16;
  inputs.floats.assign(3, std::vector<glm::vec4>(inputs.size()));
  for (std::size_t i = 0; i < inputs.size(); ++i) {
    inputs.floats[0][i] = glm::vec4(uniform(random) * 0.9f, 0.5f * uniform(random) + 0.6f, uniform(random), 0.0f);
    inputs.floats[1][i] = glm::vec4(glm::normalize(glm::vec3(uniform(random), uniform(random), uniform(random))), 0.0f);
    inputs.floats[2][i] = glm::vec4(0.5f * (uniform(random) + 1.0f), 0.5f * (uniform(random) + 1.0f), 0.5f * (uniform(random) + 1.0f), 0.0f);
  }
  kernel_source source;
  source.name = "lightwave_vertex_bounce";
  // The lib's lightwave_vertex_bounce, the function lightwave.vert's capture calls, with the VPLs
  // from a table as there from a float texture (the pipeline test runs lightwave.vert itself on a
  // scene). The count is a constant of the source, the settings a std140 block: every target has
  // both (Vulkan has no default-block uniforms).
  source.defines = {{"VPLKIT_LIGHTWAVE_FETCH_FLUX", "1"}};
  source.includes = {"lib/lightwave.glsl"};
  source.declarations = "const int vpl_count = " + std::to_string(count) + ";\n"
                        "lightwave_flux_vpl lightwave_fetch_flux_vpl(int index) {\n"
                        "  vec4 position_radius = vpls(ivec2(0, index));\n"
                        "  return lightwave_flux_vpl(position_radius.xyz, vpls(ivec2(1, index)).xyz, vpls(ivec2(2, index)).xyz, position_radius.w);\n"
                        "}\n";
  // Second output: the sum continued from a partial sum (fin2 as one), as each pass of
  // lightwave_capture.frag continues the last one's.
  source.body = "fout0 = vec4(lightwave_vertex_bounce(fin0.xyz, fin1.xyz, fin2.xyz, vpl_count, irradiance), 0.0);\n"
                "fout1 = vec4(lightwave_bounce_sum(fin0.xyz, fin1.xyz, vpl_count, fin2.xyz, irradiance.min_distance), 0.0);";
  source.float_outputs = 2;
  kernel_resources resources;
  resources.tables = {{"vpls", 3, count, texels}};
  resources.blocks = {settings_block("irradiance", irradiance)};
  // lightwave_bounce_sums (lightwave_capture.frag's), four receivers made from the element's:
  // moved along the axes and turned by swizzles, from swizzled partial sums; in a run of its own
  // (transform feedback captures at most 4 outputs on GL 3.3).
  kernel_source sums_source = source;
  sums_source.name = "lightwave_bounce_sums";
  sums_source.body = "vec3 xs[4], ns[4], sums[4];\n"
                     "xs[0] = fin0.xyz; xs[1] = fin0.xyz + vec3(0.25, 0.0, 0.0); xs[2] = fin0.xyz + vec3(0.0, 0.125, 0.0); xs[3] = fin0.xyz - vec3(0.0, 0.0, 0.5);\n"
                     "ns[0] = fin1.xyz; ns[1] = fin1.yzx; ns[2] = fin1.zxy; ns[3] = -fin1.xyz;\n"
                     "sums[0] = fin2.xyz; sums[1] = fin2.yzx; sums[2] = fin2.zxy; sums[3] = vec3(0.0);\n"
                     "lightwave_bounce_sums(xs, ns, vpl_count, sums, irradiance.min_distance);\n"
                     "fout0 = vec4(sums[0], sums[3].x); fout1 = vec4(sums[1], sums[3].y); fout2 = vec4(sums[2], sums[3].z);";
  sums_source.float_outputs = 3;
  std::vector<glm::vec4> cpu(inputs.size()), continued(inputs.size());
  std::array<std::vector<glm::vec4>, 3> packed_sums;
  for (std::vector<glm::vec4>& packed : packed_sums) packed.resize(inputs.size());
  const auto fetch = [&](int index) { return vpls[static_cast<std::size_t>(index)]; };
  for (std::size_t i = 0; i < inputs.size(); ++i) {
    const glm::vec3 x(inputs.floats[0][i]), n(inputs.floats[1][i]), third(inputs.floats[2][i]);
    cpu[i] = glm::vec4(lightwave_vertex_bounce(x, n, third, fetch, count, irradiance), 0.0f);
    continued[i] = glm::vec4(lightwave_bounce_sum(x, n, fetch, count, third, irradiance.min_distance), 0.0f);
    const std::array<glm::vec3, 4> xs = {x, x + glm::vec3(0.25f, 0.0f, 0.0f), x + glm::vec3(0.0f, 0.125f, 0.0f), x - glm::vec3(0.0f, 0.0f, 0.5f)};
    const std::array<glm::vec3, 4> ns = {n, glm::vec3(n.y, n.z, n.x), glm::vec3(n.z, n.x, n.y), -n};
    const std::array<glm::vec3, 4> partial = {third, glm::vec3(third.y, third.z, third.x), glm::vec3(third.z, third.x, third.y), glm::vec3(0.0f)};
    const std::array<glm::vec3, 4> sums = lightwave_bounce_sums(xs, ns, fetch, count, partial, irradiance.min_distance);
    for (std::size_t k = 0; k < 3; ++k) packed_sums[k][i] = glm::vec4(sums[k], sums[3][static_cast<glm::length_t>(k)]);
  }
  // 2000 terms of two divides each, summed in the same order: 1e-5 relative, 1e-7 absolute near 0.
  const tolerance bounds{1e-7f, 1e-5f, 64, 0.0, "2000 terms of Eq. 3.2"};
  for (const testing::target_run& run : testing::every_vertex_target()) {
    const std::string target = run.name();
    CAPTURE(target);
    if (!testing::target_runs(run.where)) continue;
    source.name = "lightwave_vertex_bounce (" + target + ")";
    sums_source.name = "lightwave_bounce_sums (" + target + ")";
    const kernel_outputs gpu = run.run(source, inputs, run.where, resources);
    const kernel_outputs gpu_sums = run.run(sums_source, inputs, run.where, resources);
    require_parity(compare(source.name, gpu.floats[0], cpu, inputs, bounds, 3));
    require_parity(compare("lightwave_bounce_sum from a partial sum (" + target + ")", gpu.floats[1], continued, inputs, bounds, 3));
    for (std::size_t k = 0; k < 3; ++k)
      require_parity(compare("lightwave_bounce_sums, receiver " + std::to_string(k) + " and receiver 3's channel " + std::to_string(k) + " (" + target + ")",
                             gpu_sums.floats[k], packed_sums[k], inputs, bounds, 4));
  }
}

TEST_CASE("parity: a point light's sphere layouts (lightwave_sphere_sample, lightwave_sphere_layout_vpl) and its ray flux, on every target") {
  const lightwave_layout_settings<float> layout = test_layout();
  const int samples = lightwave_sphere_sample_count(layout.angle_deg, layout.per_ray);  // 12970
  const int vpls = lightwave_sphere_vpl_count(layout.angle_deg, layout.per_ray);        // 12610
  kernel_inputs inputs;
  inputs.width = 128;
  inputs.height = 102;  // 13056 texels >= 12970
  inputs.uints.assign(1, std::vector<glm::uvec4>(inputs.size()));
  inputs.floats.assign(1, std::vector<glm::vec4>(inputs.size()));
  std::mt19937 random(38);
  std::uniform_real_distribution<float> uniform(-1.0f, 1.0f);
  for (std::size_t i = 0; i < inputs.size(); ++i) {
    inputs.uints[0][i] = glm::uvec4(static_cast<unsigned>(std::min<std::size_t>(i, static_cast<std::size_t>(samples - 1))),
                                    static_cast<unsigned>(i % static_cast<std::size_t>(vpls)), 0u, 0u);
    // A surface normal for the flux: random, so that both faces are met.
    inputs.floats[0][i] = glm::vec4(glm::normalize(glm::vec3(uniform(random), uniform(random), uniform(random))), 0.0f);
  }
  point_light<float> light;
  light.position = {0.2f, 1.9f, -0.3f};
  light.intensity = {3.0f, 2.0f, 1.0f};
  kernel_source source;
  source.includes = {"lib/lightwave.glsl"};
  // The cone settings from the layout's block (every target has std140 blocks; the half-angle is not read).
  source.body = "lightwave_cone_settings cone = lightwave_cone_settings(layout_settings.light_direction, layout_settings.angle_deg, layout_settings.per_ray, 17.0);\n"
                "vec4 sample_ = lightwave_sphere_sample(int(uin0.x), cone);\n"
                "lightwave_vpl vpl = lightwave_sphere_layout_vpl(int(uin0.y), layout_settings);\n"
                "fout0 = sample_;\n"
                "fout1 = vec4(vpl.position, vpl.attenuation);\n"
                "fout2 = vec4(vpl.normal, float(lightwave_sphere_vpl_count(layout_settings.angle_deg, layout_settings.per_ray)));\n"
                "fout3 = vec4(lightwave_ray_flux(light, sample_.xyz, sample_.w, vec3(0.5, 0.7, 0.9), fin0.xyz), "
                "float(lightwave_sphere_sample_count(layout_settings.angle_deg, layout_settings.per_ray)));";
  source.float_outputs = 4;
  kernel_resources resources;
  resources.blocks = {settings_block("layout_settings", layout), settings_block("light", light)};
  lightwave_cone_settings<float> cone;
  cone.light_direction = layout.light_direction;
  cone.angle_deg = layout.angle_deg;
  cone.per_ray = layout.per_ray;
  cone.half_angle_deg = 17.0f;
  std::vector<glm::vec4> sample_out(inputs.size()), position(inputs.size()), normal(inputs.size()), flux(inputs.size());
  std::size_t lit = 0;
  for (std::size_t i = 0; i < inputs.size(); ++i) {
    const glm::vec4 sample = lightwave_sphere_sample(static_cast<int>(inputs.uints[0][i].x), cone);
    const lightwave_vpl<float> vpl = lightwave_sphere_layout_vpl(static_cast<int>(inputs.uints[0][i].y), layout);
    sample_out[i] = sample;
    position[i] = glm::vec4(vpl.position, vpl.attenuation);
    normal[i] = glm::vec4(vpl.normal, static_cast<float>(vpls));
    flux[i] = glm::vec4(lightwave_ray_flux(light, glm::vec3(sample), sample.w, glm::vec3(0.5f, 0.7f, 0.9f), glm::vec3(inputs.floats[0][i])),
                        static_cast<float>(samples));
    lit += flux[i].x > 0.0f;
  }
  CHECK(lit > inputs.size() / 4);  // both faces are met
  CHECK(lit < 3 * inputs.size() / 4);
  for (const testing::target_run& run : testing::every_target()) {
    const std::string target = run.name();
    CAPTURE(target);
    if (!testing::target_runs(run.where)) continue;
    source.name = "point light sphere layouts (" + target + ")";
    const kernel_outputs gpu = run.run(source, inputs, run.where, resources);
    // As lightwave_cone_sample's and lightwave_layout_vpl's bounds: the same arithmetic, plus a negation.
    require_parity(compare("lightwave_sphere_sample (" + target + ")", gpu.floats[0], sample_out, inputs, {1e-6f, 1e-6f, 16, 0.0, "polynomial cos, sqrt, normalize, cross"}));
    require_parity(compare("lightwave_sphere_layout_vpl position, attenuation (" + target + ")", gpu.floats[1], position, inputs,
                           {1e-6f, 0.0f, 8, 0.0, "polynomial sin/cos, normalize, cross"}));
    require_parity(compare("lightwave_sphere_layout_vpl normal, count (" + target + ")", gpu.floats[2], normal, inputs,
                           {1e-6f, 0.0f, 8, 0.0, "polynomial sin/cos, normalize, cross"}));
    // The flux: the sample's solid angle (1e-6 relative) times the intensity and albedo; whether
    // the random surface faces the ray is a decision that may flip where they are perpendicular
    // to a few ulp (1e-3 of the texels at most).
    require_parity(compare("lightwave_ray_flux for a point light (" + target + ")", gpu.floats[3], flux, inputs,
                           {1e-7f, 2e-6f, 16, 1e-3, "the solid angle's cancellation; the facing decision at near-ties"}));
  }
}

TEST_CASE("parity: a sun's parallel layout (lightwave_parallel_sample) and its ray flux, on every target") {
  const lightwave_layout_settings<float> layout = test_layout();
  const int samples = lightwave_parallel_sample_count(layout.angle_deg, layout.per_ray);
  kernel_inputs inputs;
  inputs.width = 128;
  inputs.height = (samples + 127) / 128;
  inputs.uints.assign(1, std::vector<glm::uvec4>(inputs.size()));
  inputs.floats.assign(1, std::vector<glm::vec4>(inputs.size()));
  std::mt19937 random(39);
  std::uniform_real_distribution<float> uniform(-1.0f, 1.0f);
  for (std::size_t i = 0; i < inputs.size(); ++i) {
    inputs.uints[0][i] = glm::uvec4(static_cast<unsigned>(std::min<std::size_t>(i, static_cast<std::size_t>(samples - 1))), 0u, 0u, 0u);
    inputs.floats[0][i] = glm::vec4(glm::normalize(glm::vec3(uniform(random), uniform(random), uniform(random))), 0.0f);
  }
  directional_light<float> sun;
  sun.direction = glm::normalize(glm::vec3(0.3f, -1.0f, 0.2f));
  sun.irradiance = {3.0f, 2.0f, 1.0f};
  kernel_source source;
  source.includes = {"lib/lightwave.glsl"};
  source.body = "vec3 sample_ = lightwave_parallel_sample(int(uin0.x), layout_settings.angle_deg, layout_settings.per_ray);\n"
                "fout0 = vec4(sample_, float(lightwave_parallel_sample_count(layout_settings.angle_deg, layout_settings.per_ray)));\n"
                "fout1 = vec4(lightwave_ray_flux(light, light.direction, sample_.z, vec3(0.5, 0.7, 0.9), fin0.xyz), float(lightwave_parallel_side(layout_settings.angle_deg)));";
  source.float_outputs = 2;
  kernel_resources resources;
  resources.blocks = {settings_block("layout_settings", layout), settings_block("light", sun)};
  std::vector<glm::vec4> sample_out(inputs.size()), flux(inputs.size());
  std::size_t lit = 0;
  for (std::size_t i = 0; i < inputs.size(); ++i) {
    const glm::vec3 sample = lightwave_parallel_sample<float>(static_cast<int>(inputs.uints[0][i].x), layout.angle_deg, layout.per_ray);
    sample_out[i] = glm::vec4(sample, static_cast<float>(samples));
    flux[i] = glm::vec4(lightwave_ray_flux(sun, sun.direction, sample.z, glm::vec3(0.5f, 0.7f, 0.9f), glm::vec3(inputs.floats[0][i])),
                        static_cast<float>(lightwave_parallel_side(layout.angle_deg)));
    lit += flux[i].x > 0.0f;
  }
  CHECK(lit > inputs.size() / 4);  // both faces are met
  CHECK(lit < 3 * inputs.size() / 4);
  for (const testing::target_run& run : testing::every_target()) {
    const std::string target = run.name();
    CAPTURE(target);
    if (!testing::target_runs(run.where)) continue;
    source.name = "sun parallel layout (" + target + ")";
    const kernel_outputs gpu = run.run(source, inputs, run.where, resources);
    // A few multiplies, adds and a floor: the lattice's fraction rounds alike on every target.
    require_parity(compare("lightwave_parallel_sample (" + target + ")", gpu.floats[0], sample_out, inputs, {1e-6f, 1e-6f, 8, 0.0, "the lattice's floor and a few products"}));
    require_parity(compare("lightwave_ray_flux for a sun (" + target + ")", gpu.floats[1], flux, inputs,
                           {1e-7f, 2e-6f, 16, 1e-3, "the facing decision at near-ties"}));
  }
}
