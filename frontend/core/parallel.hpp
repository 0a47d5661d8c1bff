// The frontend's one threading helper (CPU mirrors and references): parallel_for runs body(i)
// for i in [0, count), items interleaved over `threads` (the calling thread takes part; i, i +
// threads, ... on one thread, so that neighbouring rows land on different threads and the
// work stays balanced). parallel_tiles is the 2D form, in 8 x 8 tiles: neighbouring receivers
// sample overlapping RSM regions, so a tile reuses the cache.
#pragma once

#include <algorithm>
#include <thread>
#include <vector>

namespace vplkit {

/// Number of threads to use for "all cores".
inline int hardware_threads() { return static_cast<int>(std::max(1u, std::thread::hardware_concurrency())); }

template <typename Body>
void parallel_for(int count, int threads, const Body& body) {
  threads = std::clamp(threads, 1, std::max(count, 1));
  const auto work = [&](int first) {
    for (int i = first; i < count; i += threads) body(i);
  };
  std::vector<std::thread> workers;
  for (int t = 1; t < threads; ++t) workers.emplace_back(work, t);
  work(0);
  for (std::thread& worker : workers) worker.join();
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
