// GLSL twin of include/vplkit/bilateral.hpp: the edge-aware post filter of [RSMV].
// The including shader defines bilateral_tap bilateral_fetch(ivec2 texel).
#ifndef VPLKIT_BILATERAL_GLSL
#define VPLKIT_BILATERAL_GLSL

struct bilateral_tap {
  vec3 value;
  float depth;
  vec3 normal;
};

struct bilateral_settings {
  int kernel_size;
  float spatial_sigma;
  float depth_sigma;
  int normal_power;
};

bilateral_tap bilateral_fetch(ivec2 texel);

float bilateral_weight(vec2 offset, float centre_depth, float tap_depth, vec3 centre_normal, vec3 tap_normal,
                       bilateral_settings settings) {
  float spatial = exp(-dot(offset, offset) / (2.0 * settings.spatial_sigma * settings.spatial_sigma));
  // Relative to the centre's depth; a centre at depth 0 (nothing there) matches only depth 0.
  float depth = tap_depth == centre_depth ? 1.0 : 0.0;
  if (centre_depth != 0.0) {
    float relative = (tap_depth - centre_depth) / (settings.depth_sigma * centre_depth);
    depth = exp(-0.5 * relative * relative);
  }
  float facing = max(0.0, dot(centre_normal, tap_normal));
  float normal = 1.0;
  for (int i = 0; i < settings.normal_power; ++i) normal *= facing;
  return spatial * depth * normal;
}

void bilateral_add_tap(ivec2 texel, vec2 centre, float centre_depth, vec3 centre_normal, ivec2 size,
                       bilateral_settings settings, inout vec3 sum, inout float weight_sum) {
  if (texel.x < 0 || texel.y < 0 || texel.x >= size.x || texel.y >= size.y) return;
  bilateral_tap tap = bilateral_fetch(texel);
  if (!(tap.depth < 0.0)) return;
  float weight = bilateral_weight(vec2(texel) + 0.5 - centre, centre_depth, tap.depth, centre_normal, tap.normal, settings);
  sum += weight * tap.value;
  weight_sum += weight;
}

vec3 bilateral_filter(vec2 centre, float centre_depth, vec3 centre_normal, ivec2 size, bilateral_settings settings) {
  ivec2 base = ivec2(floor(centre));
  int radius = settings.kernel_size / 2;
  vec3 sum = vec3(0.0);
  float weight_sum = 0.0;
  for (int j = -radius; j <= radius; ++j)
    for (int i = -radius; i <= radius; ++i)
      bilateral_add_tap(base + ivec2(i, j), centre, centre_depth, centre_normal, size, settings, sum, weight_sum);
  return weight_sum > 0.0 ? sum / weight_sum : vec3(0.0);
}

vec3 bilateral_filter_axis(vec2 centre, float centre_depth, vec3 centre_normal, ivec2 size, int axis,
                           bilateral_settings settings) {
  ivec2 base = ivec2(floor(centre));
  ivec2 step_size = axis == 0 ? ivec2(1, 0) : ivec2(0, 1);
  int radius = settings.kernel_size / 2;
  vec3 sum = vec3(0.0);
  float weight_sum = 0.0;
  for (int i = -radius; i <= radius; ++i)
    bilateral_add_tap(base + step_size * i, centre, centre_depth, centre_normal, size, settings, sum, weight_sum);
  return weight_sum > 0.0 ? sum / weight_sum : vec3(0.0);
}

#endif
