#version 330 core
// Direct-light pass: Lambertian radiance albedo / pi * E, with E from the spot light
// (lib/direct_light.glsl) times the shadow-map visibility (hardware 2x2 PCF).
#include "lib/direct_light.glsl"

uniform spot_light light;
uniform irradiance_settings irradiance;
uniform sampler2DShadow shadow_map;

in vec3 world_position;
in vec3 world_normal;
in vec3 surface_albedo;
in vec4 light_clip_position;
layout(location = 0) out vec4 radiance;

const float pi = 3.14159265358979;

float shadow_visibility() {
  vec3 projected = light_clip_position.xyz / light_clip_position.w * 0.5 + 0.5;
  if (any(lessThan(projected, vec3(0.0))) || any(greaterThan(projected, vec3(1.0)))) return 0.0;
  return texture(shadow_map, projected);
}

void main() {
  vec3 n = normalize(world_normal);
  vec3 irradiance_at_point = spot_light_irradiance(world_position, n, light, irradiance);
  radiance = vec4(surface_albedo / pi * irradiance_at_point * shadow_visibility(), 1.0);
}
