#version 330 core
// Pass 4, post processing ([RSMV], section 4.5): the indirect buffer upsampled and blurred
// by the bilateral filter (full 2D, or the y axis over pass 4a's output when VPLKIT_SEPARABLE),
// then direct light from the G-buffer (albedo, shadow density) plus indirect:
//   radiance = albedo / pi * (E_direct * shadow_density + E_indirect).
// Writes [radiance | 1], [filtered indirect irradiance | 1] and [shadowed direct irradiance | 1]
// (render's -direct.pfm).
// VPLKIT_PACKED_BLUR: the y pass reads pass 4a's packed taps (blur_x.frag), one fetch per tap.
#ifndef VPLKIT_PACKED_BLUR
#define VPLKIT_PACKED_BLUR 0  // the pipeline defines it; 0 for a program loaded without it
#endif
#if VPLKIT_PACKED_BLUR
#extension GL_ARB_shading_language_packing : require
#endif
#ifndef VPLKIT_LIGHT_POINT
#define VPLKIT_LIGHT_POINT 0  // the pipeline defines it; 0 for a program loaded without it
#endif
#include "lib/bilateral.glsl"
#include "lib/cube_map.glsl"
#include "lib/direct_light.glsl"
#include "lib/shading.glsl"

uniform bilateral_settings bilateral;
uniform irradiance_settings irradiance;
uniform int indirect_divisor;
uniform ivec2 indirect_size;
uniform ivec2 gbuffer_size;
#if VPLKIT_PACKED_BLUR
uniform usampler2D indirect_buffer;
#else
uniform sampler2D indirect_buffer;
#endif
uniform sampler2D gbuffer_position_depth;
uniform sampler2D gbuffer_albedo_density;
uniform sampler2D gbuffer_normal;
#if VPLKIT_LIGHT_DIRECTIONAL
uniform directional_light directional;
#elif VPLKIT_LIGHT_POINT
uniform point_light point;
uniform int light_face;  // the cube face this pass draws (lib/cube_map.glsl)
#else
uniform spot_light spot;
#endif

layout(location = 0) out vec4 radiance;
layout(location = 1) out vec4 indirect_out;
layout(location = 2) out vec4 direct_out;

bilateral_tap bilateral_fetch(ivec2 texel) {
#if VPLKIT_PACKED_BLUR
  uvec4 words = texelFetch(indirect_buffer, texel, 0);
  vec2 blue_depth = unpackHalf2x16(words.y);
  return bilateral_tap(vec3(unpackHalf2x16(words.x), blue_depth.x), blue_depth.y, vec3(unpackHalf2x16(words.z), unpackHalf2x16(words.w).x));
#else
  vec4 value = texelFetch(indirect_buffer, texel, 0);
  return bilateral_tap(value.xyz, value.w, texelFetch(gbuffer_normal, min(texel * indirect_divisor, gbuffer_size - 1), 0).xyz);
#endif
}

void main() {
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  vec4 position_depth = texelFetch(gbuffer_position_depth, pixel, 0);
  if (!(position_depth.w < 0.0)) {
    radiance = vec4(0.0, 0.0, 0.0, 1.0);
    indirect_out = vec4(0.0, 0.0, 0.0, 1.0);
    direct_out = vec4(0.0, 0.0, 0.0, 1.0);
    return;
  }
  vec4 albedo_density = texelFetch(gbuffer_albedo_density, pixel, 0);
  vec3 n = texelFetch(gbuffer_normal, pixel, 0).xyz;
  vec3 indirect_irradiance = vec3(0.0);
#if VPLKIT_INDIRECT
  vec2 centre = (vec2(pixel) + 0.5) / float(indirect_divisor);
#if VPLKIT_SEPARABLE
  indirect_irradiance = bilateral_filter_axis(centre, position_depth.w, n, indirect_size, 1, bilateral);
#else
  indirect_irradiance = bilateral_filter(centre, position_depth.w, n, indirect_size, bilateral);
#endif
#endif
#if VPLKIT_LIGHT_DIRECTIONAL
  vec3 direct = directional_light_irradiance(n, directional);
#elif VPLKIT_LIGHT_POINT
  // Each receiver takes a point light's direct light from the one face its direction falls in:
  // the face whose RSM depth shadowed it in the G-buffer of this pass.
  vec3 direct = cube_face_of(position_depth.xyz - point.position) == light_face ? point_light_irradiance(position_depth.xyz, n, point, irradiance)
                                                                               : vec3(0.0);
#else
  vec3 direct = spot_light_irradiance(position_depth.xyz, n, spot, irradiance);
#endif
  radiance = vec4(diffuse_radiance(albedo_density.rgb, direct, albedo_density.a, indirect_irradiance), 1.0);
  indirect_out = vec4(indirect_irradiance, 1.0);
  direct_out = vec4(direct * albedo_density.a, 1.0);
}
