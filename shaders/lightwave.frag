#version 330 core
// Light Wave main pass, fragment stage ([LW], section 4.3, Eq. 4.9):
//   colour = direct * shadow + indirect * indirect_shadow
// VPLKIT_LIGHTWAVE_MODE: 0 direct only, 1 faked indirect (Eq. 5.2), 2 indirect without shadows,
// 3 accurate indirect shadows (the VPL shadow maps), 4 integrated indirect shadows (lookups
// stepped between every pair of maps, lib/lightwave.glsl).
// VPLKIT_LIGHTWAVE_SHADOW_VARIANT (accurate shadows): 0 importance: each map stands for a group
// of VPLs and shadows the share of this fragment's indirect light that its group, taken as one
// light, brings here; where the map does not cover the fragment (behind its camera, outside its
// frustum or depth range) or its VPL does not light it, that share stays lit; with the flux
// energy the lookup counts by lightwave_group_confidence (the smaller the group looks, the more
// one VPL's view stands for it; the thesis energy, which has no ground truth to weigh that
// against, takes each lookup at face value); it fades to lit towards the map's border
// (lightwave_map_fade, over 5 % of the map). 1 thesis: the plain
// mean of the lookups, outside a map counting as lit. See lightwave_settings.
// VPLKIT_LIGHTWAVE_ENERGY: 0 the thesis's VPL weights (Eq. 4.5), 1 the flux VPLs' irradiance.
// Shadow maps: layer 0 of the depth array is the spot light's, layers 1 .. maps the VPLs'.
// Output 1 is the indirect shadow factor (red), output 2 the indirect radiance added to the
// direct light (after the factor), for tests and reports, output 3 the indirect irradiance: what
// `vplkit render` writes to -indirect.pfm for every family (see main()).
// VPLKIT_LIGHTWAVE_INDIRECT_BUFFER (the flux energy): the indirect light comes from the screen
// buffer lightwave_indirect.frag filled at this pixel from the receivers, not from the vertices.
#include "lib/direct_light.glsl"
#include "lib/lightwave.glsl"
#define VPLKIT_SHADOW_BIAS_ONLY
#include "lib/shadow.glsl"
#include "surface_material.glsl"

// VPLKIT_MAX_SHADOW_MAPS comes from lightwave_max_shadow_maps (lightwave_pipeline.hpp).
#ifndef VPLKIT_MAX_SHADOW_MAPS
#error "VPLKIT_MAX_SHADOW_MAPS must be defined by the pipeline (lightwave_max_shadow_maps)"
#endif

uniform spot_light light;
uniform irradiance_settings irradiance;
uniform sampler2DArrayShadow shadow_maps;
uniform mat4 shadow_matrix[VPLKIT_MAX_SHADOW_MAPS + 1];
uniform vec4 caster_position[VPLKIT_MAX_SHADOW_MAPS];         // map i + 1's VPL: position | attenuation (thesis) or radius (flux)
uniform vec4 caster_normal[VPLKIT_MAX_SHADOW_MAPS];           // its normal | -
uniform vec4 group_position_radius[VPLKIT_MAX_SHADOW_MAPS];   // its group as one light (importance)
uniform vec4 group_normal_power[VPLKIT_MAX_SHADOW_MAPS];
uniform int indirect_maps;
uniform int integrated_steps;
uniform float faked_multiplier;
uniform int shadow_map_width;
uniform shadow_density_settings shadow_bias;  // its normal offset and slope-scaled bias (lib/shadow.glsl)

in vec3 world_position;
in vec3 world_normal;
in vec3 surface_albedo;
in vec3 vertex_indirect;
#if VPLKIT_LIGHTWAVE_INDIRECT_BUFFER
uniform sampler2D indirect_buffer;
#endif
layout(location = 0) out vec4 colour;
layout(location = 1) out vec4 indirect_shadow;
layout(location = 2) out vec4 indirect_out;
layout(location = 3) out vec4 indirect_irradiance_out;
layout(location = 4) out vec4 direct_irradiance_out;  // render's -direct.pfm: the shadowed direct irradiance

// (x, y, depth) in [0, 1] and whether the point is inside map `layer`'s frustum (lib/lightwave.glsl),
// looked up from the receiver moved along its normal and towards the map's origin (the light,
// or the VPL of map i > 0) by lib/shadow.glsl's normal offset and slope-scaled bias, in the
// receiver's texel footprint in that map. The map's view is rigid, so the projection's x scale
// is the length of the matrix's first row.
vec4 map_coordinate(int layer) {
  mat4 m = shadow_matrix[layer];
  vec3 origin = layer == 0 ? light.position : caster_position[max(layer - 1, 0)].xyz;
  vec3 n = normalize(world_normal);
  vec3 to_origin = normalize(origin - world_position);
  vec4 clip = m * vec4(world_position, 1.0);
  float footprint = 2.0 * abs(clip.w) / (length(vec3(m[0][0], m[1][0], m[2][0])) * float(shadow_map_width));
  float slope_bias = shadow_slope_bias(dot(n, to_origin), footprint, shadow_bias);
  vec3 lookup = shadow_normal_offset(world_position, n, to_origin, footprint, shadow_bias) + to_origin * slope_bias;
  return lightwave_map_coordinate(m * vec4(lookup, 1.0));
}

// 1 = lit; a further depth bias is in the raster state.
float shadow_lookup(vec3 coordinate, int layer) { return texture(shadow_maps, vec4(coordinate.xy, float(layer), coordinate.z)); }

// The light of caster i's group, as one light, at (x, n), and whether caster i's own VPL lights it.
#if VPLKIT_LIGHTWAVE_ENERGY == 1
float group_light(int i, vec3 x, vec3 n) {
  vec4 a = group_position_radius[i], b = group_normal_power[i];
  return lightwave_bounce_weight(x, n, lightwave_flux_vpl(a.xyz, b.xyz, vec3(b.w), a.w), irradiance.min_distance);
}
bool caster_lights(int i, vec3 x, vec3 n) { return lightwave_flux_vpl_faces(x, n, caster_position[i].xyz, caster_normal[i].xyz); }
#else
float group_light(int i, vec3 x, vec3 n) {
  vec4 a = group_position_radius[i], b = group_normal_power[i];
  return lightwave_vpl_weight(x, n, lightwave_vpl(a.xyz, b.xyz, 0.0)) * b.w;
}
bool caster_lights(int i, vec3 x, vec3 n) {
  vec4 a = caster_position[i];
  return lightwave_vpl_weight(x, n, lightwave_vpl(a.xyz, caster_normal[i].xyz, a.w)) > 0.0;
}
#endif

void main() {
  // The base-colour texture at this fragment multiplies the vertex's albedo in the direct light
  // and in the vertex's indirect light (Eq. 4.5 is linear in the receiver's albedo).
  vec3 texture_colour = material_albedo(vec3(1.0));
#if VPLKIT_LIGHTWAVE_INDIRECT_BUFFER
  vec3 textured_indirect = texelFetch(indirect_buffer, ivec2(gl_FragCoord.xy), 0).rgb * texture_colour;
#else
  vec3 textured_indirect = vertex_indirect * texture_colour;
#endif
  vec3 n = normalize(world_normal);
  vec3 direct = surface_albedo * texture_colour * 0.318309886183790671538 * spot_light_irradiance(world_position, n, light, irradiance);
  // Outside the light's frustum there is no direct light to shadow.
  vec4 light_coordinate = map_coordinate(0);
  float shadow = light_coordinate.w > 0.5 ? shadow_lookup(light_coordinate.xyz, 0) : 1.0;
  float factor = 1.0;
  vec3 indirect = vec3(0.0);
#if VPLKIT_LIGHTWAVE_MODE == 0
  colour = vec4(direct * shadow, 1.0);
#elif VPLKIT_LIGHTWAVE_MODE == 1
  colour = vec4(lightwave_faked_indirect(direct, shadow, faked_multiplier), 1.0);
  indirect = colour.rgb - direct * shadow;
#elif VPLKIT_LIGHTWAVE_MODE == 2
  indirect = textured_indirect;
  colour = vec4(direct * shadow + indirect, 1.0);
#elif VPLKIT_LIGHTWAVE_MODE == 3
#if VPLKIT_LIGHTWAVE_SHADOW_VARIANT == 0
  float lit = 0.0, total = 0.0;
  for (int i = 1; i <= indirect_maps; ++i) {
    float share = group_light(i - 1, world_position, n);
    if (!(share > 0.0)) continue;
    total += share;
    vec4 coordinate = map_coordinate(i);
#if VPLKIT_LIGHTWAVE_ENERGY == 1
    float trust = lightwave_group_confidence(world_position, group_position_radius[i - 1].xyz, group_position_radius[i - 1].w);
#else
    float trust = 1.0;  // the thesis's VPLs: each lookup at face value, as its tables measure them
#endif
    float counts = caster_lights(i - 1, world_position, n) ? trust * lightwave_map_fade(coordinate, 0.05) : 0.0;
    lit += counts > 0.0 ? share * mix(1.0, shadow_lookup(coordinate.xyz, i), counts) : share;
  }
  factor = total > 0.0 ? lit / total : 1.0;
#else  // thesis variant
  float lit = 0.0;
  for (int i = 1; i <= indirect_maps; ++i) {
    vec4 coordinate = map_coordinate(i);
    lit += coordinate.w > 0.5 ? shadow_lookup(coordinate.xyz, i) : 1.0;
  }
  factor = indirect_maps > 0 ? lit / float(indirect_maps) : 1.0;
#endif
  indirect = textured_indirect * factor;
  colour = vec4(direct * shadow + indirect, 1.0);
#else
  // An endpoint behind or outside its map does not vote; the in-between lookups run only
  // between two valid endpoints (their line then stays inside both maps' [0, 1] cube).
  float lit = 0.0;
  int lookups = 0;
  for (int a = 1; a <= indirect_maps; ++a) {
    vec4 coordinate_a = map_coordinate(a);
    for (int b = a + 1; b <= indirect_maps; ++b) {
      vec4 coordinate_b = map_coordinate(b);
      for (int lookup = 0; lookup <= integrated_steps + 1; ++lookup) {
        bool votes = lookup == 0 ? coordinate_a.w > 0.5
                                 : lookup == integrated_steps + 1 ? coordinate_b.w > 0.5 : coordinate_a.w > 0.5 && coordinate_b.w > 0.5;
        if (!votes) continue;
        vec4 step_point = lightwave_integrated_step(coordinate_a.xyz, coordinate_b.xyz, lookup, integrated_steps);
        lit += shadow_lookup(step_point.xyz, step_point.w < 0.5 ? a : b);
        ++lookups;
      }
    }
  }
  factor = lookups > 0 ? lit / float(lookups) : 1.0;
  indirect = textured_indirect * factor;
  colour = vec4(direct * shadow + indirect, 1.0);
#endif
  indirect_shadow = vec4(factor, 0.0, 0.0, 1.0);
  indirect_out = vec4(indirect, 1.0);
  // Before the albedo, as -indirect.pfm: the irradiance the spot brings, after its shadow map.
  direct_irradiance_out = vec4(spot_light_irradiance(world_position, n, light, irradiance) * shadow, 1.0);
  // -indirect.pfm is the indirect irradiance for every family: the quantity the RSM's gather and
  // final gathering compute and `vplkit reference` writes. Light Wave sums the radiance its
  // surfaces reflect (Eq. 4.5 and the flux VPLs include the receiver's albedo); the irradiance is
  // that radiance over the surface's diffuse reflectance albedo / pi, 0 where it reflects none.
  vec3 reflectance = surface_albedo * texture_colour * 0.318309886183790671538;
  indirect_irradiance_out = vec4(reflectance.r > 0.0 ? indirect.r / reflectance.r : 0.0, reflectance.g > 0.0 ? indirect.g / reflectance.g : 0.0,
                                 reflectance.b > 0.0 ? indirect.b / reflectance.b : 0.0, 1.0);
}
