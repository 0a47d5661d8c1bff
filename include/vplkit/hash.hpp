// Integer hash and uniform floats from hash bits: the one source of randomness for every
// jittered pattern in vplkit, so that a pattern drawn in C++ and in GLSL is the same pattern.
//
// hash_uint32 is the PCG hash recommended by Jarzynski and Olano, "Hash Functions for GPU
// Rendering", JCGT 9(3), 2020: one multiply-add LCG step followed by PCG's RXS-M-XS output
// permutation. It uses only 32-bit wrapping integer arithmetic, which GLSL `uint` and C++
// `std::uint32_t` define identically, so both sides are bit-identical by construction.
//
// GLSL twin: shaders/lib/hash.glsl (same names, same operations in the same order).
#pragma once

#include <cstdint>
#include <cstring>

namespace vplkit {

/// PCG hash of one 32-bit word. Bijective on 32 bits.
inline constexpr std::uint32_t hash_uint32(std::uint32_t value) {
  const std::uint32_t state = value * 747796405u + 2891336453u;
  const std::uint32_t word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
  return (word >> 22u) ^ word;
}

/// Hash of a sequence of words, folded left: hash_combine(hash_combine(a, b), c) for (a, b, c).
/// Used to derive a per-pixel, per-sample stream from (pixel x, pixel y, sample index, seed).
inline constexpr std::uint32_t hash_combine(std::uint32_t seed, std::uint32_t value) {
  return hash_uint32(seed ^ (value + 0x9e3779b9u + (seed << 6u) + (seed >> 2u)));
}

/// A float in [0, 1) from the top 23 bits of `bits`: the bits become the mantissa of a float in
/// [1, 2), and 1 is subtracted. Every step is exact, so GLSL and C++ agree to the bit. The result
/// is a multiple of 2^-23; 1.0 is never returned.
inline float uniform_float_from_bits(std::uint32_t bits) {
  const std::uint32_t one_to_two_bits = 0x3f800000u | (bits >> 9u);
  float one_to_two;
  std::memcpy(&one_to_two, &one_to_two_bits, sizeof one_to_two);
  return one_to_two - 1.0f;
}

}  // namespace vplkit
