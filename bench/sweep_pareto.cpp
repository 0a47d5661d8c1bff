// The sweep's Pareto marking (frontend/cli/sweep_report.hpp, cli::mark_pareto) on random tables of
// 2,000 and 20,000 rows, exact and within the noise: sorted sweeps, O(n log n); comparing every
// row with every other took 5.5 min per rewrite of a 20,000-row sweep. Its results are tested in
// tests/frontend/cli/test_sweep_report.cpp against a brute force; its time is measured here.
//   build/bench/vplkit_sweep_bench --benchmark_filter=mark_pareto
#include <benchmark/benchmark.h>

#include <random>
#include <string>

#include "frontend/cli/sweep_report.hpp"
#include "frontend/core/setting.hpp"

namespace {

vplkit::cli::sweep_table random_table(std::size_t rows, bool with_noise) {
  std::mt19937 random(2041);
  std::uniform_int_distribution<int> value(0, 4999), scene(0, 3);
  vplkit::cli::sweep_table table;
  table.columns = {"scene", "technique", "frame_ms", "rel_rmse", "key"};
  for (std::size_t i = 0; i < rows; ++i) {
    std::map<std::string, std::string> row{{"scene", "scene " + std::to_string(scene(random))},
                                           {"technique", "rsm-alg6"},
                                           {"frame_ms", vplkit::format_real(0.5 * value(random))},
                                           {"rel_rmse", vplkit::format_real(0.01 * value(random))},
                                           {"key", std::to_string(i)}};
    if (with_noise) row["frame_ms_noise"] = "0.1", row["rel_rmse_ref_se"] = "0.01";
    table.rows.push_back(std::move(row));
  }
  return table;
}

void mark_pareto(benchmark::State& state) {
  const vplkit::cli::sweep_table input = random_table(static_cast<std::size_t>(state.range(0)), state.range(1) != 0);
  for (auto _ : state) {
    state.PauseTiming();
    vplkit::cli::sweep_table table = input;
    state.ResumeTiming();
    vplkit::cli::mark_pareto(table, "frame_ms", "rel_rmse");
    benchmark::DoNotOptimize(table.rows.data());
  }
  state.SetItemsProcessed(state.iterations() * state.range(0));
}
BENCHMARK(mark_pareto)->ArgNames({"rows", "noise"})->ArgsProduct({{2000, 20000}, {0, 1}})->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
