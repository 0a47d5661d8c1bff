// GLSL twin of include/vplkit/direct_light.hpp: spot, directional and point light irradiance, and the
// flux of an RSM texel.
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

float spot_light_cone(spot_light light, float cos_axis) {
  float t = clamp((cos_axis - light.cos_outer) / (light.cos_inner - light.cos_outer), 0.0, 1.0);
  return t * t * (3.0 - 2.0 * t);
}

vec3 direction_to_light_at(vec3 x, vec3 position, float min_distance, out float distance_squared) {
  vec3 to_light = position - x;
  distance_squared = max(dot(to_light, to_light), min_distance * min_distance);
  return to_light / sqrt(distance_squared);
}

vec3 spot_light_irradiance(vec3 x, vec3 n, spot_light light, irradiance_settings settings) {
  float distance_squared;
  vec3 direction_to_light = direction_to_light_at(x, light.position, settings.min_distance, distance_squared);
  float cos_receiver = max(0.0, dot(n, direction_to_light));
  float cone = spot_light_cone(light, -dot(light.direction, direction_to_light));
  return light.intensity * (cone * cos_receiver / distance_squared);
}

struct directional_light {
  vec3 direction;
  vec3 irradiance;
};

vec3 directional_light_irradiance(vec3 n, directional_light light) {
  return light.irradiance * max(0.0, -dot(n, light.direction));
}

struct point_light {
  vec3 position;
  vec3 intensity;
};

vec3 point_light_irradiance(vec3 x, vec3 n, point_light light, irradiance_settings settings) {
  float distance_squared;
  vec3 direction_to_light = direction_to_light_at(x, light.position, settings.min_distance, distance_squared);
  float cos_receiver = max(0.0, dot(n, direction_to_light));
  return light.intensity * (cos_receiver / distance_squared);
}

float perspective_texel_solid_angle(vec2 ndc, float tan_half_fov, ivec2 size) {
  vec2 on_plane = ndc * tan_half_fov;
  float cos_theta = 1.0 / sqrt(1.0 + dot(on_plane, on_plane));
  float texel_area = (2.0 * tan_half_fov / float(size.x)) * (2.0 * tan_half_fov / float(size.y));
  return texel_area * (cos_theta * cos_theta * cos_theta);
}

vec3 spot_light_texel_flux(vec3 albedo, vec3 position, vec3 normal, spot_light light, vec2 ndc, float tan_half_fov,
                           ivec2 size) {
  vec3 from_light = normalize(position - light.position);
  float cone = spot_light_cone(light, dot(light.direction, from_light));
  float facing = dot(normal, from_light) < 0.0 ? 1.0 : 0.0;
  return albedo * light.intensity * (facing * cone * perspective_texel_solid_angle(ndc, tan_half_fov, size));
}

vec3 point_light_texel_flux(vec3 albedo, vec3 position, vec3 normal, point_light light, vec2 ndc, ivec2 size) {
  vec3 from_light = position - light.position;
  float facing = dot(normal, from_light) < 0.0 ? 1.0 : 0.0;
  return albedo * light.intensity * (facing * perspective_texel_solid_angle(ndc, 1.0, size));
}

vec3 directional_light_texel_flux(vec3 albedo, vec3 normal, directional_light light, float texel_area) {
  float facing = dot(normal, light.direction) < 0.0 ? 1.0 : 0.0;
  return albedo * light.irradiance * (facing * texel_area);
}

#endif
