#version 330 core
// Pass 2, G-buffer generation ([RSMV], Fig. 4.3): [world position | camera eye depth],
// [albedo | shadow density (Alg. 4)], [world normal | -].
#include "lib/shadow.glsl"
#include "lib/transform.glsl"
#include "surface_material.glsl"

uniform mat4 camera_view;
uniform mat4 light_view;
uniform mat4 light_view_projection;
uniform mat4 light_projection;
uniform ivec2 rsm_size;
uniform shadow_density_settings shadow;
uniform usampler2D rsm_packed;  // lib/rsm_packing.glsl: x holds the light eye depth's bits

in vec3 world_position;
in vec3 world_normal;
in vec3 surface_albedo;
layout(location = 0) out vec4 position_depth;
layout(location = 1) out vec4 albedo_density;
layout(location = 2) out vec4 normal_out;

float rsm_depth_fetch(ivec2 texel) { return uintBitsToFloat(texelFetch(rsm_packed, texel, 0).x); }

// Change of the light eye depth per RSM texel across this surface, from screen-space
// derivatives (receiver-plane depth bias, Isidoro 2006): solve
// [d(rsm)/dx d(rsm)/dy]^T * gradient = [d(depth)/dx d(depth)/dy]. Clamped, because at
// silhouettes the derivatives straddle two surfaces; at max_slope RSM texel footprints per texel,
// the steepest slope the bias is made for (lib/shadow.glsl).
vec2 receiver_depth_gradient(vec2 rsm_coordinate, float receiver_depth, float footprint) {
  vec2 rsm_dx = dFdx(rsm_coordinate), rsm_dy = dFdy(rsm_coordinate);
  float depth_dx = dFdx(receiver_depth), depth_dy = dFdy(receiver_depth);
  float determinant = rsm_dx.x * rsm_dy.y - rsm_dx.y * rsm_dy.x;
  if (abs(determinant) < 1e-8) return vec2(0.0);
  vec2 gradient = vec2(rsm_dy.y * depth_dx - rsm_dx.y * depth_dy, rsm_dx.x * depth_dy - rsm_dy.x * depth_dx) / determinant;
  float limit = shadow.max_slope * footprint;  // scene units per RSM texel
  return clamp(gradient, vec2(-limit), vec2(limit));
}

void main() {
  vec3 albedo = material_albedo(surface_albedo);
  // The slope-scaled, normal-offset bias (lib/shadow.glsl) in the receiver's RSM texel footprint.
  vec3 n = normalize(world_normal);
  vec3 eye_position = transform_point(light_view, world_position);
  float footprint = shadow_texel_footprint(light_projection, eye_position.z, rsm_size.x);
  vec3 to_light = light_projection[3][3] == 0.0 ? normalize(-eye_position) : vec3(0.0, 0.0, 1.0);
  float cos_theta = dot(transform_direction(light_view, n), to_light);
  vec3 lookup_position = shadow_normal_offset(world_position, n, transpose(mat3(light_view)) * to_light, footprint, shadow);
  shadow_density_settings biased = shadow;
  biased.depth_bias = shadow_slope_bias(cos_theta, footprint, shadow);
  vec2 rsm_coordinate = map_coordinate(light_view_projection, lookup_position, rsm_size);
  float receiver_depth = transform_point(light_view, lookup_position).z;
  vec2 depth_gradient = receiver_depth_gradient(rsm_coordinate, receiver_depth, footprint);
  position_depth = vec4(world_position, transform_point(camera_view, world_position).z);
  albedo_density = vec4(albedo, shadow_density(rsm_coordinate, receiver_depth, depth_gradient, rsm_size, biased));
  normal_out = vec4(normalize(world_normal), 0.0);
}
