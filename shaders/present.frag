#version 330 core
// Shows one layer of a technique's frame on an 8-bit window with the encoding of the PNG writer
// (frontend/image/image.cpp: exposure, clamp, sRGB transfer curve), nearest texel, so that a
// window of the image's size shows the pixels `vplkit render` writes. `mode`:
//   0: exposure * RGB (to_srgb8)
//   1: |L(image) - L(other)| * exposure as grey (luminance_difference, Fig. 5.1c of [RSMV])
//   2: the red channel as grey (red_as_grey: the Light Wave indirect shadow factor)
uniform sampler2D image;
uniform sampler2D other;
uniform int mode;
uniform float exposure;
uniform ivec2 viewport_size;
layout(location = 0) out vec4 colour;

// As linear_to_srgb in image.cpp: 0 unless > 0 (negative, zero and NaN), at most 1, the linear
// segment up to 0.0031308 inclusive.
vec3 linear_to_srgb(vec3 value) {
  value = mix(vec3(0.0), min(value, vec3(1.0)), greaterThan(value, vec3(0.0)));
  return mix(1.055 * pow(value, vec3(1.0 / 2.4)) - 0.055, 12.92 * value, lessThanEqual(value, vec3(0.0031308)));
}

// Rec. 709, as vplkit::luminance, in its order.
float luminance(vec3 rgb) { return 0.2126 * rgb.r + 0.7152 * rgb.g + 0.0722 * rgb.b; }

void main() {
  ivec2 size = textureSize(image, 0);
  ivec2 texel = clamp(ivec2(gl_FragCoord.xy * vec2(size) / vec2(viewport_size)), ivec2(0), size - 1);
  vec4 value = texelFetch(image, texel, 0);
  vec3 linear;
  if (mode == 1) linear = vec3(abs(luminance(value.rgb) - luminance(texelFetch(other, texel, 0).rgb)) * exposure);
  else if (mode == 2) linear = vec3(value.r);
  else linear = value.rgb * exposure;
  colour = vec4(linear_to_srgb(linear), 1.0);
}
