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
// Shadow maps: the first light_layers layers of the depth array are the light's (a spot's frustum
// or a sun's orthographic window: one; a point light's six cube faces, lib/cube_map.glsl, the face
// a receiver's direction from the light falls in shadowing it), the next ones the VPLs'.
// VPLKIT_LIGHT_POINT / VPLKIT_LIGHT_DIRECTIONAL: the light's kind (else a spot).
// Output 1 is the indirect shadow factor (red), output 2 the indirect radiance added to the
// direct light (after the factor), for tests and reports, output 3 the indirect irradiance: what
// `vplkit render` writes to -indirect.pfm for every family (see main()), output 4 the light's
// direct irradiance after its shadow map (-direct.pfm).
// VPLKIT_LIGHTWAVE_INDIRECT_BUFFER (the flux energy): the indirect light comes from the screen
// buffer lightwave_indirect.frag filled at this pixel from the receivers, not from the vertices.
#ifndef VPLKIT_LIGHT_POINT
#define VPLKIT_LIGHT_POINT 0  // the pipeline defines it; 0 for a program loaded without it
#endif
#ifndef VPLKIT_LIGHT_DIRECTIONAL
#define VPLKIT_LIGHT_DIRECTIONAL 0
#endif
#include "lib/cube_map.glsl"
#include "lib/direct_light.glsl"
#include "lib/lightwave.glsl"
#define VPLKIT_SHADOW_BIAS_ONLY
#include "lib/shadow.glsl"
#include "surface_material.glsl"

// VPLKIT_MAX_SHADOW_MAPS comes from lightwave_max_shadow_maps (lightwave_pipeline.hpp).
#ifndef VPLKIT_MAX_SHADOW_MAPS
#error "VPLKIT_MAX_SHADOW_MAPS must be defined by the pipeline (lightwave_max_shadow_maps)"
#endif

#if VPLKIT_LIGHT_POINT
uniform point_light light;
#elif VPLKIT_LIGHT_DIRECTIONAL
uniform directional_light light;
#else
uniform spot_light light;
#endif
uniform irradiance_settings irradiance;
uniform sampler2DArrayShadow shadow_maps;
uniform mat4 shadow_matrix[VPLKIT_MAX_SHADOW_MAPS + 6];
uniform int light_layers;     // the light's own maps: 1, or a point light's 6 faces
uniform int light_map_width;  // the texels across the light's own frusta
uniform vec4 caster_position[VPLKIT_MAX_SHADOW_MAPS];         // map i + 1's VPL: position | attenuation (thesis) or radius (flux)
uniform vec4 caster_normal[VPLKIT_MAX_SHADOW_MAPS];           // its normal | -
uniform vec4 group_position_radius[VPLKIT_MAX_SHADOW_MAPS];   // its group as one light (importance)
uniform vec4 group_normal_power[VPLKIT_MAX_SHADOW_MAPS];
uniform int indirect_maps;
uniform int integrated_steps;
// In-between lookups only between maps whose VPLs' normals agree this far (-2: every pair; a point
// light's maps, placed by importance over the whole room: lightwave_integrated_pair_cos).
uniform float integrated_pair_cos;
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

// The receiver moved along its normal and towards a map's origin (`to_origin`: towards the light,
// or the VPL of a VPL's map) by lib/shadow.glsl's normal offset and slope-scaled bias, in the
// receiver's texel footprint in map `m` of `map_width` texels across. The map's view is rigid, so
// the projection's x scale is the length of the matrix's first row (1 / half-width for a sun's
// orthographic window, whose clip w is 1).
vec3 biased_lookup(mat4 m, vec3 to_origin, int map_width) {
  vec3 n = normalize(world_normal);
  vec4 clip = m * vec4(world_position, 1.0);
  float footprint = 2.0 * abs(clip.w) / (length(vec3(m[0][0], m[1][0], m[2][0])) * float(map_width));
  float slope_bias = shadow_slope_bias(dot(n, to_origin), footprint, shadow_bias);
  return shadow_normal_offset(world_position, n, to_origin, footprint, shadow_bias) + to_origin * slope_bias;
}

// VPL map i (1 .. indirect_maps) is layer light_layers - 1 + i of the array.
int vpl_layer(int i) { return light_layers - 1 + i; }

// (x, y, depth) in [0, 1] and whether the receiver is inside VPL map i's frustum (lib/lightwave.glsl).
vec4 map_coordinate(int i) {
  mat4 m = shadow_matrix[vpl_layer(i)];
  vec3 to_origin = normalize(caster_position[i - 1].xyz - world_position);
  return lightwave_map_coordinate(m * vec4(biased_lookup(m, to_origin, shadow_map_width), 1.0));
}

// 1 = lit; a further depth bias is in the raster state.
float shadow_lookup(vec3 coordinate, int layer) { return texture(shadow_maps, vec4(coordinate.xy, float(layer), coordinate.z)); }

// The light's own shadow at the receiver; outside its frustum there is no direct light to shadow.
float light_shadow() {
#if VPLKIT_LIGHT_DIRECTIONAL
  int layer = 0;
  vec3 lookup = biased_lookup(shadow_matrix[0], -light.direction, light_map_width);
#elif VPLKIT_LIGHT_POINT
  // The face the receiver's direction falls in, then the face its biased lookup point falls in
  // (the offset may carry a receiver by a seam over to the next face, whose frustum then holds it).
  vec3 to_light = normalize(light.position - world_position);
  int layer = cube_face_of(world_position - light.position);
  vec3 lookup = biased_lookup(shadow_matrix[layer], to_light, light_map_width);
  layer = cube_face_of(lookup - light.position);
#else
  int layer = 0;
  vec3 lookup = biased_lookup(shadow_matrix[0], normalize(light.position - world_position), light_map_width);
#endif
  vec4 coordinate = lightwave_map_coordinate(shadow_matrix[layer] * vec4(lookup, 1.0));
  return coordinate.w > 0.5 ? shadow_lookup(coordinate.xyz, layer) : 1.0;
}

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
#if VPLKIT_LIGHT_POINT
  vec3 light_irradiance = point_light_irradiance(world_position, n, light, irradiance);
#elif VPLKIT_LIGHT_DIRECTIONAL
  vec3 light_irradiance = directional_light_irradiance(n, light);
#else
  vec3 light_irradiance = spot_light_irradiance(world_position, n, light, irradiance);
#endif
  vec3 direct = surface_albedo * texture_colour * 0.318309886183790671538 * light_irradiance;
  float shadow = light_shadow();
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
    lit += counts > 0.0 ? share * mix(1.0, shadow_lookup(coordinate.xyz, vpl_layer(i)), counts) : share;
  }
  factor = total > 0.0 ? lit / total : 1.0;
#else  // thesis variant
  float lit = 0.0;
  for (int i = 1; i <= indirect_maps; ++i) {
    vec4 coordinate = map_coordinate(i);
    lit += coordinate.w > 0.5 ? shadow_lookup(coordinate.xyz, vpl_layer(i)) : 1.0;
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
      bool between = dot(caster_normal[a - 1].xyz, caster_normal[b - 1].xyz) >= integrated_pair_cos;
      for (int lookup = 0; lookup <= integrated_steps + 1; ++lookup) {
        bool votes = lookup == 0 ? coordinate_a.w > 0.5
                                 : lookup == integrated_steps + 1 ? coordinate_b.w > 0.5 : between && coordinate_a.w > 0.5 && coordinate_b.w > 0.5;
        if (!votes) continue;
        vec4 step_point = lightwave_integrated_step(coordinate_a.xyz, coordinate_b.xyz, lookup, integrated_steps);
        lit += shadow_lookup(step_point.xyz, vpl_layer(step_point.w < 0.5 ? a : b));
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
  // Before the albedo, as -indirect.pfm: the irradiance the light brings, after its shadow map.
  direct_irradiance_out = vec4(light_irradiance * shadow, 1.0);
  // -indirect.pfm is the indirect irradiance for every family: the quantity the RSM's gather and
  // final gathering compute and `vplkit reference` writes. Light Wave sums the radiance its
  // surfaces reflect (Eq. 4.5 and the flux VPLs include the receiver's albedo); the irradiance is
  // that radiance over the surface's diffuse reflectance albedo / pi, 0 where it reflects none.
  vec3 reflectance = surface_albedo * texture_colour * 0.318309886183790671538;
  indirect_irradiance_out = vec4(reflectance.r > 0.0 ? indirect.r / reflectance.r : 0.0, reflectance.g > 0.0 ? indirect.g / reflectance.g : 0.0,
                                 reflectance.b > 0.0 ? indirect.b / reflectance.b : 0.0, 1.0);
}
