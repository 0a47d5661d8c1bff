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

float integer_power(float base, int power) {
  float result = 1.0;
  for (int k = power; k > 0; k >>= 1) {
    if ((k & 1) != 0) result *= base;
    base *= base;
  }
  return result;
}

// What a tap's weight needs of its centre, once per centre (see the C++ twin).
struct bilateral_centre {
  float depth;
  vec3 normal;
  float spatial_scale;
  float depth_scale;
};

bilateral_centre make_bilateral_centre(float depth, vec3 normal, bilateral_settings settings) {
  return bilateral_centre(depth, normal, 1.0 / (2.0 * settings.spatial_sigma * settings.spatial_sigma),
                          depth != 0.0 ? 1.0 / (settings.depth_sigma * depth) : 0.0);
}

// One exp of the spatial and depth exponents' sum (see the C++ twin).
float bilateral_weight(vec2 offset, float tap_depth, vec3 tap_normal, bilateral_centre centre, int normal_power) {
  float exponent = dot(offset, offset) * centre.spatial_scale;
  // Relative to the centre's depth; a centre at depth 0 (nothing there) matches only depth 0.
  float depth = tap_depth == centre.depth ? 1.0 : 0.0;
  if (centre.depth != 0.0) {
    float relative = (tap_depth - centre.depth) * centre.depth_scale;
    exponent += 0.5 * relative * relative;
    depth = 1.0;
  }
  float facing = max(0.0, dot(centre.normal, tap_normal));
  return exp(-exponent) * depth * integer_power(facing, normal_power);
}

float bilateral_weight(vec2 offset, float centre_depth, float tap_depth, vec3 centre_normal, vec3 tap_normal,
                       bilateral_settings settings) {
  return bilateral_weight(offset, tap_depth, tap_normal, make_bilateral_centre(centre_depth, centre_normal, settings),
                                 settings.normal_power);
}

void bilateral_add_tap(ivec2 texel, vec2 centre_coordinate, bilateral_centre centre, ivec2 size, int normal_power,
                       inout vec3 sum, inout float weight_sum) {
  if (texel.x < 0 || texel.y < 0 || texel.x >= size.x || texel.y >= size.y) return;
  bilateral_tap tap = bilateral_fetch(texel);
  if (!(tap.depth < 0.0)) return;
  float weight = bilateral_weight(vec2(texel) + 0.5 - centre_coordinate, tap.depth, tap.normal, centre, normal_power);
  sum += weight * tap.value;
  weight_sum += weight;
}

vec3 bilateral_filter(vec2 centre, float centre_depth, vec3 centre_normal, ivec2 size, bilateral_settings settings) {
  ivec2 base = ivec2(floor(centre));
  int radius = settings.kernel_size / 2;
  bilateral_centre constants = make_bilateral_centre(centre_depth, centre_normal, settings);
  vec3 sum = vec3(0.0);
  float weight_sum = 0.0;
  for (int j = -radius; j <= radius; ++j)
    for (int i = -radius; i <= radius; ++i)
      bilateral_add_tap(base + ivec2(i, j), centre, constants, size, settings.normal_power, sum, weight_sum);
  return weight_sum > 0.0 ? sum / weight_sum : vec3(0.0);
}

vec3 bilateral_filter_axis(vec2 centre, float centre_depth, vec3 centre_normal, ivec2 size, int axis,
                           bilateral_settings settings) {
  ivec2 base = ivec2(floor(centre));
  ivec2 step_size = axis == 0 ? ivec2(1, 0) : ivec2(0, 1);
  int radius = settings.kernel_size / 2;
  bilateral_centre constants = make_bilateral_centre(centre_depth, centre_normal, settings);
  vec3 sum = vec3(0.0);
  float weight_sum = 0.0;
  for (int i = -radius; i <= radius; ++i)
    bilateral_add_tap(base + step_size * i, centre, constants, size, settings.normal_power, sum, weight_sum);
  return weight_sum > 0.0 ? sum / weight_sum : vec3(0.0);
}

#endif
