#version 330 core
// Pass 1, RSM generation ([RSMV], Fig. 4.2): [world position | light eye depth],
// [world normal | -], [reflected flux | -]. VPLKIT_LIGHT_DIRECTIONAL selects the light.
#include "lib/direct_light.glsl"
#include "lib/transform.glsl"

uniform mat4 light_view;
uniform ivec2 rsm_size;
#if VPLKIT_LIGHT_DIRECTIONAL
uniform directional_light directional;
uniform float texel_area;
#else
uniform spot_light spot;
uniform float tan_half_fov;
#endif

in vec3 world_position;
in vec3 world_normal;
in vec3 surface_albedo;
layout(location = 0) out vec4 position_depth;
layout(location = 1) out vec4 normal_out;
layout(location = 2) out vec4 flux_out;

void main() {
  vec3 n = normalize(world_normal);
  position_depth = vec4(world_position, transform_point(light_view, world_position).z);
  normal_out = vec4(n, 0.0);
#if VPLKIT_LIGHT_DIRECTIONAL
  flux_out = vec4(directional_light_texel_flux(surface_albedo, n, directional, texel_area), 0.0);
#else
  vec2 ndc = gl_FragCoord.xy / vec2(rsm_size) * 2.0 - 1.0;
  flux_out = vec4(spot_light_texel_flux(surface_albedo, world_position, n, spot, ndc, tan_half_fov, rsm_size), 0.0);
#endif
}
