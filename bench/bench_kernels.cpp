// Kernel micro-benchmarks (Google Benchmark): Eq. 3.2 throughput in float and double, the cost
// of Alg. 3 against Alg. 6 over slots x samples per path, the whole gather with and without
// visibility, and the form factors (the polygon's fast and exact forms against the point's).
// A sweep is a filter (a regular expression over the names), e.g.
//   build/bench/vplkit_bench --benchmark_filter=alg
//   build/bench/vplkit_bench --benchmark_filter='form_factor_throughput|final_gather_cost' --benchmark_repetitions=3
// (docs/performance.md; the GLSL twins: build/bench/vplkit_glsl_bench).
#include <benchmark/benchmark.h>

#include <random>
#include <vector>

#include <vplkit/final_gather.hpp>
#include <vplkit/form_factor.hpp>
#include <vplkit/form_factor_grid.hpp>
#include <vplkit/hash.hpp>
#include <vplkit/irradiance.hpp>
#include <vplkit/micro_linear_buffer.hpp>
#include <vplkit/rsm_gather.hpp>
#include <vplkit/rsm_gather_batch.hpp>

namespace {

template <typename T>
void pixel_light_irradiance_throughput(benchmark::State& state) {
  using vec3 = glm::vec<3, T>;
  constexpr std::size_t count = 4096;  // fits in L1/L2: measures arithmetic, not memory
  std::mt19937 random(1);
  std::uniform_real_distribution<T> uniform(-1, 1);
  std::vector<vec3> points(count), normals(count);
  for (std::size_t i = 0; i < count; ++i) {
    points[i] = vec3(uniform(random), uniform(random), uniform(random));
    normals[i] = glm::normalize(vec3(uniform(random), uniform(random), uniform(random)) + vec3(0, 0, T(0.01)));
  }
  const vec3 x(0, 0, 2), n(0, 0, -1), flux(1);
  for (auto _ : state) {
    vec3 sum(0);
    for (std::size_t i = 0; i < count; ++i) sum += vplkit::pixel_light_irradiance(x, n, points[i], normals[i], flux);
    benchmark::DoNotOptimize(sum);
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()) * static_cast<std::int64_t>(count));
}
BENCHMARK_TEMPLATE(pixel_light_irradiance_throughput, float);
BENCHMARK_TEMPLATE(pixel_light_irradiance_throughput, double);

// Slot indices of 1024 paths; a path's visibility is evaluated sample by sample as in Alg. 5.
std::vector<int> random_paths(int slots, int samples_per_path) {
  std::vector<int> indices(static_cast<std::size_t>(1024 * samples_per_path));
  for (std::size_t i = 0; i < indices.size(); ++i)
    indices[i] = static_cast<int>(vplkit::hash_uint32(static_cast<std::uint32_t>(i)) % static_cast<std::uint32_t>(slots));
  return indices;
}

template <bool BranchFree>
void visibility_cost(benchmark::State& state) {
  const int slots = static_cast<int>(state.range(0));
  const int samples = static_cast<int>(state.range(1));
  const std::vector<int> indices = random_paths(slots, samples);
  for (auto _ : state) {
    float visible = 0.0f;
    for (std::size_t path = 0; path < 1024; ++path) {
      vplkit::micro_linear_buffer<float> buffer;
      vplkit::micro_linear_buffer_reset(buffer, slots);
      for (int sample = 0; sample < samples; ++sample) {
        const int index = indices[path * static_cast<std::size_t>(samples) + static_cast<std::size_t>(sample)];
        if constexpr (BranchFree) visible += glm::clamp(vplkit::micro_linear_buffer_alg6(buffer, index), 0.0f, 1.0f);
        else visible += vplkit::micro_linear_buffer_alg3(buffer, index);
      }
    }
    benchmark::DoNotOptimize(visible);
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()) * 1024 * samples);
}
void alg3(benchmark::State& state) { visibility_cost<false>(state); }
void alg6(benchmark::State& state) { visibility_cost<true>(state); }
BENCHMARK(alg3)->ArgNames({"slots", "samples"})->ArgsProduct({{2, 5, 8, 16}, {5, 10, 20, 40}});
BENCHMARK(alg6)->ArgNames({"slots", "samples"})->ArgsProduct({{2, 5, 8, 16}, {5, 10, 20, 40}});

// The whole per-receiver gather (Alg. 1/5) on a synthetic 512^2 RSM (a floor with a block, as
// seen by an orthographic light from above), one thread: the CPU cost of visibility at the same
// 150 samples, without the GL pipeline around it. The gather works in the light's eye space.
const glm::mat4 bench_light_view(1, 0, 0, 0, 0, 0, -1, 0, 0, 1, 0, 0, 0, 0, -10, 1);
struct synthetic_rsm {
  std::vector<vplkit::rsm_texel<float>> texels;
  synthetic_rsm() : texels(512 * 512) {
    for (int y = 0; y < 512; ++y)
      for (int x = 0; x < 512; ++x) {
        const float wx = (static_cast<float>(x) - 256.0f) * 0.01f, wz = (static_cast<float>(y) - 256.0f) * 0.01f;
        const float height = (wx > 0.3f && wx < 0.8f) ? 0.6f : 0.0f;
        texels[static_cast<std::size_t>(y * 512 + x)] = {vplkit::transform_point(bench_light_view, glm::vec3(wx, height, -wz)),
                                                         vplkit::transform_direction(bench_light_view, glm::vec3(0, 1, 0)), glm::vec3(1.0f)};
      }
  }
};

template <vplkit::rsm_visibility Visibility>
void gather_cost(benchmark::State& state) {
  static const synthetic_rsm rsm;
  vplkit::rsm_gather_settings<float> settings;
  const auto fetch = [&](glm::ivec2 t) { return rsm.texels[static_cast<std::size_t>(t.y * 512 + t.x)]; };
  std::uint32_t receiver = 0;
  for (auto _ : state) {
    const float x = static_cast<float>(receiver % 64) * 0.01f, z = static_cast<float>(receiver / 64 % 64) * 0.01f;
    const vplkit::gather_receiver<float> r{vplkit::transform_point(bench_light_view, glm::vec3(x, 0.05f, -z)),
                                           vplkit::transform_direction(bench_light_view, glm::vec3(1, 0, 0)),
                                           glm::vec2(256.0f + 100.0f * x, 256.0f + 100.0f * z), glm::uvec2(receiver % 64, receiver / 64)};
    benchmark::DoNotOptimize(vplkit::gather_rsm<vplkit::rsm_pattern::radial, Visibility>(r, fetch, settings));
    ++receiver;
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()) * 150);
}
BENCHMARK_TEMPLATE(gather_cost, vplkit::rsm_visibility::none);
BENCHMARK_TEMPLATE(gather_cost, vplkit::rsm_visibility::alg3);
BENCHMARK_TEMPLATE(gather_cost, vplkit::rsm_visibility::alg6);

// The batch gather (rsm_gather_batch.hpp) on the same RSM and receivers as gather_cost: a block
// of 4096 receivers per iteration, each thread its own block (the caller's split over cores), so
// with ->Threads(2) and real time items_per_second is the rate of both cores together. avx2:0 is
// the portable instantiation, avx2:1 the AVX2 one (batch_isa.hpp; skipped on a CPU without it).
template <vplkit::rsm_visibility Visibility>
void gather_batch_cost(benchmark::State& state) {
  static const synthetic_rsm rsm;
  static const vplkit::rsm_plane_storage<float> planes =
      vplkit::make_rsm_planes<float>(glm::ivec2(512), [](glm::ivec2 t) { return rsm.texels[static_cast<std::size_t>(t.y * 512 + t.x)]; });
  const vplkit::rsm_gather_settings<float> settings;
  constexpr std::uint32_t count = 4096;
  std::vector<vplkit::gather_receiver<float>> receivers(count);
  for (std::uint32_t receiver = 0; receiver < count; ++receiver) {
    const float x = static_cast<float>(receiver % 64) * 0.01f, z = static_cast<float>(receiver / 64 % 64) * 0.01f;
    receivers[receiver] = {vplkit::transform_point(bench_light_view, glm::vec3(x, 0.05f, -z)), vplkit::transform_direction(bench_light_view, glm::vec3(1, 0, 0)),
                           glm::vec2(256.0f + 100.0f * x, 256.0f + 100.0f * z), glm::uvec2(receiver % 64, receiver / 64)};
  }
  std::vector<glm::vec3> irradiance(count);
  const vplkit::batch_isa isa = state.range(0) != 0 ? vplkit::batch_isa::avx2 : vplkit::batch_isa::portable;
  if (!vplkit::batch_isa_supported(isa)) {
    state.SkipWithError("this CPU or build has no AVX2");
    return;
  }
  for (auto _ : state) {
    vplkit::gather_rsm_batch<Visibility>(receivers.data(), receivers.size(), planes.view(), settings, irradiance.data(), isa);
    benchmark::DoNotOptimize(irradiance.data());
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()) * count * 150);
}
BENCHMARK_TEMPLATE(gather_batch_cost, vplkit::rsm_visibility::none)->ArgName("avx2")->Arg(0)->Arg(1)->Threads(1)->Threads(2)->UseRealTime();
BENCHMARK_TEMPLATE(gather_batch_cost, vplkit::rsm_visibility::alg6)->ArgName("avx2")->Arg(0)->Arg(1)->Threads(1)->Threads(2)->UseRealTime();

// Form factors ([FG]): the clipped polygon-to-point against the point-to-point kernel, one
// quad each, and the whole gather over a 6 x 4 x 4 distance cube map.
struct form_factor_inputs {
  std::vector<glm::vec3> normals = std::vector<glm::vec3>(1024), offsets = std::vector<glm::vec3>(1024);
  form_factor_inputs() {
    std::mt19937 random(2);
    std::uniform_real_distribution<float> uniform(-1, 1);
    for (std::size_t i = 0; i < 1024; ++i) {
      normals[i] = glm::normalize(glm::vec3(uniform(random), uniform(random), uniform(random)));
      offsets[i] = glm::vec3(uniform(random), uniform(random), uniform(random)) * 0.2f;
    }
  }
};

void polygon_form_factor_throughput(benchmark::State& state) {
  const form_factor_inputs in;
  for (auto _ : state) {
    float sum = 0.0f;
    for (std::size_t i = 0; i < 1024; ++i) {
      const glm::vec3 c = glm::vec3(0, 0, 1) + in.offsets[i];
      sum += vplkit::polygon_form_factor(glm::vec3(0.0f), in.normals[i], c, c + glm::vec3(0.3f, 0, 0), c + glm::vec3(0.3f, 0.3f, 0), c + glm::vec3(0, 0.3f, 0));
    }
    benchmark::DoNotOptimize(sum);
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()) * 1024);
}
BENCHMARK(polygon_form_factor_throughput);

void polygon_form_factor_exact_throughput(benchmark::State& state) {
  const form_factor_inputs in;
  for (auto _ : state) {
    float sum = 0.0f;
    for (std::size_t i = 0; i < 1024; ++i) {
      const glm::vec3 c = glm::vec3(0, 0, 1) + in.offsets[i];
      sum += vplkit::polygon_form_factor_exact(glm::vec3(0.0f), in.normals[i], c, c + glm::vec3(0.3f, 0, 0), c + glm::vec3(0.3f, 0.3f, 0),
                                               c + glm::vec3(0, 0.3f, 0));
    }
    benchmark::DoNotOptimize(sum);
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()) * 1024);
}
BENCHMARK(polygon_form_factor_exact_throughput);

void point_form_factor_throughput(benchmark::State& state) {
  const form_factor_inputs in;
  for (auto _ : state) {
    float sum = 0.0f;
    for (std::size_t i = 0; i < 1024; ++i)
      sum += vplkit::point_form_factor(glm::vec3(0.0f), in.normals[i], glm::vec3(0.15f, 0.15f, 1) + in.offsets[i], glm::vec3(0, 0, -1)) * 0.09f;
    benchmark::DoNotOptimize(sum);
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()) * 1024);
}
BENCHMARK(point_form_factor_throughput);

// The polygon form factor to every cell of a 32 x 32 grid (a cube-map face 1 unit away, cells
// 1/32 wide) from one receiver per iteration, its normal one of form_factor_inputs': per cell,
// comparable with the two above (form_factor_grid.hpp shares corners and edges between cells).
// avx2:0 is the portable instantiation, avx2:1 the AVX2 one (batch_isa.hpp).
void polygon_form_factor_grid_throughput(benchmark::State& state) {
  const form_factor_inputs in;
  vplkit::form_factor_grid_scratch<float> scratch;
  std::vector<float> out(32 * 32);
  std::size_t k = 0;
  const vplkit::batch_isa isa = state.range(0) != 0 ? vplkit::batch_isa::avx2 : vplkit::batch_isa::portable;
  if (!vplkit::batch_isa_supported(isa)) {
    state.SkipWithError("this CPU or build has no AVX2");
    return;
  }
  for (auto _ : state) {
    vplkit::polygon_form_factor_grid(glm::vec3(0.0f), in.normals[k++ & 1023u], glm::vec3(-0.5f, -0.5f, 1.0f), glm::vec3(1.0f / 32.0f, 0, 0),
                                     glm::vec3(0, 1.0f / 32.0f, 0), 32, 32, out.data(), scratch, isa);
    benchmark::DoNotOptimize(out.data());
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()) * 1024);
}
BENCHMARK(polygon_form_factor_grid_throughput)->ArgName("avx2")->Arg(0)->Arg(1);

template <vplkit::gather_form_factor Kind>
void final_gather_cost(benchmark::State& state) {
  const auto constant = [](int face, int, int) { return glm::vec4(0.5f + 0.1f * static_cast<float>(face), 0.5f, 0.5f, 1.0f); };
  std::uint32_t k = 0;
  for (auto _ : state) {
    const glm::vec3 x(0.1f * static_cast<float>(k % 5), 0.05f * static_cast<float>(k % 7), 0.0f);
    benchmark::DoNotOptimize(vplkit::final_gather_irradiance<Kind>(x, glm::vec3(0, 1, 0), glm::vec3(0.0f), 4, constant));
    ++k;
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()));
}
BENCHMARK_TEMPLATE(final_gather_cost, vplkit::gather_form_factor::polygon);
BENCHMARK_TEMPLATE(final_gather_cost, vplkit::gather_form_factor::point);

}  // namespace

BENCHMARK_MAIN();
