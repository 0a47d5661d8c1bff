// GLSL twin of include/vplkit/shadow.hpp: shadow density, Alg. 4 of [RSMV] (see the header
// for the depth convention and the receiver-plane bias). The including shader defines
// float rsm_depth_fetch(ivec2 texel).
#ifndef VPLKIT_SHADOW_GLSL
#define VPLKIT_SHADOW_GLSL

struct shadow_density_settings {
  int kernel_size;
  float depth_bias;
};

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
