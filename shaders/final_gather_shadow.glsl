// Final gathering: one of the scene's lights at a time (the pipeline draws the environment's
// direct light once per light and sums: final_gather_pipeline.cpp), its irradiance and its shadow
// in the environment, read from a map of the room's light eye depths (final_gather_light_depth.frag)
// with lib/shadow.glsl's Alg. 4 and its slope-scaled, normal-offset bias, as the RSM techniques'
// G-buffer pass does. A spot has one perspective map, a sun one orthographic map over the room's
// bounds, a point light six 90-degree faces side by side (lib/cube_map.glsl: the face of the
// receiver's direction from the light, as the RSM family's point lights). The Monte Carlo
// reference shadows the environment's direct light with rays through the room (the object left
// out, as the cube map leaves it out), so the faces and the reference light the same surfaces.
// The window is one texel (final_gather_pipeline.cpp says why), so the receiver-plane gradient,
// which only matters across a wider window, is 0.
#ifndef VPLKIT_FINAL_GATHER_SHADOW_GLSL
#define VPLKIT_FINAL_GATHER_SHADOW_GLSL

#include "lib/cube_map.glsl"
#include "lib/direct_light.glsl"
#include "lib/shadow.glsl"
#include "lib/transform.glsl"

// light_kind's values: frontend/scene/scene.hpp's light_kind, and -1 for no light (an unlit
// scene: the cube map still needs the environment's distances).
#define FINAL_GATHER_NO_LIGHT -1
#define FINAL_GATHER_SPOT 0
#define FINAL_GATHER_DIRECTIONAL 1
#define FINAL_GATHER_POINT 2

uniform int light_kind;
uniform spot_light spot;
uniform directional_light sun;
uniform point_light point;
uniform sampler2D light_depth;   // x: the room's light eye depth, 0 where nothing was drawn; one tile per face
uniform mat4 light_view[6];      // per tile: [0] for a spot or a sun, a point light's faces 0..5
uniform mat4 light_projection[6];
uniform mat4 light_view_projection[6];
uniform int light_depth_size;    // a tile's side
uniform shadow_density_settings shadow;

int light_depth_tile = 0;
float rsm_depth_fetch(ivec2 texel) { return texelFetch(light_depth, texel + ivec2(light_depth_tile * light_depth_size, 0), 0).x; }

// The light's irradiance at (x, n) before its shadow; 0 without a light.
vec3 final_gather_light_irradiance(vec3 x, vec3 n, irradiance_settings settings) {
  if (light_kind == FINAL_GATHER_SPOT) return spot_light_irradiance(x, n, spot, settings);
  if (light_kind == FINAL_GATHER_POINT) return point_light_irradiance(x, n, point, settings);
  if (light_kind == FINAL_GATHER_DIRECTIONAL) return directional_light_irradiance(n, sun);
  return vec3(0.0);
}

// 1 where the light reaches (x, n) past the room, 0 where the room hides it.
float final_gather_light_visibility(vec3 x, vec3 n) {
  if (light_kind == FINAL_GATHER_NO_LIGHT) return 1.0;
  int tile = light_kind == FINAL_GATHER_POINT ? cube_face_of(x - point.position) : 0;
  light_depth_tile = tile;
  mat4 view = light_view[tile], projection = light_projection[tile];
  vec3 eye_position = transform_point(view, x);
  if (!(eye_position.z < 0.0)) return 1.0;  // behind a spot: its cone gives no light there anyway
  float footprint = shadow_texel_footprint(projection, eye_position.z, light_depth_size);
  // Towards the light: along the ray for a perspective map, the map's axis for a sun's.
  vec3 to_light = projection[3][3] == 0.0 ? normalize(-eye_position) : vec3(0.0, 0.0, 1.0);
  float cos_theta = dot(transform_direction(view, n), to_light);
  vec3 lookup_position = shadow_normal_offset(x, n, transpose(mat3(view)) * to_light, footprint, shadow);
  shadow_density_settings biased = shadow;
  biased.depth_bias = shadow_slope_bias(cos_theta, footprint, shadow);
  vec2 coordinate = map_coordinate(light_view_projection[tile], lookup_position, ivec2(light_depth_size));
  // A point light's receiver near a face's edge may look up just past it (the normal offset):
  // its face's edge texel, not the neighbour tile (nor "outside", which Alg. 4 counts as shadow).
  if (light_kind == FINAL_GATHER_POINT) coordinate = clamp(coordinate, vec2(0.0), vec2(float(light_depth_size) - 0.5));
  float receiver_depth = transform_point(view, lookup_position).z;
  return shadow_density(coordinate, receiver_depth, vec2(0.0), ivec2(light_depth_size), biased);
}

#endif
