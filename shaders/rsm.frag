#version 330 core
// Pass 1, RSM generation ([RSMV], Fig. 4.2): each texel's pixel light, its light eye-space
// depth, normal and reflected flux, packed into one RGBA32UI texel (lib/rsm_packing.glsl: the
// position is rebuilt from the depth on the texel's centre ray). VPLKIT_LIGHT_DIRECTIONAL or
// VPLKIT_LIGHT_POINT selects the light (neither: a spot); a point light draws one cube face per
// RSM, a 90-degree perspective view (tan_half_fov = 1).
#ifndef VPLKIT_LIGHT_POINT
#define VPLKIT_LIGHT_POINT 0  // the pipeline defines it; 0 for a program loaded without it
#endif
#include "lib/direct_light.glsl"
#include "lib/rsm_packing.glsl"
#include "lib/transform.glsl"
#include "surface_material.glsl"

uniform mat4 light_view;
uniform ivec2 rsm_size;
#if VPLKIT_LIGHT_DIRECTIONAL
uniform directional_light directional;
uniform float texel_area;
#elif VPLKIT_LIGHT_POINT
uniform point_light point;
#else
uniform spot_light spot;
uniform float tan_half_fov;
#endif

in vec3 world_position;
in vec3 world_normal;
in vec3 surface_albedo;
layout(location = 0) out uvec4 packed_texel;

void main() {
  vec3 albedo = material_albedo(surface_albedo);
  vec3 n = normalize(world_normal);
#if VPLKIT_LIGHT_DIRECTIONAL
  vec3 flux = directional_light_texel_flux(albedo, n, directional, texel_area);
#elif VPLKIT_LIGHT_POINT
  vec2 ndc = gl_FragCoord.xy / vec2(rsm_size) * 2.0 - 1.0;
  vec3 flux = point_light_texel_flux(albedo, world_position, n, point, ndc, rsm_size);
#else
  vec2 ndc = gl_FragCoord.xy / vec2(rsm_size) * 2.0 - 1.0;
  vec3 flux = spot_light_texel_flux(albedo, world_position, n, spot, ndc, tan_half_fov, rsm_size);
#endif
  packed_texel = pack_rsm_texel(transform_point(light_view, world_position).z, transform_direction(light_view, n), flux);
}
