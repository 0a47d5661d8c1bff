// GLSL twin of include/vplkit/hash.hpp: PCG hash (Jarzynski and Olano, JCGT 2020) and uniform
// floats from hash bits. Bit-identical to the C++ side; see the header for the reasoning.
#ifndef VPLKIT_HASH_GLSL
#define VPLKIT_HASH_GLSL

uint hash_uint32(uint value) {
  uint state = value * 747796405u + 2891336453u;
  uint word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
  return (word >> 22u) ^ word;
}

uint hash_combine(uint seed, uint value) {
  return hash_uint32(seed ^ (value + 0x9e3779b9u + (seed << 6u) + (seed >> 2u)));
}

float uniform_float_from_bits(uint bits) {
  uint one_to_two_bits = 0x3f800000u | (bits >> 9u);
  return uintBitsToFloat(one_to_two_bits) - 1.0;
}

#endif
