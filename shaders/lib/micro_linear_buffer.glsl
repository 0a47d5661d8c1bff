// GLSL twin of include/vplkit/micro_linear_buffer.hpp ([RSMV], section 3.3, Alg. 2, 3, 6, and the
// variant alg6_ray): Alg. 2 and 3 keep one bit per slot, Alg. 6 an 8-bit claim count per slot
// (see the header). The literals 0.02 and 0.2 are alg6_ray_tangent_slope and alg6_ray_behind_slope.
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
  vec3 previous_position;
  vec3 previous_normal;
};

void micro_linear_buffer_reset(out micro_linear_buffer linear_buffer, int slot_count) {
  linear_buffer.claims = uvec4(0u);
  linear_buffer.occluded = 0u;
  linear_buffer.previous_index = -1;
  linear_buffer.previous_visibility = 1.0;
  linear_buffer.previous_position = vec3(0.0);
  linear_buffer.previous_normal = vec3(0.0);
}

float micro_linear_buffer_alg2(inout micro_linear_buffer linear_buffer, int index) {
  uint bit = 1u << uint(index);
  float visibility = (linear_buffer.occluded & bit) == 0u ? 1.0 : 0.0;
  linear_buffer.occluded |= bit;
  linear_buffer.previous_index = index;
  linear_buffer.previous_visibility = visibility;
  return visibility;
}

float micro_linear_buffer_alg3(inout micro_linear_buffer linear_buffer, int index) {
  float visibility = linear_buffer.previous_visibility;
  if (index != linear_buffer.previous_index) {
    uint bit = 1u << uint(index);
    visibility = (linear_buffer.occluded & bit) == 0u ? 1.0 : 0.0;
    linear_buffer.occluded |= bit;
  }
  linear_buffer.previous_index = index;
  linear_buffer.previous_visibility = visibility;
  return visibility;
}

float micro_linear_buffer_alg6(inout micro_linear_buffer linear_buffer, int index) {
  bool same_as_previous = index == linear_buffer.previous_index;
  uint word = uint(index) >> 2u;
  uint shift = (uint(index) & 3u) * 8u;
  uvec4 in_word = uvec4(word == 0u ? 1u : 0u, word == 1u ? 1u : 0u, word == 2u ? 1u : 0u, word == 3u ? 1u : 0u);
  uint claims_word = word == 0u ? linear_buffer.claims.x : word == 1u ? linear_buffer.claims.y : word == 2u ? linear_buffer.claims.z : linear_buffer.claims.w;
  uint count = (claims_word >> shift) & 255u;
  float slot_value = 1.0 - float(count);
  float visibility = same_as_previous ? linear_buffer.previous_visibility : slot_value;
  uint claim = same_as_previous || count == 255u ? 0u : 1u;
  linear_buffer.claims += in_word * (claim << shift);
  linear_buffer.previous_index = index;
  linear_buffer.previous_visibility = visibility;
  return visibility;
}

bool alg6_ray_in_front(vec3 x, vec3 n, vec3 xp, float min_distance) {
  vec3 d = xp - x;
  float facing = n.x * d.x + n.y * d.y + n.z * d.z;
  float d_length = sqrt(d.x * d.x + d.y * d.y + d.z * d.z);
  return facing > 0.02 * d_length + min_distance;
}

float micro_linear_buffer_alg6_ray(inout micro_linear_buffer linear_buffer, int index, vec3 receiver, vec3 position, vec3 normal) {
  vec3 to_receiver = receiver - linear_buffer.previous_position;
  vec3 step = position - linear_buffer.previous_position;
  float faces = linear_buffer.previous_normal.x * to_receiver.x + linear_buffer.previous_normal.y * to_receiver.y + linear_buffer.previous_normal.z * to_receiver.z;
  float ahead = linear_buffer.previous_normal.x * step.x + linear_buffer.previous_normal.y * step.y + linear_buffer.previous_normal.z * step.z;
  float step_length = sqrt(step.x * step.x + step.y * step.y + step.z * step.z);
  if (!(faces > 0.0) || ahead < -0.2 * step_length) linear_buffer.previous_index = -1;
  float visibility = micro_linear_buffer_alg6(linear_buffer, index);
  linear_buffer.previous_position = position;
  linear_buffer.previous_normal = normal;
  return visibility;
}

#endif
