// Final gathering: the spot light's shadow in the environment, read from a map of the room's
// light eye depths (final_gather_light_depth.frag) with lib/shadow.glsl's Alg. 4 and its
// slope-scaled, normal-offset bias, as the RSM techniques' G-buffer pass does. The Monte Carlo
// reference shadows the environment's direct light with rays through the room (the object left
// out, as the cube map leaves it out), so the faces and the reference light the same surfaces.
// The window is one texel (final_gather_pipeline.cpp says why), so the receiver-plane gradient,
// which only matters across a wider window, is 0.
#ifndef VPLKIT_FINAL_GATHER_SHADOW_GLSL
#define VPLKIT_FINAL_GATHER_SHADOW_GLSL

#include "lib/shadow.glsl"
#include "lib/transform.glsl"

uniform sampler2D light_depth;   // x: the room's light eye depth, 0 where nothing was drawn
uniform mat4 light_view;
uniform mat4 light_projection;
uniform mat4 light_view_projection;
uniform int light_depth_size;
uniform shadow_density_settings shadow;

float rsm_depth_fetch(ivec2 texel) { return texelFetch(light_depth, texel, 0).x; }

// 1 where the spot light reaches (x, n) past the room, 0 where the room hides it.
float final_gather_light_visibility(vec3 x, vec3 n) {
  vec3 eye_position = transform_point(light_view, x);
  if (!(eye_position.z < 0.0)) return 1.0;  // behind the spot: its cone gives no light there anyway
  float footprint = shadow_texel_footprint(light_projection, eye_position.z, light_depth_size);
  vec3 to_light = normalize(-eye_position);
  float cos_theta = dot(transform_direction(light_view, n), to_light);
  vec3 lookup_position = shadow_normal_offset(x, n, transpose(mat3(light_view)) * to_light, footprint, shadow);
  shadow_density_settings biased = shadow;
  biased.depth_bias = shadow_slope_bias(cos_theta, footprint, shadow);
  vec2 coordinate = map_coordinate(light_view_projection, lookup_position, ivec2(light_depth_size));
  float receiver_depth = transform_point(light_view, lookup_position).z;
  return shadow_density(coordinate, receiver_depth, vec2(0.0), ivec2(light_depth_size), biased);
}

#endif
