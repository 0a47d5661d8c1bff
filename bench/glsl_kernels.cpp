// GLSL kernel micro-benchmarks (Google Benchmark): the shipped twins in shaders/lib/ run through
// the parity harness (vplkit::parity::run_fragment) on whatever headless context it finds
// (llvmpipe here, a GPU where one is), so that a lever is measured on the kernel alone, the
// variants interleaved in one process, without a pipeline's other passes around it.
//   build/bench/vplkit_glsl_bench --benchmark_filter=form_factor --benchmark_repetitions=3
// Each run uploads the inputs, draws one fragment per texel and reads the outputs back; every
// fragment evaluates its kernel `evaluations` times (x moved each time, so none is hoisted), so
// that the kernel outweighs the transfers: items_per_second counts kernel evaluations.
#include <benchmark/benchmark.h>

#include <random>
#include <string>

#include <vplkit/parity/parity.hpp>

namespace {

constexpr int grid = 128;         // fragments per side
constexpr int evaluations = 32;   // per fragment

// Quads as the final gather meets them: a texel-sized quad at distance ~1 around a receiver with
// a random normal, about half of them straddling or below its tangent plane.
const vplkit::parity::kernel_inputs& quad_inputs() {
  static const vplkit::parity::kernel_inputs inputs = [] {
    vplkit::parity::kernel_inputs in;
    in.width = grid;
    in.height = grid;
    in.floats.assign(5, std::vector<glm::vec4>(in.size()));
    std::mt19937 random(7);
    std::uniform_real_distribution<float> uniform(-1.0f, 1.0f);
    for (std::size_t i = 0; i < in.size(); ++i) {
      const glm::vec3 n = glm::normalize(glm::vec3(uniform(random), uniform(random), uniform(random)));
      const glm::vec3 origin = glm::normalize(glm::vec3(uniform(random), uniform(random), uniform(random)));
      const glm::vec3 e1 = glm::vec3(uniform(random), uniform(random), uniform(random)) * 0.4f, e2 = glm::vec3(uniform(random), uniform(random), uniform(random)) * 0.4f;
      in.floats[0][i] = glm::vec4(n, 0.0f);
      in.floats[1][i] = glm::vec4(origin, 0.0f);
      in.floats[2][i] = glm::vec4(origin + e1, 0.0f);
      in.floats[3][i] = glm::vec4(origin + e1 + e2, 0.0f);
      in.floats[4][i] = glm::vec4(origin + e2, 0.0f);
    }
    return in;
  }();
  return inputs;
}

void run_kernel(benchmark::State& state, const vplkit::parity::kernel_source& source, const vplkit::parity::kernel_inputs& inputs) {
  vplkit::parity::run_fragment(source, inputs);  // compile and warm up outside the timing
  for (auto _ : state) benchmark::DoNotOptimize(vplkit::parity::run_fragment(source, inputs));
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()) * grid * grid * evaluations);
}

void form_factor_kernel(benchmark::State& state, const std::string& call) {
  vplkit::parity::kernel_source source;
  source.name = call;
  source.includes = {"lib/form_factor.glsl"};
  source.body = "float sum = 0.0;\n"
                "for (int e = 0; e < " + std::to_string(evaluations) + "; ++e) {\n"
                "  vec3 x = vec3(0.01 * float(e), -0.007 * float(e), 0.003 * float(e));\n"
                "  vec3 n = fin0.xyz, c0 = fin1.xyz, c1 = fin2.xyz, c2 = fin3.xyz, c3 = fin4.xyz;\n"
                "  sum += " + call + ";\n"
                "}\n"
                "fout0 = vec4(sum);";
  source.float_outputs = 1;
  run_kernel(state, source, quad_inputs());
}

void glsl_polygon_form_factor(benchmark::State& state) { form_factor_kernel(state, "polygon_form_factor(x, n, c0, c1, c2, c3)"); }
void glsl_polygon_form_factor_exact(benchmark::State& state) { form_factor_kernel(state, "polygon_form_factor_exact(x, n, c0, c1, c2, c3)"); }
void glsl_point_form_factor(benchmark::State& state) {
  form_factor_kernel(state, "point_form_factor(x, n, 0.25 * (c0 + c1 + c2 + c3), normalize(cross(c2 - c0, c3 - c1))) * 0.5 * length(cross(c2 - c0, c3 - c1))");
}
BENCHMARK(glsl_polygon_form_factor)->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK(glsl_polygon_form_factor_exact)->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK(glsl_point_form_factor)->UseRealTime()->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
