// What a reference run costs, and the order and timing of its work: shared by the brute-force
// gather and the Monte Carlo reference, which both announce their cost before they start and
// report their progress while they run.
#pragma once

#include <algorithm>
#include <cstdint>
#include <numeric>
#include <string>

#include "frontend/core/parallel.hpp"
#include "frontend/core/progress.hpp"

namespace vplkit {

/// What a reference run costs before it starts: an upper bound of its rays and an estimate of
/// its wall time on this machine (a calibration run of a sample of its work, same threads).
struct reference_cost {
  double rays = 0.0;          ///< at most this many rays
  double seconds = 0.0;       ///< estimated wall time
  std::uint64_t units = 0;    ///< the work items progress counts (pixels, receivers)
  std::string unit;           ///< their name
  std::string what;           ///< how the rays are counted, for the announcement
};

namespace reference_work {

// Items in a scrambled order: k -> k * stride mod count, with a stride coprime with the count
// near 0.618 count. The finished part is then a sample of the whole image (not its empty top
// rows first), so the progress and its time left are fair from the start.
class scrambled_order {
 public:
  explicit scrambled_order(std::uint64_t count) : count_(std::max<std::uint64_t>(count, 1)) {
    stride_ = std::max<std::uint64_t>(1, static_cast<std::uint64_t>(0.6180339887 * static_cast<double>(count_)));
    while (std::gcd(stride_, count_) != 1) ++stride_;
  }
  std::uint64_t operator()(std::uint64_t k) const { return k * stride_ % count_; }  // k, stride < count <= 2^31: no overflow

 private:
  std::uint64_t count_, stride_ = 1;
};

// Runs `work(i)` for `count` items spread evenly over [0, total) on `threads` and returns the wall time.
template <typename Work>
double time_sample(std::uint64_t total, std::uint64_t count, int threads, const Work& work) {
  const double start = steady_seconds();
  parallel_for(static_cast<int>(count), threads, [&](int k) {
    work(static_cast<std::uint64_t>((static_cast<double>(k) + 0.5) / static_cast<double>(count) * static_cast<double>(total)));
  });
  return steady_seconds() - start;
}

}  // namespace reference_work
}  // namespace vplkit
