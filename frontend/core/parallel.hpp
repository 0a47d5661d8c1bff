// The frontend's one threading helper (CPU mirrors and references): parallel_for runs body(i)
// for i in [0, count), items interleaved over `threads` (the calling thread takes part; i, i +
// threads, ... on one thread, so that neighbouring rows land on different threads and the
// work stays balanced). parallel_tiles is the 2D form, in 8 x 8 tiles: neighbouring receivers
// sample overlapping RSM regions, so a tile reuses the cache. An exception thrown by body (a ray
// refused before it reaches Embree, a bad_alloc) stops the other threads at their next item and
// is rethrown on the calling thread: one escaping a std::thread would call std::terminate.
#pragma once

#include <algorithm>
#include <atomic>
#include <cstdlib>
#include <exception>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "frontend/core/error.hpp"

namespace vplkit {

/// Number of threads to use for "all cores": the cores, or $VPLKIT_THREADS where it is set (the
/// test suite sets it so that tests running side by side share the cores instead of each taking
/// all of them). Throws vplkit::error when the variable is not a whole number in [1, 1024].
inline int hardware_threads() {
  if (const char* from_environment = std::getenv("VPLKIT_THREADS"); from_environment && *from_environment) {
    const std::string text(from_environment);
    if (text.size() > 4 || text.find_first_not_of("0123456789") != std::string::npos || std::stoi(text) < 1 || std::stoi(text) > 1024)
      throw error("VPLKIT_THREADS must be a whole number in [1, 1024]; got '" + excerpt(text) + "'");
    return std::stoi(text);
  }
  return static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
}

template <typename Body>
void parallel_for(int count, int threads, const Body& body) {
  threads = std::clamp(threads, 1, std::max(count, 1));
  std::atomic<bool> failed{false};
  std::exception_ptr first_failure;
  std::mutex failure_mutex;
  const auto work = [&](int first) {
    try {
      for (int i = first; i < count && !failed.load(std::memory_order_relaxed); i += threads) body(i);
    } catch (...) {
      const std::lock_guard<std::mutex> lock(failure_mutex);
      if (!first_failure) first_failure = std::current_exception();
      failed = true;
    }
  };
  std::vector<std::thread> workers;
  for (int t = 1; t < threads; ++t) workers.emplace_back(work, t);
  work(0);
  for (std::thread& worker : workers) worker.join();
  if (first_failure) std::rethrow_exception(first_failure);
}

/// texel(x, y) for every texel of a width x height grid, tile by tile.
template <typename Texel>
void parallel_tiles(int width, int height, int threads, const Texel& texel) {
  constexpr int tile = 8;
  const int tiles_x = (width + tile - 1) / tile, tiles_y = (height + tile - 1) / tile;
  parallel_for(tiles_x * tiles_y, threads, [&](int t) {
    const int x0 = (t % tiles_x) * tile, y0 = (t / tiles_x) * tile;
    for (int y = y0; y < std::min(y0 + tile, height); ++y)
      for (int x = x0; x < std::min(x0 + tile, width); ++x) texel(x, y);
  });
}

}  // namespace vplkit
