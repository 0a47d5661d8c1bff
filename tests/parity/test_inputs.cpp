// The seeded input generators of vplkit::parity (include/vplkit/parity/inputs.hpp): ranges,
// distributions, reproducibility, edge cases first. CPU only (the kernel test binary).
#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <set>
#include <stdexcept>

#include <vplkit/parity/inputs.hpp>

// The names this file tests, one by one: a using-directive would reach into the files compiled
// after this one in its unity batch (tests/CMakeLists.txt).
using vplkit::parity::float_generator;
using vplkit::parity::geometry_inputs;
using vplkit::parity::grid_of;
using vplkit::parity::kernel_inputs;
using vplkit::parity::log_uniform_values;
using vplkit::parity::points;
using vplkit::parity::random_inputs;
using vplkit::parity::seeded_grid;
using vplkit::parity::special_values;
using vplkit::parity::uniform_values;
using vplkit::parity::unit_vectors;

TEST_CASE("the same seed gives the same numbers; another seed other numbers") {
  random_inputs a(42), b(42), c(43);
  bool all_same = true, any_differs = false;
  for (int i = 0; i < 1000; ++i) {
    const float x = a.uniform(-1.0f, 1.0f), y = b.uniform(-1.0f, 1.0f), z = c.uniform(-1.0f, 1.0f);
    all_same = all_same && x == y;
    any_differs = any_differs || x != z;
  }
  CHECK(all_same);
  CHECK(any_differs);
  // The engine is std::mt19937, whose 10000th output from the default seed the standard fixes:
  // bits() passes it through unchanged, so the sequences are the same on every platform.
  random_inputs standard(5489u);
  for (int i = 0; i < 9999; ++i) standard.bits();
  CHECK(standard.bits() == 4123659995u);
}

TEST_CASE("unit_interval, uniform and uniform_uint stay in range and cover it") {
  random_inputs random(1);
  float low = 1.0f, high = 0.0f;
  std::array<int, 10> bins{};
  for (int i = 0; i < 100000; ++i) {
    const float u = random.unit_interval();
    REQUIRE(u >= 0.0f);
    REQUIRE(u < 1.0f);
    REQUIRE(u * 16777216.0f == std::floor(u * 16777216.0f));  // k / 2^24 exactly
    low = std::min(low, u);
    high = std::max(high, u);
    ++bins[static_cast<std::size_t>(u * 10.0f)];
  }
  CHECK(low < 1e-3f);
  CHECK(high > 0.999f);
  for (int count : bins) CHECK(std::abs(count - 10000) < 500);  // 5 sigma is ~475
  for (int i = 0; i < 1000; ++i) {
    const float v = random.uniform(-3.0f, 5.0f);
    REQUIRE(v >= -3.0f);
    REQUIRE(v <= 5.0f);
  }
  CHECK(random.uniform(2.0f, 2.0f) == 2.0f);
  std::set<std::uint32_t> seen;
  for (int i = 0; i < 1000; ++i) {
    const std::uint32_t k = random.uniform_uint(3, 9);
    REQUIRE(k >= 3);
    REQUIRE(k <= 9);
    seen.insert(k);
  }
  CHECK(seen.size() == 7);
  CHECK(random.uniform_uint(0, 0xffffffffu) <= 0xffffffffu);
  CHECK_THROWS_AS(random.uniform(1.0f, 0.0f), std::invalid_argument);
  CHECK_THROWS_AS(random.uniform(0.0f, std::numeric_limits<float>::infinity()), std::invalid_argument);
  CHECK_THROWS_AS(random.uniform_uint(2, 1), std::invalid_argument);
}

TEST_CASE("log_uniform puts the same share of values in every decade") {
  random_inputs random(2);
  std::array<int, 6> decades{};
  const int draws = 60000;
  for (int i = 0; i < draws; ++i) {
    const float v = random.log_uniform(1e-3f, 1e3f);
    REQUIRE(v >= 1e-3f);
    REQUIRE(v <= 1e3f);
    ++decades[static_cast<std::size_t>(std::min(5.0, std::floor(std::log10(static_cast<double>(v)) + 3.0)))];
  }
  for (int count : decades) CHECK(std::abs(count - draws / 6) < 460);  // 5 sigma
  CHECK_THROWS_AS(random.log_uniform(0.0f, 1.0f), std::invalid_argument);
  CHECK_THROWS_AS(random.log_uniform(2.0f, 1.0f), std::invalid_argument);
}

TEST_CASE("unit_vector is unit length and uniform on the sphere") {
  random_inputs random(3);
  const int draws = 60000;
  glm::dvec3 sum(0.0);
  std::array<int, 4> x_bins{};
  for (int i = 0; i < draws; ++i) {
    const glm::vec3 v = random.unit_vector();
    REQUIRE(std::fabs(glm::length(v) - 1.0f) < 1e-6f);
    sum += glm::dvec3(v);
    // Uniform on the sphere: each coordinate is uniform in [-1, 1] (Archimedes).
    ++x_bins[static_cast<std::size_t>(std::min(3.0, std::floor((static_cast<double>(v.x) + 1.0) * 2.0)))];
  }
  CHECK(glm::length(sum / static_cast<double>(draws)) < 0.01);
  for (int count : x_bins) CHECK(std::abs(count - draws / 4) < 530);  // 5 sigma
}

TEST_CASE("special_values holds both signs of the values where arithmetic breaks") {
  const std::vector<float> values = special_values();
  for (float v : {0.0f, std::numeric_limits<float>::denorm_min(), std::numeric_limits<float>::min(), 1.0f,
                  std::numeric_limits<float>::max(), std::nextafter(1.0f, 2.0f)}) {
    CHECK(std::count(values.begin(), values.end(), v) >= 1);
    CHECK(std::count(values.begin(), values.end(), -v) >= 1);
  }
  CHECK(std::signbit(values[1]));  // -0 is there as itself
  for (float v : values) CHECK(std::isfinite(v));
}

TEST_CASE("seeded_grid draws texel by texel and puts the edge cases first") {
  const std::vector<float_generator> generators = {points(2.0f), unit_vectors(), uniform_values(5.0f, 6.0f), log_uniform_values(1e-2f, 1e2f)};
  const glm::vec4 edge(9.0f);
  const kernel_inputs a = seeded_grid(16, 8, 7, generators, {{edge, edge, edge, edge}});
  const kernel_inputs b = seeded_grid(16, 8, 7, generators, {{edge, edge, edge, edge}});
  REQUIRE(a.width == 16);
  REQUIRE(a.height == 8);
  REQUIRE(a.floats.size() == 4);
  CHECK(a.floats == b.floats);
  for (std::size_t input = 0; input < 4; ++input) CHECK(a.floats[input][0] == edge);
  // Texel 0's values are drawn first, input by input (and then replaced by the edge case).
  random_inputs random(7);
  std::vector<glm::vec4> first;
  for (const float_generator& generator : generators) first.push_back(generator(random));
  for (std::size_t input = 0; input < 4; ++input) CHECK(a.floats[input][0] != first[input]);
  const kernel_inputs plain = seeded_grid(16, 8, 7, generators);
  for (std::size_t input = 0; input < 4; ++input) CHECK(plain.floats[input][0] == first[input]);
  for (std::size_t i = 1; i < a.size(); ++i) {
    REQUIRE(std::fabs(glm::length(glm::vec3(a.floats[1][i])) - 1.0f) < 1e-6f);
    for (int c = 0; c < 4; ++c) {
      REQUIRE(std::fabs(a.floats[0][i][c]) <= (c < 3 ? 2.0f : 0.0f));
      REQUIRE(a.floats[2][i][c] >= 5.0f);
      REQUIRE(a.floats[3][i][c] <= 1e2f);
    }
  }
  CHECK_THROWS_AS(seeded_grid(2, 1, 7, generators, {{edge}}), std::invalid_argument);  // one value for four inputs
  CHECK_THROWS_AS(seeded_grid(1, 1, 7, generators, {{edge, edge, edge, edge}, {edge, edge, edge, edge}}), std::invalid_argument);
  CHECK_THROWS_AS(grid_of(0, 4, 1), std::invalid_argument);
}

TEST_CASE("geometry_inputs: receiver and light pairs with the edge cases first") {
  const kernel_inputs inputs = geometry_inputs(8);
  REQUIRE(inputs.size() == 64 * 64);
  REQUIRE(inputs.floats.size() == 4);
  CHECK(inputs.floats[0][0] == inputs.floats[2][0]);                    // coincident points
  CHECK(inputs.floats[1][1] == glm::vec4(0.0f));                        // zero normals
  CHECK(std::isinf(std::pow(static_cast<float>(inputs.floats[0][8].x), 4.0f)));  // d^4 overflows in float
  CHECK(geometry_inputs(8).floats == inputs.floats);
  CHECK(geometry_inputs(9).floats != inputs.floats);
}
