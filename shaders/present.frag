#version 330 core
// Shows a linear radiance texture on an 8-bit window: clamp, then the sRGB transfer curve (the
// same encoding as the PNG writer, frontend/image/image.cpp).
uniform sampler2D image;
in vec2 texture_coordinate;
layout(location = 0) out vec4 colour;
vec3 linear_to_srgb(vec3 value) {
  value = clamp(value, 0.0, 1.0);
  return mix(12.92 * value, 1.055 * pow(value, vec3(1.0 / 2.4)) - 0.055, step(vec3(0.0031308), value));
}
void main() { colour = vec4(linear_to_srgb(texture(image, texture_coordinate).rgb), 1.0); }
