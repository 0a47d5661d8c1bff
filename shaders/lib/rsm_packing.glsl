// GLSL twin of include/vplkit/rsm_packing.hpp: one RSM texel in one RGBA32UI texel (light
// eye-space depth bits, the normal as 3 x 16-bit fixed point, the flux as 3 x 16 float bits),
// the position rebuilt on the texel's centre ray. Same operations in the same order.
#ifndef VPLKIT_RSM_PACKING_GLSL
#define VPLKIT_RSM_PACKING_GLSL

#include "lib/rsm_texel.glsl"

struct rsm_unprojection {
  vec2 ray_origin;
  vec2 ray_step;
  int perspective;
};

uint snorm16_bits(float v) { return uint(int(floor(clamp(v, -1.0, 1.0) * 32767.0 + 0.5))) & 0xFFFFu; }
float snorm16_low(uint bits) { return float(int(bits << 16u) >> 16) * (1.0 / 32767.0); }
float snorm16_high(uint bits) { return float(int(bits) >> 16) * (1.0 / 32767.0); }

uint flux16_bits(float value) {
  uint bits = floatBitsToUint(max(value, 0.0)) & 0x7FFFFFFFu;
  return bits >= 0x7F800000u ? (bits == 0x7F800000u ? 0xFEFFu : 0u) : min((bits + 0x4000u) >> 15u, 0xFEFFu);
}
float flux16_low(uint bits) { return uintBitsToFloat((bits << 15u) & 0x7FFF8000u); }
float flux16_high(uint bits) { return uintBitsToFloat((bits >> 1u) & 0x7FFF8000u); }

uvec4 pack_rsm_texel(float eye_depth, vec3 normal, vec3 flux) {
  return uvec4(floatBitsToUint(eye_depth), snorm16_bits(normal.x) | (snorm16_bits(normal.y) << 16u),
               snorm16_bits(normal.z) | (flux16_bits(flux.r) << 16u), flux16_bits(flux.g) | (flux16_bits(flux.b) << 16u));
}

rsm_texel unpack_rsm_texel(uvec4 bits, ivec2 texel, rsm_unprojection light) {
  float z = uintBitsToFloat(bits.x);
  vec2 ray = light.ray_origin + vec2(texel) * light.ray_step;
  vec2 xy = light.perspective != 0 ? ray * -z : ray;
  return rsm_texel(vec3(xy, z), vec3(snorm16_low(bits.y), snorm16_high(bits.y), snorm16_low(bits.z)),
                   vec3(flux16_high(bits.z), flux16_low(bits.w), flux16_high(bits.w)));
}

#endif
