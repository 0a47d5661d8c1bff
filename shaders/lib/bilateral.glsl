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

// A loop of constant trip count over the power's bits (normal_power <= 64: 7 bits), which the
// compiler unrolls into straight multiplies and selects: llvmpipe ran the loop of data-dependent
// trip count with its per-iteration mask tests, a tenth of the post filter (docs/performance.md).
// A bit that is 0 multiplies by 1.0, exact: the same value as the loop it replaced.
const int integer_power_bits = 7;

float integer_power(float base, int power) {
  float result = 1.0;
  for (int b = 0; b < integer_power_bits; ++b) {
    result *= ((power >> b) & 1) != 0 ? base : 1.0;
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
  // Selects, not a branch (llvmpipe runs a branch's both sides under a lane mask, with its tests):
  // at depth 0 the exponent gains 0, exact, so the values are those of the branch.
  bool surface = centre.depth != 0.0;
  float relative = surface ? (tap_depth - centre.depth) * centre.depth_scale : 0.0;
  exponent += 0.5 * relative * relative;
  float depth = surface || tap_depth == centre.depth ? 1.0 : 0.0;
  float facing = max(0.0, dot(centre.normal, tap_normal));
  return exp(-exponent) * depth * integer_power(facing, normal_power);
}

float bilateral_weight(vec2 offset, float centre_depth, float tap_depth, vec3 centre_normal, vec3 tap_normal,
                       bilateral_settings settings) {
  return bilateral_weight(offset, tap_depth, tap_normal, make_bilateral_centre(centre_depth, centre_normal, settings),
                                 settings.normal_power);
}

void bilateral_accumulate(bilateral_tap tap, vec2 offset, bilateral_centre centre, int normal_power, inout vec3 sum, inout float weight_sum) {
  float weight = bilateral_weight(offset, tap.depth, tap.normal, centre, normal_power);
  sum += weight * tap.value;
  weight_sum += weight;
}

void bilateral_add_tap(ivec2 texel, vec2 centre_coordinate, bilateral_centre centre, ivec2 size, int normal_power,
                       inout vec3 sum, inout float weight_sum) {
  if (texel.x < 0 || texel.y < 0 || texel.x >= size.x || texel.y >= size.y) return;
  bilateral_tap tap = bilateral_fetch(texel);
  if (!(tap.depth < 0.0)) return;
  bilateral_accumulate(tap, vec2(texel) + 0.5 - centre_coordinate, centre, normal_power, sum, weight_sum);
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

// The centre of full-resolution pixel 2 texel + (s & 1, s >> 1) on the half-resolution grid.
vec2 bilateral_quad_centre(ivec2 texel, int s) {
  return (vec2(2 * texel + ivec2(s & 1, s >> 1)) + 0.5) / 2.0;
}

// bilateral_filter_axis for the 2 x 2 full-resolution pixels of half-resolution texel `texel`
// (see the C++ twin): each tap fetched once for the four, each pixel's sums in the same order.
// Pixel s (filtered_s) is 2 texel + (s & 1, s >> 1), of depth centre_depth[s] and normal
// normal_s. Four named accumulators, not arrays: llvmpipe kept the arrays of a loop over the
// four in memory, which cost more than the fetches saved (docs/performance.md).
void bilateral_filter_axis_quad(ivec2 texel, vec4 centre_depth, vec3 normal_0, vec3 normal_1, vec3 normal_2, vec3 normal_3, ivec2 size,
                                int axis, bilateral_settings settings, out vec3 filtered_0, out vec3 filtered_1, out vec3 filtered_2,
                                out vec3 filtered_3) {
  ivec2 step_size = axis == 0 ? ivec2(1, 0) : ivec2(0, 1);
  int radius = settings.kernel_size / 2;
  vec2 centre_0 = bilateral_quad_centre(texel, 0), centre_1 = bilateral_quad_centre(texel, 1);
  vec2 centre_2 = bilateral_quad_centre(texel, 2), centre_3 = bilateral_quad_centre(texel, 3);
  bilateral_centre constants_0 = make_bilateral_centre(centre_depth.x, normal_0, settings);
  bilateral_centre constants_1 = make_bilateral_centre(centre_depth.y, normal_1, settings);
  bilateral_centre constants_2 = make_bilateral_centre(centre_depth.z, normal_2, settings);
  bilateral_centre constants_3 = make_bilateral_centre(centre_depth.w, normal_3, settings);
  vec3 sum_0 = vec3(0.0), sum_1 = vec3(0.0), sum_2 = vec3(0.0), sum_3 = vec3(0.0);
  float weight_sum_0 = 0.0, weight_sum_1 = 0.0, weight_sum_2 = 0.0, weight_sum_3 = 0.0;
  for (int i = -radius; i <= radius; ++i) {
    ivec2 tap_texel = texel + step_size * i;
    if (tap_texel.x < 0 || tap_texel.y < 0 || tap_texel.x >= size.x || tap_texel.y >= size.y) continue;
    bilateral_tap tap = bilateral_fetch(tap_texel);
    if (!(tap.depth < 0.0)) continue;
    vec2 tap_centre = vec2(tap_texel) + 0.5;
    bilateral_accumulate(tap, tap_centre - centre_0, constants_0, settings.normal_power, sum_0, weight_sum_0);
    bilateral_accumulate(tap, tap_centre - centre_1, constants_1, settings.normal_power, sum_1, weight_sum_1);
    bilateral_accumulate(tap, tap_centre - centre_2, constants_2, settings.normal_power, sum_2, weight_sum_2);
    bilateral_accumulate(tap, tap_centre - centre_3, constants_3, settings.normal_power, sum_3, weight_sum_3);
  }
  filtered_0 = weight_sum_0 > 0.0 ? sum_0 / weight_sum_0 : vec3(0.0);
  filtered_1 = weight_sum_1 > 0.0 ? sum_1 / weight_sum_1 : vec3(0.0);
  filtered_2 = weight_sum_2 > 0.0 ? sum_2 / weight_sum_2 : vec3(0.0);
  filtered_3 = weight_sum_3 > 0.0 ? sum_3 / weight_sum_3 : vec3(0.0);
}

#endif
