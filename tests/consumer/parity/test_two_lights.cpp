// A user's property test of its own GLSL with vplkit::parity, from an installed vplkit:
// shaders/my/two_lights.glsl (which includes vplkit's lib/irradiance.glsl) against its C++ twin
// on 10^4 seeded inputs, through the doctest adapter.
//
// Two suites, run as two processes (CMakeLists.txt): the default one adds shaders/ as the shader
// root; "perturbed" adds a copy of it whose two_lights_irradiance returns sum * 1.001, so its
// first case must fail with a report that names the worst texel (check_perturbed_report.cmake
// reads it) and its second checks that report's content from inside. A third, "targets", runs the
// same property on the target CONSUMER_TARGET names (gl33, gl45, gles3, vulkan; one process per
// target, CMakeLists.txt), or exits 77 (ctest: skipped) naming what this machine lacks.
#define DOCTEST_CONFIG_IMPLEMENT_WITH_MAIN
#include <doctest/doctest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <sstream>
#include <string>

#include <vplkit/parity/doctest.hpp>

#include "two_lights_test.hpp"

namespace fs = std::filesystem;
namespace parity = vplkit::parity;

namespace {

parity::comparison run_and_compare(std::uint32_t seed) {
  const parity::kernel_inputs in = two_lights::inputs(seed);
  const parity::kernel_outputs gpu = parity::run_fragment(two_lights::kernel(), in, two_lights::uniforms());
  return two_lights::compare(gpu.floats[0], in);
}

std::string read_text(const fs::path& path) {
  std::ifstream in(path);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

}  // namespace

TEST_CASE("two_lights.glsl equals its C++ twin on 10^4 seeded inputs") {
  parity::add_shader_root(CONSUMER_SHADERS);
  MESSAGE("context: " << parity::test_context_kind());
  for (std::uint32_t seed : {1u, 2u}) parity::require_parity(run_and_compare(seed));
}

TEST_CASE("the includes resolve to the consumer's folder and to the installed vplkit twins") {
  parity::add_shader_root(CONSUMER_SHADERS);
  const parity::shader_library& shaders = parity::test_shaders();
  CHECK(fs::equivalent(shaders.locate("my/two_lights.glsl"), fs::path(CONSUMER_SHADERS) / "my/two_lights.glsl"));
  CHECK(fs::equivalent(shaders.locate("lib/irradiance.glsl"), fs::path(INSTALLED_VPLKIT_SHADERS) / "lib/irradiance.glsl"));
  CHECK(fs::equivalent(shaders.roots().back(), INSTALLED_VPLKIT_SHADERS));
}

TEST_CASE("the source vplkit_expand_glsl wrote at build time runs bit for bit like the includes") {
  parity::add_shader_root(CONSUMER_SHADERS);
  const std::string expanded = read_text(EXPANDED_TWO_LIGHTS);
  REQUIRE(expanded.find("vec3 pixel_light_irradiance(") != std::string::npos);
  REQUIRE(expanded.find("#include") == std::string::npos);
  const parity::kernel_inputs in = two_lights::inputs(3);
  parity::kernel_source self_contained = two_lights::kernel();
  self_contained.includes.clear();
  self_contained.declarations = expanded + self_contained.declarations;
  const parity::kernel_outputs included = parity::run_fragment(two_lights::kernel(), in, two_lights::uniforms());
  const parity::kernel_outputs built = parity::run_fragment(self_contained, in, two_lights::uniforms());
  parity::require_parity(parity::compare("expanded two_lights_irradiance", built.floats[0], included.floats[0], in,
                                         {0.0f, 0.0f, 0, 0.0, "the same GLSL: bit for bit"}, 3));
}

TEST_CASE("perturbed: a copy of the GLSL off by 0.1 % fails" * doctest::test_suite("perturbed")) {
  parity::add_shader_root(PERTURBED_SHADERS);
  parity::require_parity(run_and_compare(1));
}

TEST_CASE("perturbed: the report names the worst texel, its values and its inputs" * doctest::test_suite("perturbed")) {
  parity::add_shader_root(PERTURBED_SHADERS);
  const parity::kernel_inputs in = two_lights::inputs(1);
  const parity::kernel_outputs gpu = parity::run_fragment(two_lights::kernel(), in, two_lights::uniforms());
  const std::vector<glm::vec4> cpu = two_lights::on_cpu(in);
  const parity::comparison result = two_lights::compare(gpu.floats[0], in);
  CHECK_FALSE(result.passed());
  // Every value above 1 % of its error scale is off by 1e-5 of the scale or more, almost twice
  // the bound: each is a mismatch (values near 0, and near-tangent lights, may pass).
  const std::vector<glm::vec4> scales = two_lights::error_scales(in);
  std::size_t clearly_perturbed = 0;
  for (std::size_t i = 0; i < cpu.size(); ++i)
    for (int c = 0; c < 3; ++c) clearly_perturbed += std::fabs(cpu[i][c]) > 1e-2f * scales[i][c] ? 1 : 0;
  MESSAGE(result.summary());
  CHECK(clearly_perturbed > result.values / 10);
  CHECK(result.mismatches >= clearly_perturbed);
  // "texel (x, y).c: gpu=... cpu=...": the named texel is one the perturbation moved by 0.1 %, and
  // the inputs listed are that texel's.
  int x = -1, y = -1;
  char channel = '?';
  REQUIRE(std::sscanf(result.worst.c_str(), "texel (%d, %d).%c", &x, &y, &channel) == 3);
  REQUIRE(x >= 0);
  REQUIRE(x < in.width);
  REQUIRE(y >= 0);
  REQUIRE(y < in.height);
  const std::size_t index = static_cast<std::size_t>(y) * static_cast<std::size_t>(in.width) + static_cast<std::size_t>(x);
  const int c = channel - 'x';
  REQUIRE((c >= 0 && c < 3));
  CHECK(gpu.floats[0][index][c] / cpu[index][c] == doctest::Approx(1.001).epsilon(5e-5));
  std::ostringstream fin0;
  fin0 << std::setprecision(9) << "fin0=(" << in.floats[0][index].x << ", " << in.floats[0][index].y;
  CHECK(result.worst.find(fin0.str()) != std::string::npos);
  CHECK(result.summary().find("worst texel (" + std::to_string(x) + ", " + std::to_string(y) + ")") != std::string::npos);
  CHECK(result.summary().find("tolerance: abs <= 6e-06 x the texel's abs_scale or rel <= 0 or ulp <= 0") != std::string::npos);
}

TEST_CASE("targets: two_lights.glsl equals its C++ twin on the target CONSUMER_TARGET names" * doctest::test_suite("targets")) {
  const char* name = std::getenv("CONSUMER_TARGET");
  REQUIRE(name);
  const std::string wanted = name;
  const parity::target* chosen = nullptr;
  for (const parity::target& where : parity::all_targets())
    if (wanted == parity::target_name(where)) chosen = &where;
  INFO("CONSUMER_TARGET=" << wanted);
  REQUIRE(chosen);
  const parity::target where = *chosen;
  if (const std::string reason = parity::target_unavailable(where); !reason.empty()) {
    // Skipped, visibly: ctest lists the test as "Skipped" and prints this line.
    std::cout << "SKIPPED: target " << wanted << " is not available on this machine: " << reason << std::endl;
    std::exit(77);
  }
  parity::add_shader_root(CONSUMER_SHADERS);
  for (std::uint32_t seed : {1u, 2u}) {
    const parity::kernel_inputs in = two_lights::inputs(seed);
    // Compute where the target has it (gl45, vulkan), fragment where not (gl33, gles3).
    const bool compute = where == parity::target::gl45 || where == parity::target::vulkan;
    const parity::kernel_outputs gpu = compute ? parity::run_compute(two_lights::kernel_on_targets(), in, where, two_lights::resources_on_targets())
                                               : parity::run_fragment(two_lights::kernel_on_targets(), in, where, two_lights::resources_on_targets());
    const parity::comparison result = two_lights::compare(gpu.floats[0], in);
    MESSAGE(wanted << std::string(compute ? " compute: " : " fragment: ") << result.summary());
    parity::require_parity(result);
  }
}
