// Properties of the shared integer hash and of uniform floats from bits (include/vplkit/hash.hpp).
#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <bitset>
#include <cmath>
#include <cstring>
#include <vector>

#include <vplkit/hash.hpp>

using vplkit::hash_combine;
using vplkit::hash_uint32;
using vplkit::uniform_float_from_bits;

TEST_CASE("hash_uint32 is a bijection: no collisions on 2^20 consecutive inputs") {
  std::vector<std::uint32_t> values;
  for (std::uint32_t i = 0; i < (1u << 20); ++i) values.push_back(hash_uint32(i));
  std::sort(values.begin(), values.end());
  CHECK(std::adjacent_find(values.begin(), values.end()) == values.end());
}

TEST_CASE("hash_uint32 avalanches: flipping one input bit flips about half of the output bits") {
  // For a good hash each output bit flips with probability 1/2 for every input bit. Averaged over
  // 4096 inputs, every (input bit, output bit) pair must flip between 40% and 60% of the time.
  constexpr int samples = 4096;
  std::array<std::array<int, 32>, 32> flips{};
  for (std::uint32_t i = 0; i < samples; ++i) {
    const std::uint32_t input = hash_uint32(i * 2654435761u);  // spread inputs over all bits
    const std::uint32_t output = hash_uint32(input);
    for (int bit = 0; bit < 32; ++bit) {
      const std::uint32_t changed = output ^ hash_uint32(input ^ (1u << bit));
      for (int out_bit = 0; out_bit < 32; ++out_bit) flips[bit][out_bit] += (changed >> out_bit) & 1u;
    }
  }
  double worst = 0.0;
  for (const auto& row : flips)
    for (int count : row) worst = std::max(worst, std::fabs(count / double(samples) - 0.5));
  CAPTURE(worst);
  CHECK(worst < 0.1);
}

TEST_CASE("hash_combine depends on the order and on every word") {
  CHECK(hash_combine(hash_combine(0u, 1u), 2u) != hash_combine(hash_combine(0u, 2u), 1u));
  int distinct_neighbours = 0;
  for (std::uint32_t x = 0; x < 256; ++x)
    distinct_neighbours += hash_combine(hash_combine(7u, x), 3u) != hash_combine(hash_combine(7u, x + 1), 3u);
  CHECK(distinct_neighbours == 256);
}

TEST_CASE("uniform_float_from_bits covers [0, 1) exactly at its ends") {
  CHECK(uniform_float_from_bits(0u) == 0.0f);
  CHECK(uniform_float_from_bits(0x1ffu) == 0.0f);  // the low 9 bits are dropped
  CHECK(uniform_float_from_bits(0xffffffffu) == 1.0f - std::ldexp(1.0f, -23));
  CHECK(uniform_float_from_bits(0x80000000u) == 0.5f);
  // Monotone in the top 23 bits.
  for (std::uint32_t top = 1; top < 5000; ++top)
    REQUIRE(uniform_float_from_bits(top << 9u) > uniform_float_from_bits((top - 1u) << 9u));
}

TEST_CASE("hashed uniform floats are uniform: chi-square over 64 bins") {
  constexpr int bins = 64;
  constexpr int samples = 1 << 18;
  std::array<int, bins> counts{};
  double sum = 0.0;
  for (std::uint32_t i = 0; i < samples; ++i) {
    const float u = uniform_float_from_bits(hash_uint32(i));
    REQUIRE(u >= 0.0f);
    REQUIRE(u < 1.0f);
    sum += u;
    ++counts[static_cast<std::size_t>(u * bins)];
  }
  const double expected = double(samples) / bins;
  double chi_square = 0.0;
  for (int count : counts) chi_square += (count - expected) * (count - expected) / expected;
  CAPTURE(chi_square);
  // 63 degrees of freedom: P(chi^2 > 110) < 2e-4 for a uniform source.
  CHECK(chi_square < 110.0);
  CHECK(std::fabs(sum / samples - 0.5) < 0.003);
}
