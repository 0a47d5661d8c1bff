#version 330 core
// Light Wave main pass, fragment stage (paper 003, section 4.3, Eq. 4.9):
//   colour = direct * shadow + indirect * indirect_shadow
// VPLKIT_LIGHTWAVE_MODE: 0 direct only, 1 faked indirect (Eq. 5.2), 2 indirect without shadows,
// 3 accurate indirect shadows (mean of the VPL shadow maps), 4 integrated indirect shadows
// (lookups stepped between every pair of maps, lib/lightwave.glsl).
// Shadow maps: layer 0 of the depth array is the spot light's, layers 1 .. maps the VPLs'.
#include "lib/direct_light.glsl"
#include "lib/lightwave.glsl"

#define VPLKIT_MAX_SHADOW_MAPS 64

uniform spot_light light;
uniform irradiance_settings irradiance;
uniform sampler2DArrayShadow shadow_maps;
uniform mat4 shadow_matrix[VPLKIT_MAX_SHADOW_MAPS + 1];
uniform int indirect_maps;
uniform int integrated_steps;
uniform float faked_multiplier;

in vec3 world_position;
in vec3 world_normal;
in vec3 surface_albedo;
in vec3 vertex_indirect;
layout(location = 0) out vec4 colour;

// Map coordinates in [0, 1] with the compared depth; the depth bias is in the raster state.
vec3 shadow_coordinate(int layer) {
  vec4 clip = shadow_matrix[layer] * vec4(world_position, 1.0);
  return clip.xyz / clip.w * 0.5 + 0.5;
}

// 1 = lit. Outside a map's frustum the map knows nothing: lit.
float shadow_lookup(vec3 coordinate, int layer) {
  if (any(lessThan(coordinate, vec3(0.0))) || any(greaterThan(coordinate, vec3(1.0)))) return 1.0;
  return texture(shadow_maps, vec4(coordinate.xy, float(layer), coordinate.z));
}

void main() {
  vec3 n = normalize(world_normal);
  vec3 direct = surface_albedo * 0.318309886183790671538 * spot_light_irradiance(world_position, n, light, irradiance);
  float shadow = shadow_lookup(shadow_coordinate(0), 0);
#if VPLKIT_LIGHTWAVE_MODE == 0
  colour = vec4(direct * shadow, 1.0);
#elif VPLKIT_LIGHTWAVE_MODE == 1
  colour = vec4(lightwave_faked_indirect(direct, shadow, faked_multiplier), 1.0);
#elif VPLKIT_LIGHTWAVE_MODE == 2
  colour = vec4(direct * shadow + vertex_indirect, 1.0);
#elif VPLKIT_LIGHTWAVE_MODE == 3
  float lit = 0.0;
  for (int i = 1; i <= indirect_maps; ++i) lit += shadow_lookup(shadow_coordinate(i), i);
  colour = vec4(direct * shadow + vertex_indirect * (lit / float(max(indirect_maps, 1))), 1.0);
#else
  float lit = 0.0;
  int lookups = 0;
  for (int a = 1; a <= indirect_maps; ++a) {
    vec3 coordinate_a = shadow_coordinate(a);
    for (int b = a + 1; b <= indirect_maps; ++b) {
      vec3 coordinate_b = shadow_coordinate(b);
      for (int lookup = 0; lookup <= integrated_steps + 1; ++lookup) {
        vec4 step_point = lightwave_integrated_step(coordinate_a, coordinate_b, lookup, integrated_steps);
        lit += shadow_lookup(step_point.xyz, step_point.w < 0.5 ? a : b);
        ++lookups;
      }
    }
  }
  colour = vec4(direct * shadow + vertex_indirect * (lit / float(max(lookups, 1))), 1.0);
#endif
}
