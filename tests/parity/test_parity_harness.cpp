// The harness itself must be able to fail: a deliberately wrong CPU twin is caught, the worst
// texel is located, the tolerance bounds and the allowed flip fraction work as documented.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>
#include <string>

#include <vplkit/hash.hpp>
#include <vplkit/parity/doctest.hpp>

using namespace vplkit::parity;

namespace {
kernel_inputs ramp(int width, int height) {
  kernel_inputs inputs;
  inputs.width = width;
  inputs.height = height;
  inputs.floats.assign(1, std::vector<glm::vec4>(inputs.size()));
  for (std::size_t i = 0; i < inputs.size(); ++i) inputs.floats[0][i] = glm::vec4(static_cast<float>(i), 1.0f, -2.0f, 0.5f);
  return inputs;
}
}  // namespace

TEST_CASE("ulp_distance counts representable floats between two values") {
  CHECK(ulp_distance(1.0f, 1.0f) == 0);
  CHECK(ulp_distance(0.0f, -0.0f) == 0);
  CHECK(ulp_distance(1.0f, std::nextafter(1.0f, 2.0f)) == 1);
  CHECK(ulp_distance(-std::numeric_limits<float>::denorm_min(), std::numeric_limits<float>::denorm_min()) == 2);
}

TEST_CASE("the harness finds a wrong texel, names its coordinates and inputs") {
  const kernel_inputs inputs = ramp(8, 4);
  kernel_source source;
  source.name = "copy";
  source.body = "fout0 = fin0 * 2.0;";
  source.float_outputs = 1;
  const kernel_outputs gpu = run_fragment(source, inputs);
  std::vector<glm::vec4> cpu(inputs.size());
  for (std::size_t i = 0; i < inputs.size(); ++i) cpu[i] = inputs.floats[0][i] * 2.0f;
  CHECK(compare("copy", gpu.floats[0], cpu, inputs, {}).passed());

  cpu[13].y += 1e-3f;  // texel (5, 1)
  const comparison wrong = compare("copy", gpu.floats[0], cpu, inputs, {0.0f, 1e-6f, 2, 0.0, "exact copy"});
  CHECK(!wrong.passed());
  CHECK(wrong.mismatches == 1);
  CHECK(wrong.worst.find("texel (5, 1).y") == 0);
  CHECK(wrong.worst.find("fin0=(13, 1, -2, 0.5)") != std::string::npos);
  // One flip among 128 values passes with an allowed fraction of 1%, not with 0.5%.
  CHECK(compare("copy", gpu.floats[0], cpu, inputs, {0.0f, 0.0f, 0, 0.01, "flip"}).passed());
  CHECK(!compare("copy", gpu.floats[0], cpu, inputs, {0.0f, 0.0f, 0, 0.005, "flip"}).passed());

  cpu[13].y = std::numeric_limits<float>::quiet_NaN();  // a NaN never passes
  CHECK(!compare("copy", gpu.floats[0], cpu, inputs, {1e30f, 1e30f, 1 << 30, 0.0, "loose"}).passed());
}

TEST_CASE("abs_scale makes the absolute bound per texel, and a failing summary states the tolerance") {
  const kernel_inputs inputs = ramp(8, 4);
  std::vector<glm::vec4> gpu(inputs.size(), glm::vec4(1.0f)), cpu = gpu;
  cpu[13].x += 1e-3f;  // texel (5, 1)
  tolerance bounds{1e-4f, 0.0f, 0, 0.0, "scaled on purpose"};
  const comparison unscaled = compare("scale", gpu, cpu, inputs, bounds, 1);
  CHECK(!unscaled.passed());
  CHECK(unscaled.summary().find("tolerance: abs <= 0.0001 or rel <= 0 or ulp <= 0, allowed fraction 0 (scaled on purpose)") != std::string::npos);
  bounds.abs_scale.assign(inputs.size(), glm::vec4(1.0f));
  bounds.abs_scale[13].x = 20.0f;  // 1e-3 <= 1e-4 * 20
  const comparison scaled = compare("scale", gpu, cpu, inputs, bounds, 1);
  CHECK(scaled.passed());
  CHECK(scaled.max_abs_over_bound == doctest::Approx(0.5).epsilon(1e-3));
  CHECK(scaled.worst.find("texel (5, 1).x: gpu=1 cpu=1.00100005 (abs 0.00100004673 of 0.0019999") == 0);
  CHECK(scaled.summary().find("tolerance:") == std::string::npos);
  bounds.abs_scale[13].x = 5.0f;
  CHECK(!compare("scale", gpu, cpu, inputs, bounds, 1).passed());
  bounds.abs_scale.pop_back();
  CHECK_THROWS_WITH(compare("scale", gpu, cpu, inputs, bounds, 1), doctest::Contains("abs_scale has 31 values for 32 texels"));
}

TEST_CASE("a folder given to add_shader_root is searched before vplkit's shaders") {
  CHECK_THROWS_WITH(add_shader_root("/nonexistent/vplkit-parity-root"), doctest::Contains("/nonexistent/vplkit-parity-root is not a folder"));
  // A file name of its own, so that the folder changes nothing for the other tests of this process.
  const std::filesystem::path root = std::filesystem::temp_directory_path() / ("vplkit-parity-root-" + std::to_string(std::random_device{}()));
  std::filesystem::create_directories(root / "parity_root_test");
  std::ofstream(root / "parity_root_test/doubled_hash.glsl") << "#include \"lib/hash.glsl\"\nuint doubled_hash(uint v) { return 2u * hash_uint32(v); }\n";
  add_shader_root(root);
  add_shader_root(root);
  const shader_library& shaders = test_shaders();
  CHECK(shaders.locate("parity_root_test/doubled_hash.glsl") == root / "parity_root_test/doubled_hash.glsl");
  CHECK(std::count(shaders.roots().begin(), shaders.roots().end(), root) == 1);
  CHECK(std::filesystem::exists(shaders.roots().back() / "lib/hash.glsl"));  // vplkit's, last
  kernel_source source;
  source.name = "doubled_hash";
  source.includes = {"parity_root_test/doubled_hash.glsl"};
  source.body = "uout0 = uvec4(doubled_hash(uin0.x));";
  source.uint_outputs = 1;
  kernel_inputs inputs = grid_of(16, 1, 0, 1);
  for (std::size_t i = 0; i < inputs.size(); ++i) inputs.uints[0][i] = glm::uvec4(static_cast<unsigned>(i) * 977u);
  const kernel_outputs gpu = run_fragment(source, inputs);
  std::vector<glm::uvec4> cpu(inputs.size());
  for (std::size_t i = 0; i < inputs.size(); ++i) cpu[i] = glm::uvec4(2u * vplkit::hash_uint32(inputs.uints[0][i].x));
  require_parity(compare_exact("doubled_hash from an added root", gpu.uints[0], cpu, inputs));
  std::filesystem::remove_all(root);
}

TEST_CASE("the vertex-stage path returns one value per input, in order") {
  const kernel_inputs inputs = ramp(16, 3);
  kernel_source source;
  source.name = "vertex copy";
  source.body = "fout0 = fin0 + vec4(1.0);";
  source.float_outputs = 1;
  const kernel_outputs gpu = run_vertex(source, inputs);
  REQUIRE(gpu.floats[0].size() == inputs.size());
  for (std::size_t i = 0; i < inputs.size(); ++i) REQUIRE(gpu.floats[0][i] == inputs.floats[0][i] + glm::vec4(1.0f));
}

TEST_CASE("the harness runs on the headless context VPLKIT_CONTEXT asks for (EGL by default)") {
  const char* requested = std::getenv("VPLKIT_CONTEXT");
  const std::string kind = test_context_kind();
  MESSAGE("parity context: " << kind);
  if (requested && std::string(requested) == "osmesa") CHECK(kind == "OSMesa");
  else CHECK(kind.rfind("EGL", 0) == 0);
}
