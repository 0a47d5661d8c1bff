// GLSL twin of include/vplkit/direct_light.hpp: spot-light irradiance with a smooth cone.
#ifndef VPLKIT_DIRECT_LIGHT_GLSL
#define VPLKIT_DIRECT_LIGHT_GLSL

#include "lib/irradiance.glsl"

struct spot_light {
  vec3 position;
  vec3 direction;
  vec3 intensity;
  float cos_inner;
  float cos_outer;
};

vec3 spot_light_irradiance(vec3 x, vec3 n, spot_light light, irradiance_settings settings) {
  vec3 to_light = light.position - x;
  float min_distance = settings.min_distance;
  float distance_squared = max(dot(to_light, to_light), min_distance * min_distance);
  vec3 direction_to_light = to_light / sqrt(distance_squared);
  float cos_receiver = max(0.0, dot(n, direction_to_light));
  float cos_axis = -dot(light.direction, direction_to_light);
  float t = clamp((cos_axis - light.cos_outer) / (light.cos_inner - light.cos_outer), 0.0, 1.0);
  float cone = t * t * (3.0 - 2.0 * t);
  return light.intensity * (cone * cos_receiver / distance_squared);
}

#endif
