// The separable filter's y pass reads its taps from the x pass's output (blur_x.frag): with
// VPLKIT_PACKED_BLUR one RGBA32UI texel per tap (irradiance, depth and the texel's G-buffer
// normal as halves), else [irradiance | depth] and the normal from the G-buffer. Included by the
// y pass, post.frag (any indirect divisor) and blur_y.frag (divisor 2), which declare
// gbuffer_normal, indirect_divisor and gbuffer_size, and include lib/bilateral.glsl first.
#ifndef VPLKIT_BLUR_TAPS_GLSL
#define VPLKIT_BLUR_TAPS_GLSL

#ifndef VPLKIT_PACKED_BLUR
#define VPLKIT_PACKED_BLUR 0  // the pipeline defines it; 0 for a program loaded without it
#endif

#if VPLKIT_PACKED_BLUR
uniform usampler2D indirect_buffer;
#else
uniform sampler2D indirect_buffer;
#endif

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

#endif
