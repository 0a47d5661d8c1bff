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
#include <sstream>
#include <string>
#include <thread>

#include <vplkit/hash.hpp>
#include <vplkit/parity/doctest.hpp>

#include "frontend/gl/gl.hpp"

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

// doctest::Contains of a built message (it takes a C string, and copies it).
doctest::Contains contains(const std::string& text) { return doctest::Contains(text.c_str()); }

std::string thread_text(std::thread::id thread) {
  std::ostringstream text;
  text << thread;
  return text.str();
}

int gl_limit(GLenum name) {
  test_shaders();  // the context, current on this thread
  GLint value = 0;
  glGetIntegerv(name, &value);
  return value;
}

// A kernel that reads every input and writes every output, so that none is optimised away.
kernel_source sum_of_inputs(const kernel_inputs& inputs, int float_outputs, int uint_outputs) {
  kernel_source source;
  source.name = "sum of " + std::to_string(inputs.floats.size()) + " inputs";
  source.body = "vec4 sum = vec4(0.0);\n";
  for (std::size_t i = 0; i < inputs.floats.size(); ++i) source.body += "sum += fin" + std::to_string(i) + ";\n";
  for (int i = 0; i < float_outputs; ++i) source.body += "fout" + std::to_string(i) + " = sum + vec4(" + std::to_string(i) + ");\n";
  for (int i = 0; i < uint_outputs; ++i) source.body += "uout" + std::to_string(i) + " = uvec4(sum) + uvec4(" + std::to_string(i) + ");\n";
  source.float_outputs = float_outputs;
  source.uint_outputs = uint_outputs;
  return source;
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

TEST_CASE("compare refuses a tolerance, fraction or channel count that would pass without comparing") {
  // Every gpu value differs from its cpu twin: each refused argument used to let this pass.
  const kernel_inputs inputs = ramp(8, 4);
  const std::vector<glm::vec4> gpu(inputs.size(), glm::vec4(1.0f)), cpu(inputs.size(), glm::vec4(2.0f));
  const std::vector<glm::uvec4> gpu_uints(inputs.size(), glm::uvec4(1u)), cpu_uints(inputs.size(), glm::uvec4(2u));
  CHECK(!compare("all differ", gpu, cpu, inputs, {}).passed());
  const auto with_fraction = [](double fraction) { return tolerance{0.0f, 0.0f, 0, fraction, "misuse"}; };
  const double nan = std::numeric_limits<double>::quiet_NaN();
  CHECK_THROWS_WITH(compare("k", gpu, cpu, inputs, with_fraction(nan)), "parity compare k: allowed_mismatch_fraction is nan; it must be in [0, 1]");
  CHECK_THROWS_WITH(compare("k", gpu, cpu, inputs, with_fraction(-0.5)), "parity compare k: allowed_mismatch_fraction is -0.5; it must be in [0, 1]");
  CHECK_THROWS_WITH(compare("k", gpu, cpu, inputs, with_fraction(2.0)), "parity compare k: allowed_mismatch_fraction is 2; it must be in [0, 1]");
  CHECK_THROWS_WITH(compare_exact("k", gpu_uints, cpu_uints, inputs, 2.0), doctest::Contains("allowed_mismatch_fraction is 2; it must be in [0, 1]"));
  CHECK_THROWS_WITH(compare_exact("k", gpu_uints, cpu_uints, inputs, nan), doctest::Contains("allowed_mismatch_fraction is nan"));
  // The bounds of the fraction are allowed: 1 lets every value fail.
  CHECK(compare("k", gpu, cpu, inputs, with_fraction(1.0)).passed());
  CHECK(!compare("k", gpu, cpu, inputs, with_fraction(0.0)).passed());
  for (int channels : {0, -1, 5, 1 << 30})
    CHECK_THROWS_WITH(compare("k", gpu, cpu, inputs, {}, channels),
                      ("parity compare k: channels is " + std::to_string(channels) + "; it must be 1 to 4 (x, xy, xyz or xyzw)").c_str());
  CHECK_THROWS_WITH(compare_exact("k", gpu_uints, cpu_uints, inputs, 0.0, 0), doctest::Contains("channels is 0; it must be 1 to 4"));
  for (int channels = 1; channels <= 4; ++channels) CHECK(compare("k", gpu, cpu, inputs, {}, channels).values == inputs.size() * static_cast<std::size_t>(channels));

  const float inf = std::numeric_limits<float>::infinity(), fnan = std::numeric_limits<float>::quiet_NaN();
  for (float bad : {fnan, inf, -inf, -1e-6f}) {
    CHECK_THROWS_WITH(compare("k", gpu, cpu, inputs, {bad, 0.0f, 0, 0.0, ""}), doctest::Contains("the tolerance's max_abs is "));
    CHECK_THROWS_WITH(compare("k", gpu, cpu, inputs, {0.0f, bad, 0, 0.0, ""}), doctest::Contains("the tolerance's max_rel is "));
  }
  CHECK_THROWS_WITH(compare("k", gpu, cpu, inputs, {0.0f, 0.0f, -1, 0.0, ""}),
                    "parity compare k: the tolerance's max_ulp is -1; bounds must be finite and non-negative");
  tolerance scaled{1.0f, 0.0f, 0, 0.0, ""};
  scaled.abs_scale.assign(inputs.size(), glm::vec4(1.0f));
  scaled.abs_scale[13].z = fnan;  // texel (5, 1)
  CHECK_THROWS_WITH(compare("k", gpu, cpu, inputs, scaled),
                    "parity compare k: the tolerance's abs_scale of texel (5, 1).z is nan; bounds must be finite and non-negative");
  scaled.abs_scale[13].z = -2.0f;
  CHECK_THROWS_WITH(compare("k", gpu, cpu, inputs, scaled), doctest::Contains("abs_scale of texel (5, 1).z is -2"));
}

TEST_CASE("compare refuses an empty grid and outputs or inputs that are not one per texel") {
  const kernel_inputs inputs = ramp(8, 4);
  const std::vector<glm::vec4> values(inputs.size(), glm::vec4(1.0f));
  kernel_inputs empty;
  CHECK_THROWS_WITH(compare("k", {}, {}, empty, {}), "parity compare k: the input grid is 0x0; it must be at least 1x1");
  CHECK_THROWS_WITH(compare_exact("k", {}, {}, empty), doctest::Contains("the input grid is 0x0"));
  // -1 x -1 is 1 texel when cast to size_t: the sign is checked, not the product.
  kernel_inputs negative;
  negative.width = negative.height = -1;
  CHECK_THROWS_WITH(compare("k", {glm::vec4(0.0f)}, {glm::vec4(1.0f)}, negative, {}), doctest::Contains("the input grid is -1x-1"));
  // An input shorter than the grid was read past its end by the report of a mismatch.
  kernel_inputs short_input = inputs;
  short_input.floats[0].resize(5);
  std::vector<glm::vec4> cpu = values;
  cpu[31].x = 2.0f;
  CHECK_THROWS_WITH(compare("k", values, cpu, short_input, {}), "parity compare k: float input 0 has 5 values for a 8x4 grid (32 texels)");
  kernel_inputs long_uint = inputs;
  long_uint.uints.assign(1, std::vector<glm::uvec4>(33));
  CHECK_THROWS_WITH(compare("k", values, values, long_uint, {}), doctest::Contains("uint input 0 has 33 values for a 8x4 grid"));
  CHECK_THROWS_WITH(compare("k", std::vector<glm::vec4>(31), values, inputs, {}),
                    "parity compare k: the outputs have gpu 31 and cpu 32 values for a 8x4 grid (32 texels)");
  CHECK_THROWS_WITH(compare_exact("k", std::vector<glm::uvec4>(32), std::vector<glm::uvec4>(64), inputs),
                    doctest::Contains("the outputs have gpu 32 and cpu 64 values"));
}

TEST_CASE("a run refuses an empty grid, inputs that are not one per texel and a kernel without outputs") {
  kernel_inputs inputs = ramp(4, 2);
  kernel_source source = sum_of_inputs(inputs, 1, 0);
  inputs.floats[0].pop_back();
  CHECK_THROWS_WITH(run_fragment(source, inputs), ("parity run_fragment " + source.name + ": float input 0 has 7 values for a 4x2 grid (8 texels)").c_str());
  CHECK_THROWS_WITH(run_vertex(source, inputs), contains("run_vertex " + source.name + ": float input 0 has 7 values"));
  CHECK_THROWS_WITH(run_fragment(source, kernel_inputs{}), doctest::Contains("the input grid is 0x0; it must be at least 1x1"));
  source.float_outputs = 0;
  CHECK_THROWS_WITH(run_fragment(source, ramp(4, 2)), doctest::Contains("the kernel has no outputs: set float_outputs or uint_outputs"));
  source.float_outputs = -1;
  CHECK_THROWS_WITH(run_vertex(source, ramp(4, 2)), doctest::Contains("float_outputs -1 and uint_outputs 0: an output count cannot be negative"));
}

TEST_CASE("more inputs or outputs than the stage has names the GL limit; as many as it has run") {
  // The vertex stage: one attribute per input (GL 3.3: 16, llvmpipe's too).
  const int attributes = gl_limit(GL_MAX_VERTEX_ATTRIBS);
  CHECK(attributes >= 16);
  const auto grid_with = [](int count) {
    kernel_inputs inputs = grid_of(4, 1, count);
    for (std::size_t i = 0; i < inputs.floats.size(); ++i)
      for (std::size_t t = 0; t < inputs.size(); ++t) inputs.floats[i][t] = glm::vec4(static_cast<float>(i + t));
    return inputs;
  };
  const auto expected_sum = [](const kernel_inputs& inputs, std::size_t texel) {
    glm::vec4 sum(0.0f);
    for (const auto& input : inputs.floats) sum += input[texel];
    return sum;
  };
  const kernel_inputs forty = grid_with(40);
  CHECK_THROWS_WITH(run_vertex(sum_of_inputs(forty, 1, 0), forty),
                    ("parity run_vertex sum of 40 inputs: 40 inputs (40 float, 0 uint), each a vertex attribute, but a vertex shader has at most " +
                     std::to_string(attributes) + " (GL_MAX_VERTEX_ATTRIBS of this context): split the kernel into runs with fewer, or pack more "
                     "values into each vec4").c_str());
  const kernel_inputs all_attributes = grid_with(attributes), one_too_many = grid_with(attributes + 1);
  const kernel_outputs at_limit = run_vertex(sum_of_inputs(all_attributes, 1, 0), all_attributes);
  for (std::size_t t = 0; t < all_attributes.size(); ++t) CHECK(at_limit.floats[0][t] == expected_sum(all_attributes, t));
  CHECK_THROWS_WITH(run_vertex(sum_of_inputs(one_too_many, 1, 0), one_too_many), doctest::Contains("GL_MAX_VERTEX_ATTRIBS"));

  // The fragment stage: one texture unit per input.
  const int units = gl_limit(GL_MAX_TEXTURE_IMAGE_UNITS);
  CHECK(units >= 16);
  const kernel_inputs all_units = grid_with(units), past_units = grid_with(units + 1);
  const kernel_outputs at_units = run_fragment(sum_of_inputs(all_units, 1, 0), all_units);
  for (std::size_t t = 0; t < all_units.size(); ++t) CHECK(at_units.floats[0][t] == expected_sum(all_units, t));
  CHECK_THROWS_WITH(run_fragment(sum_of_inputs(past_units, 1, 0), past_units),
                    contains(std::to_string(units + 1) + " inputs (" + std::to_string(units + 1) + " float, 0 uint), each a texture, but a fragment "
                                      "shader has at most " + std::to_string(units) + " (GL_MAX_TEXTURE_IMAGE_UNITS of this context)"));

  // Outputs: render targets, and transform feedback buffers.
  const kernel_inputs one = grid_with(1);
  const int draw_buffers = gl_limit(GL_MAX_DRAW_BUFFERS);
  CHECK(draw_buffers >= 8);
  CHECK(run_fragment(sum_of_inputs(one, draw_buffers - 1, 1), one).uints.size() == 1);
  CHECK_THROWS_WITH(run_fragment(sum_of_inputs(one, draw_buffers, 1), one),
                    contains(std::to_string(draw_buffers + 1) + " outputs (" + std::to_string(draw_buffers) +
                                      " float, 1 uint), each a render target, but a fragment shader has at most " + std::to_string(draw_buffers) +
                                      " (GL_MAX_DRAW_BUFFERS of this context)"));
  const int captured = gl_limit(GL_MAX_TRANSFORM_FEEDBACK_SEPARATE_ATTRIBS);
  CHECK(captured >= 4);
  CHECK(run_vertex(sum_of_inputs(one, captured, 0), one).floats.size() == static_cast<std::size_t>(captured));
  CHECK_THROWS_WITH(run_vertex(sum_of_inputs(one, captured, 1), one),
                    contains("each captured by transform feedback, but a vertex shader has at most " + std::to_string(captured) +
                                      " (GL_MAX_TRANSFORM_FEEDBACK_SEPARATE_ATTRIBS of this context)"));
}

TEST_CASE("a call from a thread without the context says so and names the context's thread") {
  const kernel_inputs inputs = ramp(4, 1);
  const kernel_source source = sum_of_inputs(inputs, 1, 0);
  const kernel_outputs here = run_fragment(source, inputs);  // the context is this thread's
  const std::string this_thread = thread_text(std::this_thread::get_id());
  std::string worker_thread, run_error, shaders_error, kind;
  std::thread worker([&] {
    worker_thread = thread_text(std::this_thread::get_id());
    try {
      run_vertex(source, inputs);
    } catch (const std::exception& failure) {
      run_error = failure.what();
    }
    try {
      test_shaders();
    } catch (const std::exception& failure) {
      shaders_error = failure.what();
    }
    kind = test_context_kind();  // a fact, not a GL call: any thread may ask
  });
  worker.join();
  CHECK(run_error == "vplkit::parity: run_vertex of " + source.name + " was called on thread " + worker_thread +
                         ", but the headless GL context is current on thread " + this_thread +
                         " (the thread of the first parity call, which made it): a GL context is current on one thread, so make every "
                         "parity call on that one");
  CHECK(shaders_error.find("test_shaders was called on thread " + worker_thread) != std::string::npos);
  CHECK(kind == test_context_kind());
  // This thread still runs, with the same result.
  CHECK(run_fragment(source, inputs).floats[0] == here.floats[0]);
}
