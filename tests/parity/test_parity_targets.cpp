// vplkit::parity's targets (gl33, gl45, gles3, vulkan): every stage a target has runs the same
// kernel, with a vec4 and a uvec4 table, a std140 uniform block and float and uint inputs and
// outputs, to the same exact results; a stage a target lacks is refused by name; a wrong result on Vulkan is reported
// at its texel like on GL; a compile error on Vulkan names the line; and the default context is
// current again after a run on another target.
#include <doctest/doctest.h>

#include <cstring>
#include <string>
#include <vector>

#include <vplkit/irradiance.hpp>
#include <vplkit/parity/doctest.hpp>

#include "doc_examples/parity_targets.cpp"  // docs/glsl-twins.md's example, taken from the page
#include "frontend/gl/gl.hpp"
#include "tests/parity/targets.hpp"

using namespace vplkit;
using namespace vplkit::parity;

namespace {

// fout0 = 2 fin0 + the table's texel + the block's min_distance; uout0 = uin0 xor the texel's
// coordinates xor the uint table's texel: every value a small multiple of 1/8, exact on every
// target, so the runs must agree bit for bit, and every part (input, table, uint table, block,
// uint path, texel numbering) shows when wrong.
kernel_source plumbing_kernel(const std::string& name) {
  kernel_source source;
  source.name = name;
  source.includes = {"lib/irradiance.glsl"};
  source.body =
      "fout0 = 2.0 * fin0 + offsets(texel) + vec4(settings.min_distance);\n"
      "uout0 = uin0 ^ uvec4(uint(texel.x), uint(texel.y), 7u, 0u) ^ words(texel);";
  source.float_outputs = 1;
  source.uint_outputs = 1;
  return source;
}

constexpr int grid_width = 13, grid_height = 7;  // not a multiple of the compute runs' 64

kernel_inputs plumbing_inputs() {
  kernel_inputs inputs = grid_of(grid_width, grid_height, 1, 1);
  for (std::size_t i = 0; i < inputs.size(); ++i) {
    const float f = static_cast<float>(i);
    inputs.floats[0][i] = glm::vec4(f, -f / 8.0f, 0.5f, f * 4.0f);
    inputs.uints[0][i] = glm::uvec4(static_cast<unsigned>(i), 3u * static_cast<unsigned>(i), 0xffffffffu, 0u);
  }
  return inputs;
}

kernel_resources plumbing_resources(float min_distance) {
  kernel_resources resources;
  std::vector<glm::vec4> offsets;
  for (int y = 0; y < grid_height; ++y)
    for (int x = 0; x < grid_width; ++x) offsets.push_back(glm::vec4(static_cast<float>(x), static_cast<float>(100 * y), 0.125f, -1.0f));
  resources.tables = {{"offsets", grid_width, grid_height, offsets}};
  // Words a float path would not carry: the top bit, a signalling NaN's pattern (a float texture
  // or conversion may quieten it), all ones, and one per texel.
  std::vector<glm::uvec4> words;
  for (unsigned i = 0; i < static_cast<unsigned>(grid_width * grid_height); ++i) words.push_back(glm::uvec4(0x80000000u | i, 0x7f800001u, 0xffffffffu - i, i << 20));
  resources.uint_tables = {{"words", grid_width, grid_height, words}};
  resources.blocks = {settings_block("settings", irradiance_settings<float>{min_distance})};
  return resources;
}

}  // namespace

TEST_CASE("parity targets: every stage of every target runs the same kernel with a table and a uniform block, bit for bit") {
  const kernel_inputs inputs = plumbing_inputs();
  const kernel_resources resources = plumbing_resources(0.375f);
  std::vector<glm::vec4> floats(inputs.size());
  std::vector<glm::uvec4> uints(inputs.size());
  for (std::size_t i = 0; i < inputs.size(); ++i) {
    const glm::vec4 offset = resources.tables[0].texels[i];
    floats[i] = 2.0f * inputs.floats[0][i] + offset + glm::vec4(0.375f);
    uints[i] = inputs.uints[0][i] ^ glm::uvec4(static_cast<unsigned>(i % grid_width), static_cast<unsigned>(i / grid_width), 7u, 0u) ^ resources.uint_tables[0].texels[i];
  }
  struct stage_run {
    target where;
    const char* stage;
  };
  const stage_run runs[] = {{target::gl33, "fragment"}, {target::gl33, "vertex"},  {target::gl45, "fragment"}, {target::gl45, "vertex"},
                            {target::gl45, "compute"},  {target::gles3, "fragment"}, {target::gles3, "vertex"}, {target::vulkan, "compute"}};
  for (const stage_run& run : runs) {
    const std::string name = std::string("plumbing (") + target_name(run.where) + " " + run.stage + ")";
    CAPTURE(name);
    if (!testing::target_runs(run.where)) continue;
    const kernel_source source = plumbing_kernel(name);
    const std::string stage = run.stage;
    const kernel_outputs gpu = stage == "fragment" ? run_fragment(source, inputs, run.where, resources)
                               : stage == "vertex" ? run_vertex(source, inputs, run.where, resources)
                                                   : run_compute(source, inputs, run.where, resources);
    require_parity(compare(name, gpu.floats[0], floats, inputs, {0.0f, 0.0f, 0, 0.0, "small multiples of 1/8: exact"}));
    require_parity(compare_exact(name, gpu.uints[0], uints, inputs));
  }
}

TEST_CASE("parity targets: the page's loop over every target runs the kernel on all four here, and a wrong kernel fails on each") {
  const kernel_inputs inputs = plumbing_inputs();
  const kernel_resources resources = plumbing_resources(0.375f);
  std::vector<glm::vec4> cpu(inputs.size());
  for (std::size_t i = 0; i < inputs.size(); ++i) cpu[i] = 2.0f * inputs.floats[0][i] + resources.tables[0].texels[i] + glm::vec4(0.375f);
  std::vector<std::string> skipped;
  const tolerance exact{0.0f, 0.0f, 0, 0.0, "exact"};
  const std::vector<comparison> results = compare_on_every_target(plumbing_kernel("the page's loop"), inputs, resources, cpu, exact, skipped);
  for (const std::string& reason : skipped) MESSAGE("skipped " << reason);
  std::size_t runnable = 0;  // all four (scripts/setup.sh installs every driver), but under OSMesa
  for (const target where : all_targets()) runnable += testing::target_runs(where) ? 1 : 0;
  CHECK(skipped.size() == all_targets().size() - runnable);
  REQUIRE(results.size() == runnable);
  for (const comparison& result : results) require_parity(result);
  const std::vector<comparison> wrong =
      compare_on_every_target(plumbing_kernel("the page's loop, off by 1/8"), inputs, plumbing_resources(0.5f), cpu, exact, skipped);
  REQUIRE(wrong.size() == runnable);
  for (const comparison& result : wrong) {
    CAPTURE(result.kernel);
    CHECK(result.mismatches == inputs.size() * 4);
  }
}

TEST_CASE("parity targets: a stage a target lacks is refused, naming the targets that have it") {
  const kernel_inputs inputs = plumbing_inputs();
  const kernel_resources resources = plumbing_resources(0.0f);
  const kernel_source source = plumbing_kernel("refused");
  CHECK_THROWS_WITH(run_compute(source, inputs, target::gl33, resources),
                    doctest::Contains("target gl33 has no compute shaders (GL 3.3; they came with GL 4.3): run_compute runs on gl45 and vulkan"));
  CHECK_THROWS_WITH(run_compute(source, inputs, target::gles3, resources),
                    doctest::Contains("target gles3 has no compute shaders (OpenGL ES 3.0, which WebGL2 is, has none"));
  CHECK_THROWS_WITH(run_fragment(source, inputs, target::vulkan, resources),
                    doctest::Contains("parity run_fragment refused on vulkan: vplkit::parity runs Vulkan kernels as compute shaders only"));
  CHECK_THROWS_WITH(run_vertex(source, inputs, target::vulkan, resources), doctest::Contains("use run_compute on vulkan"));
  kernel_resources with_setter = resources;
  with_setter.uniforms = [](const program&) {};
  CHECK_THROWS_WITH(run_compute(source, inputs, target::vulkan, with_setter), doctest::Contains("which Vulkan has not: pass the values in a kernel_block"));
  kernel_resources short_table = resources;
  short_table.tables[0].texels.pop_back();
  CHECK_THROWS_WITH(run_compute(source, inputs, target::gl45, short_table),
                    doctest::Contains("table 0 'offsets' is 13x7 with 90 texels: it needs a name and width * height texels"));
  kernel_resources short_words = resources;
  short_words.uint_tables[0].texels.pop_back();
  CHECK_THROWS_WITH(run_fragment(source, inputs, target::gl33, short_words),
                    doctest::Contains("uint table 0 'words' is 13x7 with 90 texels: it needs a name and width * height texels"));
  kernel_resources same_name = resources;
  same_name.uint_tables[0].name = "offsets";
  CHECK_THROWS_WITH(run_vertex(source, inputs, target::gl33, same_name),
                    doctest::Contains("uint table 0 is named 'offsets' like a table before it: each table needs a name of its own"));
}

TEST_CASE("parity targets: a wrong result on vulkan fails with the texel and its inputs, like on GL") {
  if (!testing::target_runs(target::vulkan)) return;
  const kernel_inputs inputs = plumbing_inputs();
  const kernel_resources resources = plumbing_resources(0.375f);
  kernel_source source = plumbing_kernel("off by one at texel (4, 5)");
  // One texel of the table's result is changed on the GPU side only.
  source.body += "\nif (texel == ivec2(4, 5)) fout0.y += 1.0;";
  const kernel_outputs gpu = run_compute(source, inputs, target::vulkan, resources);
  std::vector<glm::vec4> cpu(inputs.size());
  for (std::size_t i = 0; i < inputs.size(); ++i) cpu[i] = 2.0f * inputs.floats[0][i] + resources.tables[0].texels[i] + glm::vec4(0.375f);
  const comparison result = compare(source.name, gpu.floats[0], cpu, inputs, {0.0f, 0.0f, 0, 0.0, "exact"});
  MESSAGE(result.summary());
  CHECK_FALSE(result.passed());
  CHECK(result.mismatches == 1u);
  CHECK(result.worst.rfind("texel (4, 5).y: gpu=", 0) == 0);
  CHECK(result.worst.find("fin0=(69, -8.625, 0.5, 276)") != std::string::npos);
}

TEST_CASE("parity targets: a compile error on vulkan names the kernel and the line glslang reported, mapped to its file") {
  if (!testing::target_runs(target::vulkan)) return;
  kernel_source source = plumbing_kernel("undeclared on vulkan");
  source.body = "fout0 = vec4(not_declared_anywhere);";
  try {
    run_compute(source, plumbing_inputs(), target::vulkan, plumbing_resources(0.0f));
    FAIL("the compile error was not reported");
  } catch (const std::exception& failure) {
    const std::string message = failure.what();
    INFO(message);
    CHECK(message.find("vplkit::parity vulkan compute kernel undeclared on vulkan: GLSL compile error (glslang)") != std::string::npos);
    CHECK(message.find("<parity undeclared on vulkan>:") != std::string::npos);
    CHECK(message.find("not_declared_anywhere") != std::string::npos);
  }
}

TEST_CASE("parity targets: after a run on gles3 or gl45 the default GL 3.3 context is current again") {
  for (const target other : {target::gles3, target::gl45}) {
    const std::string other_name = target_name(other);
    CAPTURE(other_name);
    if (!testing::target_runs(other)) continue;
    run_fragment(plumbing_kernel("elsewhere"), plumbing_inputs(), other, plumbing_resources(0.0f));
    const char* version = reinterpret_cast<const char*>(glGetString(GL_VERSION));
    REQUIRE(version);
    CHECK(std::strncmp(version, "OpenGL ES", 9) != 0);
    CHECK(test_context_kind().find("EGL") != std::string::npos);
  }
}

TEST_CASE("parity targets: the names and the GLSL each target's shaders start with") {
  std::vector<std::string> names;
  for (const target where : all_targets()) names.push_back(target_name(where));
  CHECK(names == std::vector<std::string>{"gl33", "gl45", "gles3", "vulkan"});
  CHECK(glsl_preamble(target::gl33) == "#version 330 core\n");
  CHECK(glsl_preamble(target::gl45) == "#version 450 core\n");
  CHECK(glsl_preamble(target::vulkan) == "#version 450\n");
  CHECK(glsl_preamble(target::gles3).rfind("#version 300 es\nprecision highp float;\nprecision highp int;\n", 0) == 0);
  for (const target where : all_targets())
    MESSAGE(std::string(target_name(where)) << ": " << (target_unavailable(where).empty() ? "available" : target_unavailable(where)));
}
