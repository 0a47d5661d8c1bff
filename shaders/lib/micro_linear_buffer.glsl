// GLSL twin of include/vplkit/micro_linear_buffer.hpp (paper 000, section 3.3, Alg. 2, 3, 6).
// elevation_slots comes from the C++ make_elevation_slots through a uniform, so the bucket
// decisions are bit-identical on both sides; see the header.
#ifndef VPLKIT_MICRO_LINEAR_BUFFER_GLSL
#define VPLKIT_MICRO_LINEAR_BUFFER_GLSL

#define VPLKIT_MAX_SLOTS 16

struct elevation_slots {
  int count;
  float boundary_tangent[VPLKIT_MAX_SLOTS - 1];
};

int elevation_bucket(vec3 x_eye, vec3 xp_eye, elevation_slots slots) {
  float dx = xp_eye.x - x_eye.x;
  float dy = xp_eye.y - x_eye.y;
  float dz = xp_eye.z - x_eye.z;
  float horizontal = sqrt(dx * dx + dy * dy);
  int index = 0;
  for (int k = 0; k < slots.count - 1; ++k) index += (dz >= slots.boundary_tangent[k] * horizontal) ? 1 : 0;
  return index;
}

struct micro_linear_buffer {
  float slot[VPLKIT_MAX_SLOTS];
  int previous_index;
  float previous_visibility;
};

void micro_linear_buffer_reset(out micro_linear_buffer buffer, int slot_count) {
  for (int i = 0; i < VPLKIT_MAX_SLOTS; ++i) buffer.slot[i] = i < slot_count ? 1.0 : 0.0;
  buffer.previous_index = -1;
  buffer.previous_visibility = 1.0;
}

float micro_linear_buffer_alg2(inout micro_linear_buffer buffer, int index) {
  float visibility = buffer.slot[index];
  buffer.slot[index] = 0.0;
  buffer.previous_index = index;
  buffer.previous_visibility = visibility;
  return visibility;
}

float micro_linear_buffer_alg3(inout micro_linear_buffer buffer, int index) {
  float visibility = buffer.previous_visibility;
  if (index != buffer.previous_index) {
    visibility = buffer.slot[index];
    buffer.slot[index] = 0.0;
  }
  buffer.previous_index = index;
  buffer.previous_visibility = visibility;
  return visibility;
}

float micro_linear_buffer_alg6(inout micro_linear_buffer buffer, int index) {
  bool same_as_previous = index == buffer.previous_index;
  float slot_value = buffer.slot[index];
  float visibility = same_as_previous ? buffer.previous_visibility : slot_value;
  buffer.slot[index] = same_as_previous ? slot_value : slot_value - 1.0;
  buffer.previous_index = index;
  buffer.previous_visibility = visibility;
  return visibility;
}

#endif
