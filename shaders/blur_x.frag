#version 330 core
// Pass 4a (separable post filter only): the x axis of the bilateral filter at the indirect
// buffer's resolution. Writes [irradiance | camera eye depth] like the indirect buffer, or, with
// VPLKIT_PACKED_BLUR (rgba16f buffers), the y pass's whole tap in one RGBA32UI texel: irradiance,
// depth and the texel's G-buffer normal as halves, so that the y pass (post.frag, or blur_y.frag
// at indirect divisor 2) fetches one texture per tap instead of two (the normal fetch was a fifth
// of the 256^2 frame's post filter, docs/performance.md). The depth and the normal come from
// rgba16f textures, exact as halves; the irradiance is rounded to half as the rgba16f target
// would store it, up to the rounding mode (llvmpipe's targets truncate, its packHalf2x16 rounds
// to nearest: the filtered image moves by about one half ulp, within the RSM pipeline's rgba16f
// parity test).
#ifndef VPLKIT_PACKED_BLUR
#define VPLKIT_PACKED_BLUR 0  // the pipeline defines it; 0 for a program loaded without it
#endif
#if VPLKIT_PACKED_BLUR
#extension GL_ARB_shading_language_packing : require
#endif
#include "lib/bilateral.glsl"

uniform bilateral_settings bilateral;
uniform int indirect_divisor;
uniform ivec2 indirect_size;
uniform ivec2 gbuffer_size;
uniform sampler2D indirect_buffer;
uniform sampler2D gbuffer_normal;

#if VPLKIT_PACKED_BLUR
layout(location = 0) out uvec4 blurred;
#else
layout(location = 0) out vec4 blurred;
#endif

bilateral_tap bilateral_fetch(ivec2 texel) {
  vec4 value = texelFetch(indirect_buffer, texel, 0);
  return bilateral_tap(value.xyz, value.w, texelFetch(gbuffer_normal, min(texel * indirect_divisor, gbuffer_size - 1), 0).xyz);
}

void main() {
  ivec2 texel = ivec2(gl_FragCoord.xy);
  bilateral_tap centre = bilateral_fetch(texel);
  vec3 value = vec3(0.0);
  if (centre.depth < 0.0) value = bilateral_filter_axis(vec2(texel) + 0.5, centre.depth, centre.normal, indirect_size, 0, bilateral);
  else centre = bilateral_tap(vec3(0.0), 0.0, vec3(0.0));  // no surface: all 0, as before
#if VPLKIT_PACKED_BLUR
  blurred = uvec4(packHalf2x16(value.rg), packHalf2x16(vec2(value.b, centre.depth)), packHalf2x16(centre.normal.xy),
                  packHalf2x16(vec2(centre.normal.z, 0.0)));
#else
  blurred = vec4(value, centre.depth);
#endif
}
