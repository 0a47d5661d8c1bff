// GLSL twin of include/vplkit/micro_linear_buffer.hpp ([RSMV], section 3.3, Alg. 2, 3, 6):
// Alg. 2 and 3 keep one bit per slot, Alg. 6 an 8-bit claim count per slot (see the header).
// elevation_slots comes from the C++ make_elevation_slots through a uniform, so the bucket
// decisions are bit-identical on both sides; see the header.
#ifndef VPLKIT_MICRO_LINEAR_BUFFER_GLSL
#define VPLKIT_MICRO_LINEAR_BUFFER_GLSL

#define VPLKIT_MAX_SLOTS 16

struct elevation_slots {
  int count;
  float boundary_tangent[VPLKIT_MAX_SLOTS - 1];
};

// The loop runs to a constant where the program is built for one slot count (VPLKIT_SLOT_COUNT,
// equal to slots.count): the compiler unrolls it, which took 30 % off the RSM gather on
// llvmpipe (8 slots). Without the define it runs to the uniform count.
#ifdef VPLKIT_SLOT_COUNT
#define VPLKIT_ELEVATION_BOUNDARIES (VPLKIT_SLOT_COUNT - 1)
#else
#define VPLKIT_ELEVATION_BOUNDARIES (slots.count - 1)
#endif

int elevation_slot(float dz, float horizontal, elevation_slots slots) {
  int index = 0;
  for (int k = 0; k < VPLKIT_ELEVATION_BOUNDARIES; ++k) index += (dz >= slots.boundary_tangent[k] * horizontal) ? 1 : 0;
  return index;
}

int elevation_bucket(vec3 x_eye, vec3 xp_eye, elevation_slots slots) {
  float dx = xp_eye.x - x_eye.x;
  float dy = xp_eye.y - x_eye.y;
  float dz = xp_eye.z - x_eye.z;
  return elevation_slot(dz, sqrt(dx * dx + dy * dy), slots);
}

int elevation_bucket_about(vec3 x_eye, vec3 xp_eye, vec3 up, elevation_slots slots) {
  vec3 d = xp_eye - x_eye;
  float vertical = d.x * up.x + d.y * up.y + d.z * up.z;
  vec3 across = d - vertical * up;
  return elevation_slot(vertical, sqrt(across.x * across.x + across.y * across.y + across.z * across.z), slots);
}

struct micro_linear_buffer {
  uint occluded;
  uvec4 claims;
  int previous_index;
  float previous_visibility;
};

void micro_linear_buffer_reset(out micro_linear_buffer buffer, int slot_count) {
  buffer.claims = uvec4(0u);
  buffer.occluded = 0u;
  buffer.previous_index = -1;
  buffer.previous_visibility = 1.0;
}

float micro_linear_buffer_alg2(inout micro_linear_buffer buffer, int index) {
  uint bit = 1u << uint(index);
  float visibility = (buffer.occluded & bit) == 0u ? 1.0 : 0.0;
  buffer.occluded |= bit;
  buffer.previous_index = index;
  buffer.previous_visibility = visibility;
  return visibility;
}

float micro_linear_buffer_alg3(inout micro_linear_buffer buffer, int index) {
  float visibility = buffer.previous_visibility;
  if (index != buffer.previous_index) {
    uint bit = 1u << uint(index);
    visibility = (buffer.occluded & bit) == 0u ? 1.0 : 0.0;
    buffer.occluded |= bit;
  }
  buffer.previous_index = index;
  buffer.previous_visibility = visibility;
  return visibility;
}

float micro_linear_buffer_alg6(inout micro_linear_buffer buffer, int index) {
  bool same_as_previous = index == buffer.previous_index;
  uint word = uint(index) >> 2u;
  uint shift = (uint(index) & 3u) * 8u;
  uvec4 in_word = uvec4(word == 0u ? 1u : 0u, word == 1u ? 1u : 0u, word == 2u ? 1u : 0u, word == 3u ? 1u : 0u);
  uint claims_word = word == 0u ? buffer.claims.x : word == 1u ? buffer.claims.y : word == 2u ? buffer.claims.z : buffer.claims.w;
  uint count = (claims_word >> shift) & 255u;
  float slot_value = 1.0 - float(count);
  float visibility = same_as_previous ? buffer.previous_visibility : slot_value;
  uint claim = same_as_previous || count == 255u ? 0u : 1u;
  buffer.claims += in_word * (claim << shift);
  buffer.previous_index = index;
  buffer.previous_visibility = visibility;
  return visibility;
}

#endif
