#version 330 core
// Pass 4a (separable post filter only): the x axis of the bilateral filter at the indirect
// buffer's resolution. Writes [irradiance | camera eye depth] like the indirect buffer.
#include "lib/bilateral.glsl"

uniform bilateral_settings bilateral;
uniform int indirect_divisor;
uniform ivec2 indirect_size;
uniform ivec2 gbuffer_size;
uniform sampler2D indirect_buffer;
uniform sampler2D gbuffer_normal;

layout(location = 0) out vec4 blurred;

bilateral_tap bilateral_fetch(ivec2 texel) {
  vec4 value = texelFetch(indirect_buffer, texel, 0);
  return bilateral_tap(value.xyz, value.w, texelFetch(gbuffer_normal, min(texel * indirect_divisor, gbuffer_size - 1), 0).xyz);
}

void main() {
  ivec2 texel = ivec2(gl_FragCoord.xy);
  bilateral_tap centre = bilateral_fetch(texel);
  if (!(centre.depth < 0.0)) {
    blurred = vec4(0.0);
    return;
  }
  blurred = vec4(bilateral_filter_axis(vec2(texel) + 0.5, centre.depth, centre.normal, indirect_size, 0, bilateral),
                 centre.depth);
}
