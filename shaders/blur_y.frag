#version 330 core
// Pass 4b (separable post filter, indirect divisor 2): the y axis of the bilateral filter for the
// 2 x 2 full-resolution pixels of each indirect texel. Their centres lie in the same texel, so
// they share its column of taps (bilateral_filter_axis_quad): each tap is fetched and unpacked
// once instead of once per pixel, which was most of the post filter's time at 256^2
// (docs/performance.md). Each pixel keeps its own depth, normal and weights: the filtered values
// are post.frag's per-pixel y pass bit for bit. Writes the four pixels' values as three planes,
// red, green and blue, pixel s = (x & 1) + 2 (y & 1) in component s; post.frag picks its own.
// rgba32f planes: the shading reads the same floats it computed before, whatever the format.
#ifndef VPLKIT_PACKED_BLUR
#define VPLKIT_PACKED_BLUR 0  // the pipeline defines it; 0 for a program loaded without it
#endif
#if VPLKIT_PACKED_BLUR
#extension GL_ARB_shading_language_packing : require
#endif
#include "lib/bilateral.glsl"

uniform bilateral_settings bilateral;
uniform int indirect_divisor;  // 2 (the pipeline runs this pass only then)
uniform ivec2 indirect_size;
uniform ivec2 gbuffer_size;
uniform sampler2D gbuffer_position_depth;
uniform sampler2D gbuffer_normal;

#include "blur_taps.glsl"

layout(location = 0) out vec4 filtered_red;
layout(location = 1) out vec4 filtered_green;
layout(location = 2) out vec4 filtered_blue;

void main() {
  ivec2 texel = ivec2(gl_FragCoord.xy);
  // A pixel past an odd-sized image's edge is never read: any centre will do.
  ivec2 pixel_0 = min(2 * texel, gbuffer_size - 1), pixel_1 = min(2 * texel + ivec2(1, 0), gbuffer_size - 1);
  ivec2 pixel_2 = min(2 * texel + ivec2(0, 1), gbuffer_size - 1), pixel_3 = min(2 * texel + ivec2(1, 1), gbuffer_size - 1);
  vec4 depth = vec4(texelFetch(gbuffer_position_depth, pixel_0, 0).w, texelFetch(gbuffer_position_depth, pixel_1, 0).w,
                    texelFetch(gbuffer_position_depth, pixel_2, 0).w, texelFetch(gbuffer_position_depth, pixel_3, 0).w);
  vec3 filtered_0, filtered_1, filtered_2, filtered_3;
  bilateral_filter_axis_quad(texel, depth, texelFetch(gbuffer_normal, pixel_0, 0).xyz, texelFetch(gbuffer_normal, pixel_1, 0).xyz,
                             texelFetch(gbuffer_normal, pixel_2, 0).xyz, texelFetch(gbuffer_normal, pixel_3, 0).xyz, indirect_size, 1,
                             bilateral, filtered_0, filtered_1, filtered_2, filtered_3);
  filtered_red = vec4(filtered_0.r, filtered_1.r, filtered_2.r, filtered_3.r);
  filtered_green = vec4(filtered_0.g, filtered_1.g, filtered_2.g, filtered_3.g);
  filtered_blue = vec4(filtered_0.b, filtered_1.b, filtered_2.b, filtered_3.b);
}
