// GLSL twin of include/vplkit/shadow.hpp: shadow density, Alg. 4 of [RSMV] (see the header
// for the depth convention, the receiver-plane bias and the slope-scaled, normal-offset bias). The including shader defines
// float rsm_depth_fetch(ivec2 texel), or VPLKIT_SHADOW_BIAS_ONLY for the bias alone (Light Wave's
// hardware-compared maps).
#ifndef VPLKIT_SHADOW_GLSL
#define VPLKIT_SHADOW_GLSL

struct shadow_density_settings {
  int kernel_size;
  float depth_bias;
  float normal_offset;
  float slope_scale;
  float max_slope;
};

float shadow_texel_footprint(mat4 projection, float eye_depth, int map_size) {
  float w = projection[2][3] * eye_depth + projection[3][3];
  return 2.0 * abs(w) / (abs(projection[0][0]) * float(map_size));
}

vec3 shadow_normal_offset(vec3 position, vec3 normal, vec3 to_light, float footprint, shadow_density_settings settings) {
  float cos_theta = clamp(dot(normal, to_light), 0.0, 1.0);
  float sin_theta = sqrt(1.0 - cos_theta * cos_theta);
  return position + normal * (settings.normal_offset * footprint * sin_theta);
}

float shadow_slope_bias(float cos_theta, float footprint, shadow_density_settings settings) {
  float c = clamp(cos_theta, 0.0, 1.0);
  float tan_theta = c * settings.max_slope > sqrt(1.0 - c * c) ? sqrt(1.0 - c * c) / c : settings.max_slope;
  return settings.depth_bias + settings.slope_scale * footprint * tan_theta;
}

#ifndef VPLKIT_SHADOW_BIAS_ONLY
float rsm_depth_fetch(ivec2 texel);

float shadow_density(vec2 rsm_coordinate, float receiver_depth, vec2 depth_gradient, ivec2 rsm_size,
                     shadow_density_settings settings) {
  ivec2 centre = ivec2(floor(rsm_coordinate));
  int half_size = settings.kernel_size / 2;
  int lit = 0;
  for (int i = -half_size; i < settings.kernel_size - half_size; ++i) {
    for (int j = -half_size; j < settings.kernel_size - half_size; ++j) {
      ivec2 texel = centre + ivec2(i, j);
      if (texel.x < 0 || texel.y < 0 || texel.x >= rsm_size.x || texel.y >= rsm_size.y) continue;
      float stored = rsm_depth_fetch(texel);
      float plane_depth = receiver_depth + dot(depth_gradient, vec2(texel) + 0.5 - rsm_coordinate);
      if (!(stored < 0.0) || stored - settings.depth_bias <= plane_depth) ++lit;
    }
  }
  return float(lit) / float(settings.kernel_size * settings.kernel_size);
}
#endif

#endif
