// Properties of the sampling patterns (include/vplkit/rsm_pattern.hpp) and of the polynomial
// trigonometry they use (include/vplkit/polynomial_math.hpp).
#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <set>
#include <utility>
#include <vector>

#include <vplkit/polynomial_math.hpp>
#include <vplkit/rsm_pattern.hpp>

#include "tests/closed_forms.hpp"

using namespace vplkit;

namespace {
using closed_forms::pi;

// Mean and RMS error, over `pixels` receivers, of the radial pattern's estimate of the
// integral of f over its annulus.
template <typename F>
std::pair<double, double> radial_estimate_error(const radial_pattern_settings<double>& settings, int pixels, F f, double exact) {
  const radial_pattern_constants<double> constants = make_radial_pattern_constants(settings);
  double sum = 0.0, sum_squares = 0.0;
  for (int p = 0; p < pixels; ++p) {
    const glm::uvec2 pixel(static_cast<unsigned>(p % 64), static_cast<unsigned>(p / 64));
    double estimate = 0.0;
    for (int path = 0; path < settings.paths; ++path)
      for (int sample = 0; sample < settings.samples_per_path; ++sample) {
        const pattern_sample<double> s = radial_pattern_sample(path, sample, pixel, constants);
        estimate += s.weight * f(s.offset);
      }
    const double error = estimate / exact - 1.0;
    sum += error;
    sum_squares += error * error;
  }
  return {sum / pixels, std::sqrt(sum_squares / pixels)};
}
}  // namespace

TEST_CASE("direction_from_angle matches cos and sin to 2e-6 in float for |angle| <= 20") {
  // The patterns use angles in [-pi / P, 2 pi (1 + 1 / P)). In float the argument reduction
  // (angle / 2 pi rounded to float) dominates the error: about ulp(angle / 2 pi) * 2 pi, so
  // 2e-6 up to 20 radians (and ~1e-4 at 1000).
  double worst = 0.0;
  for (int i = -40000; i <= 40000; ++i) {
    const float angle = static_cast<float>(i) * 0.0005f;
    const glm::vec2 direction = direction_from_angle(angle);
    worst = std::max({worst, std::fabs(direction.x - std::cos(static_cast<double>(angle))),
                      std::fabs(direction.y - std::sin(static_cast<double>(angle)))});
  }
  CAPTURE(worst);
  CHECK(worst < 2e-6);
  // In double the polynomials themselves are the limit: the degree-13/14 Taylor remainders at
  // pi/2, doubled by the double-angle step, 2e-9 on [-pi, pi].
  double worst_double = 0.0;
  for (int i = -1000; i <= 1000; ++i) {
    const double angle = pi * i / 1000.0;
    const glm::dvec2 direction = direction_from_angle(angle);
    worst_double = std::max({worst_double, std::fabs(direction.x - std::cos(angle)), std::fabs(direction.y - std::sin(angle))});
  }
  CAPTURE(worst_double);
  CHECK(worst_double < 2e-9);
}

TEST_CASE("radial pattern: P paths x S samples, near to far, radii in [r_min, r_max] (scaled), one seed one pattern") {
  radial_pattern_settings<float> settings;
  settings.scale_jitter = 0.0f;
  const radial_pattern_constants<float> constants = make_radial_pattern_constants(settings);
  for (unsigned pixel = 0; pixel < 64; ++pixel) {
    for (int path = 0; path < settings.paths; ++path) {
      float previous = 0.0f;
      for (int sample = 0; sample < settings.samples_per_path; ++sample) {
        const pattern_sample<float> s = radial_pattern_sample(path, sample, glm::uvec2(pixel, 3u), constants);
        const float radius = glm::length(s.offset);
        REQUIRE(radius >= settings.min_radius * 0.9999f);
        REQUIRE(radius <= settings.max_radius * 1.0001f);
        REQUIRE(radius > previous);  // near to far along each path
        REQUIRE(s.weight > 0.0f);
        previous = radius;
      }
    }
  }
  // Different pixels get different rotations; the same pixel always the same pattern.
  const auto first = radial_pattern_sample(0, 0, glm::uvec2(1, 2), constants);
  CHECK(radial_pattern_sample(0, 0, glm::uvec2(1, 2), constants).offset == first.offset);
  CHECK(radial_pattern_sample(0, 0, glm::uvec2(2, 2), constants).offset != first.offset);
  settings.seed = 7;
  CHECK(radial_pattern_sample(0, 0, glm::uvec2(1, 2), make_radial_pattern_constants(settings)).offset != first.offset);
}

TEST_CASE("radial pattern: the weight grows with the square of the distance") {
  // weight = (2 pi / P) r (q - 1) r_ring for r in [r_ring, q r_ring], so weight / r^2 lies in
  // [(2 pi / P)(q - 1) / q, (2 pi / P)(q - 1)] for every ring: the same up to the factor q.
  radial_pattern_settings<double> settings;
  settings.scale_jitter = 0.0;
  settings.angle_jitter = 0.0;
  const auto constants = make_radial_pattern_constants(settings);
  double min_ratio = 1e30, max_ratio = 0.0;
  for (int sample = 0; sample < settings.samples_per_path; ++sample) {
    const auto s = radial_pattern_sample(3, sample, glm::uvec2(5, 5), constants);
    const double ratio = s.weight / glm::dot(s.offset, s.offset);
    min_ratio = std::min(min_ratio, ratio);
    max_ratio = std::max(max_ratio, ratio);
  }
  // Within a ring r varies by the ring ratio q = 64^(1/10) = 1.52, so weight / r^2 by at most q.
  CHECK(max_ratio / min_ratio <= constants.ring_ratio * 1.0001);
}

TEST_CASE("radial pattern integrates a constant over its annulus without bias") {
  radial_pattern_settings<double> settings;
  settings.scale_jitter = 0.0;  // the scale jitter changes the annulus itself
  const double area = pi * (settings.max_radius * settings.max_radius - settings.min_radius * settings.min_radius);
  // Named variables, not a structured binding: CAPTURE's lambda cannot capture one before C++20 (clang 14).
  const std::pair<double, double> error = radial_estimate_error(settings, 4096, [](const glm::dvec2&) { return 1.0; }, area);
  const double mean = error.first, rms = error.second;
  CAPTURE(mean);
  CAPTURE(rms);
  CHECK(std::fabs(mean) < 2e-3);  // 4096 receivers: the mean of unbiased estimates
  CHECK(rms < 0.05);              // stratified in rings and paths: each estimate is already close
}

TEST_CASE("radial pattern integrates a smooth function, and its error falls as the sample count grows") {
  // f = exp(-|o|^2 / (2 sigma^2)); over the annulus its integral is
  // 2 pi sigma^2 (exp(-r_min^2 / 2 sigma^2) - exp(-r_max^2 / 2 sigma^2)).
  const double sigma = 20.0;
  const auto f = [&](const glm::dvec2& o) { return std::exp(-glm::dot(o, o) / (2 * sigma * sigma)); };
  double previous_rms = 1e30;
  for (int samples : {5, 10, 20, 40}) {
    radial_pattern_settings<double> settings;
    settings.scale_jitter = 0.0;
    settings.samples_per_path = samples;
    const double exact = 2 * pi * sigma * sigma *
                         (std::exp(-settings.min_radius * settings.min_radius / (2 * sigma * sigma)) -
                          std::exp(-settings.max_radius * settings.max_radius / (2 * sigma * sigma)));
    const std::pair<double, double> error = radial_estimate_error(settings, 2048, f, exact);
    const double mean = error.first, rms = error.second;
    CAPTURE(samples);
    CAPTURE(mean);
    CAPTURE(rms);
    CHECK(std::fabs(mean) < 3e-3);
    CHECK(rms < previous_rms);
    previous_rms = rms;
  }
  CHECK(previous_rms < 0.01);  // 15 x 40 samples: under 1% per receiver
}

TEST_CASE("disk pattern: unshifted (the original's, the same for every receiver), inside r_max, weights sum to the disk's area in expectation") {
  for (const bool printed : {false, true}) {
    CAPTURE(printed);
    disk_pattern_settings<double> settings;
    settings.samples = 400;
    settings.printed_weights = printed;
    double weight_sum = 0.0;
    for (int sample = 0; sample < settings.samples; ++sample) {
      const auto s = rsm_disk_sample(sample, glm::dvec2(0.0), settings);
      REQUIRE(glm::length(s.offset) <= settings.max_radius);
      // Unbiased: xi1 * 2 pi r_max^2 / N; printed: xi1^2 * 3 pi r_max^2 / N; xi1 = |offset| / r_max.
      const double xi1 = glm::length(s.offset) / settings.max_radius, area = pi * settings.max_radius * settings.max_radius;
      const double expected = printed ? xi1 * xi1 * 3 * area / settings.samples : xi1 * 2 * area / settings.samples;
      REQUIRE(s.weight == doctest::Approx(expected).epsilon(1e-7));
      weight_sum += s.weight;
    }
    CHECK(weight_sum == doctest::Approx(pi * settings.max_radius * settings.max_radius).epsilon(0.1));  // 400 samples: sd ~ 3-4.5 %
  }
}

TEST_CASE("disk pattern: the default weights integrate 1/r without bias, the printed ones miss a quarter of it") {
  // f = 1/r over the disk integrates to 2 pi r_max. With the density 1 / (2 pi r_max r) of uniform
  // xi1, the default weights (~ r) cancel it exactly: the estimate is 2 pi r_max for every sample.
  // The printed weights (~ r^2) give E[3 xi1^2 / xi1] / 2 = 3/4 of it.
  const auto inverse_r = [](const glm::dvec2& o) { return 1.0 / std::max(glm::length(o), 1e-9); };
  for (const bool printed : {false, true}) {
    CAPTURE(printed);
    disk_pattern_settings<double> settings;
    settings.samples = 20000;
    settings.printed_weights = printed;
    double estimate = 0.0;
    for (int sample = 0; sample < settings.samples; ++sample) {
      const auto s = rsm_disk_sample(sample, glm::dvec2(0.0), settings);
      estimate += s.weight * inverse_r(s.offset);
    }
    const double exact = 2 * pi * settings.max_radius;
    CAPTURE(estimate / exact);
    if (printed) CHECK(std::fabs(estimate / exact - 0.75) < 0.02);
    else CHECK(estimate / exact == doctest::Approx(1.0).epsilon(1e-9));
  }
  // And a smooth function that is not a power of r: f = exp(-r / 20), integral 2 pi 20^2 (1 - (1 + 64/20) e^(-64/20)).
  disk_pattern_settings<double> settings;
  settings.samples = 40000;
  double estimate = 0.0;
  for (int sample = 0; sample < settings.samples; ++sample) {
    const auto s = rsm_disk_sample(sample, glm::dvec2(0.0), settings);
    estimate += s.weight * std::exp(-glm::length(s.offset) / 20.0);
  }
  const double exact = 2 * pi * 400.0 * (1.0 - (1.0 + 64.0 / 20.0) * std::exp(-64.0 / 20.0));
  CAPTURE(estimate / exact);
  CHECK(estimate / exact == doctest::Approx(1.0).epsilon(0.02));
}

TEST_CASE("disk pattern: the pixel shift, in [0, 1)^2, differs between pixels and seeds, 0 without per_pixel_shift") {
  disk_pattern_settings<double> settings, other_seed, fixed;
  other_seed.seed = 7;
  fixed.per_pixel_shift = false;
  std::set<std::pair<double, double>> shifts;
  for (unsigned y = 0; y < 32; ++y)
    for (unsigned x = 0; x < 32; ++x) {
      const glm::dvec2 shift = rsm_disk_pixel_shift(glm::uvec2(x, y), settings);
      REQUIRE(shift.x >= 0.0);
      REQUIRE(shift.x < 1.0);
      REQUIRE(shift.y >= 0.0);
      REQUIRE(shift.y < 1.0);
      REQUIRE(shift != rsm_disk_pixel_shift(glm::uvec2(x, y), other_seed));
      REQUIRE(rsm_disk_pixel_shift(glm::uvec2(x, y), fixed) == glm::dvec2(0.0));
      shifts.insert({shift.x, shift.y});
    }
  CHECK(shifts.size() == 32 * 32);
  // Unshifted, a sample is the original's to the bit: fract(xi + 0) = xi for xi in [0, 1), then the
  // original's offset r_max xi1 (sin 2 pi xi2, cos 2 pi xi2) and weight.
  disk_pattern_settings<float> original;
  original.per_pixel_shift = false;
  for (int sample = 0; sample < 400; ++sample) {
    const std::uint32_t sample_hash = hash_combine(original.seed ^ 0x5bd1e995u, static_cast<std::uint32_t>(sample));
    const float xi1 = uniform_float_from_bits(sample_hash);
    const float xi2 = uniform_float_from_bits(hash_uint32(sample_hash));
    const glm::vec2 direction = direction_from_turns(xi2);
    const pattern_sample<float> s = rsm_disk_sample(sample, rsm_disk_pixel_shift(glm::uvec2(3, 5), original), original);
    REQUIRE(s.offset == glm::vec2(direction.y, direction.x) * (original.max_radius * xi1));
    REQUIRE(s.weight == xi1 * (2.0f * 3.14159265358979323846f * original.max_radius * original.max_radius / float(original.samples)));
  }
}

TEST_CASE("disk pattern: across pixels a sample's radius and angle are uniform, and shifting per pixel makes the image's mean converge") {
  // Each pixel's sample k is the original's sample k moved by the pixel's shift mod 1: over many
  // pixels its xi1 (radius / r_max) and xi2 (angle / 2 pi) must each be uniform on [0, 1), which
  // is what keeps every receiver's estimate unbiased with the same weights. A shift left out, or
  // applied to one of the two only, puts every pixel in one bin.
  disk_pattern_settings<double> settings;
  settings.samples = 64;
  for (const int sample : {0, 17, 63}) {
    CAPTURE(sample);
    std::array<int, 10> radius_bins{}, angle_bins{};
    for (unsigned y = 0; y < 64; ++y)
      for (unsigned x = 0; x < 64; ++x) {
        const auto s = rsm_disk_sample(sample, rsm_disk_pixel_shift(glm::uvec2(x, y), settings), settings);
        const double xi1 = glm::length(s.offset) / settings.max_radius;
        const double xi2 = std::fmod(std::atan2(s.offset.x, s.offset.y) / (2 * pi) + 1.0, 1.0);  // offset = r (sin, cos)
        REQUIRE(xi1 < 1.0);
        REQUIRE(s.weight == doctest::Approx(xi1 * 2 * pi * settings.max_radius * settings.max_radius / settings.samples).epsilon(1e-6));
        ++radius_bins[static_cast<std::size_t>(std::min(xi1 * 10.0, 9.0))];
        ++angle_bins[static_cast<std::size_t>(std::min(xi2 * 10.0, 9.0))];
      }
    for (std::size_t bin = 0; bin < 10; ++bin) {
      CAPTURE(bin);
      CHECK(std::abs(radius_bins[bin] - 410) < 80);  // 4096 pixels in 10 bins: 410 +- 20 (one sd); 80 is four
      CHECK(std::abs(angle_bins[bin] - 410) < 80);
    }
  }
  // A bright patch: the disc of radius 6 centred 40 texels from the receiver (area 36 pi). With
  // the same 64 samples everywhere, every pixel makes the same error, so the mean over 4096
  // pixels is one pattern's estimate; shifted per pixel, the mean converges to the area.
  const auto patch = [](const glm::dvec2& offset) { return glm::length(offset - glm::dvec2(40.0, 0.0)) < 6.0 ? 1.0 : 0.0; };
  const double exact = pi * 36.0;
  const auto image_mean = [&](const disk_pattern_settings<double>& s) {
    double sum = 0.0;
    for (unsigned y = 0; y < 64; ++y)
      for (unsigned x = 0; x < 64; ++x) {
        const glm::dvec2 shift = rsm_disk_pixel_shift(glm::uvec2(x, y), s);
        for (int sample = 0; sample < s.samples; ++sample) {
          const auto d = rsm_disk_sample(sample, shift, s);
          sum += d.weight * patch(d.offset);
        }
      }
    return sum / 4096.0;
  };
  disk_pattern_settings<double> fixed = settings;
  fixed.per_pixel_shift = false;
  const double shifted_mean = image_mean(settings), fixed_mean = image_mean(fixed);
  CAPTURE(shifted_mean / exact);
  CAPTURE(fixed_mean / exact);
  CHECK(std::fabs(shifted_mean / exact - 1.0) < 0.03);  // 4096 x 64 samples (measured: 2.0 % under)
  CHECK(std::fabs(fixed_mean / exact - 1.0) > 0.2);     // one pattern of 64 samples: hit or miss (measured: missed)
}
