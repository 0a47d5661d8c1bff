// Splitting a CPU mirror's rows over threads: row(y) for every y in [0, height), rows
// interleaved over `threads` (the calling thread takes part).
#pragma once

#include <algorithm>
#include <thread>
#include <vector>

namespace vplkit {

/// Number of threads to use for "all cores".
inline int hardware_threads() { return static_cast<int>(std::max(1u, std::thread::hardware_concurrency())); }

template <typename Row>
void parallel_rows(int height, int threads, const Row& row) {
  threads = std::clamp(threads, 1, std::max(height, 1));
  std::vector<std::thread> workers;
  for (int t = 1; t < threads; ++t)
    workers.emplace_back([&, t] {
      for (int y = t; y < height; y += threads) row(y);
    });
  for (int y = 0; y < height; y += threads) row(y);
  for (std::thread& worker : workers) worker.join();
}

}  // namespace vplkit
