#version 330 core
// Pass 4, post processing ([RSMV], section 4.5): the indirect buffer upsampled and blurred
// by the bilateral filter (full 2D, or the y axis over pass 4a's output when VPLKIT_SEPARABLE),
// then direct light from the G-buffer (albedo, shadow density) plus indirect:
//   radiance = albedo / pi * (E_direct * shadow_density + E_indirect).
// Writes [radiance | 1], [filtered indirect irradiance | 1] and [shadowed direct irradiance | 1]
// (render's -direct.pfm).
// VPLKIT_PACKED_BLUR: the y pass reads pass 4a's packed taps (blur_x.frag), one fetch per tap.
// VPLKIT_QUAD_BLUR (separable, indirect divisor 2): the y pass ran in pass 4b (blur_y.frag), which
// filtered the 2 x 2 pixels of each indirect texel at once; this pass reads its pixel's value.
#ifndef VPLKIT_PACKED_BLUR
#define VPLKIT_PACKED_BLUR 0  // the pipeline defines it; 0 for a program loaded without it
#endif
#ifndef VPLKIT_QUAD_BLUR
#define VPLKIT_QUAD_BLUR 0  // the pipeline defines it; 0 for a program loaded without it
#endif
#if VPLKIT_PACKED_BLUR && !VPLKIT_QUAD_BLUR
#extension GL_ARB_shading_language_packing : require
#endif
#ifndef VPLKIT_LIGHT_POINT
#define VPLKIT_LIGHT_POINT 0  // the pipeline defines it; 0 for a program loaded without it
#endif
#if !VPLKIT_QUAD_BLUR
#include "lib/bilateral.glsl"  // with the quad y pass this pass filters nothing
#endif
#include "lib/cube_map.glsl"
#include "lib/direct_light.glsl"
#include "lib/shading.glsl"

#if !VPLKIT_QUAD_BLUR
uniform bilateral_settings bilateral;
#endif
uniform irradiance_settings irradiance;
uniform int indirect_divisor;
uniform ivec2 indirect_size;
uniform ivec2 gbuffer_size;
uniform sampler2D gbuffer_position_depth;
uniform sampler2D gbuffer_albedo_density;
uniform sampler2D gbuffer_normal;
#if VPLKIT_QUAD_BLUR
uniform sampler2D filtered_red;  // blur_y.frag's planes: component (x & 1) + 2 (y & 1) of texel pixel / 2
uniform sampler2D filtered_green;
uniform sampler2D filtered_blue;
#else
#include "blur_taps.glsl"
#endif
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
#if VPLKIT_QUAD_BLUR
  ivec2 texel = pixel / 2;
  int s = (pixel.x & 1) + 2 * (pixel.y & 1);
  indirect_irradiance = vec3(texelFetch(filtered_red, texel, 0)[s], texelFetch(filtered_green, texel, 0)[s], texelFetch(filtered_blue, texel, 0)[s]);
#elif VPLKIT_SEPARABLE
  indirect_irradiance = bilateral_filter_axis((vec2(pixel) + 0.5) / float(indirect_divisor), position_depth.w, n, indirect_size, 1, bilateral);
#else
  indirect_irradiance = bilateral_filter((vec2(pixel) + 0.5) / float(indirect_divisor), position_depth.w, n, indirect_size, bilateral);
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
