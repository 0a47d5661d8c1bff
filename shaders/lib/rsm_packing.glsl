// GLSL twin of include/vplkit/rsm_packing.hpp: one RSM texel in one RGBA32UI texel (depth bits,
// octahedral normal in 2 x 16 bits, flux in 3 x 21 float bits), and the position rebuilt from
// the texel's centre ray. Same operations in the same order.
#ifndef VPLKIT_RSM_PACKING_GLSL
#define VPLKIT_RSM_PACKING_GLSL

#include "lib/rsm_gather.glsl"
#include "lib/transform.glsl"

struct rsm_unprojection {
  mat4 inverse_light_view;
  float scale;
  int perspective;
  ivec2 size;
};

vec2 octahedral_encode(vec3 n) {
  float l1 = abs(n.x) + abs(n.y) + abs(n.z);
  vec2 p = vec2(n.x, n.y) / l1;
  if (n.z < 0.0) {
    vec2 folded = vec2(1.0) - abs(vec2(p.y, p.x));
    p = vec2(p.x >= 0.0 ? folded.x : -folded.x, p.y >= 0.0 ? folded.y : -folded.y);
  }
  return p;
}

vec3 octahedral_decode(vec2 p) {
  vec3 n = vec3(p.x, p.y, 1.0 - abs(p.x) - abs(p.y));
  if (n.z < 0.0) {
    vec2 folded = vec2(1.0) - abs(vec2(n.y, n.x));
    n.x = n.x >= 0.0 ? folded.x : -folded.x;
    n.y = n.y >= 0.0 ? folded.y : -folded.y;
  }
  return normalize(n);
}

uint quantize_signed_16(float v) { return uint(floor(clamp(v * 0.5 + 0.5, 0.0, 1.0) * 65535.0 + 0.5)); }
float dequantize_signed_16(uint q) { return float(q) / 65535.0 * 2.0 - 1.0; }

uint flux_bits_21(float value) { return (floatBitsToUint(max(value, 0.0)) >> 10u) & 0x1FFFFFu; }
float flux_from_bits_21(uint bits) { return uintBitsToFloat(bits << 10u); }

uvec4 pack_rsm_texel(float eye_depth, vec3 normal, vec3 flux) {
  vec2 oct = octahedral_encode(normal);
  uint r = flux_bits_21(flux.r), g = flux_bits_21(flux.g), b = flux_bits_21(flux.b);
  return uvec4(floatBitsToUint(eye_depth), quantize_signed_16(oct.x) | (quantize_signed_16(oct.y) << 16u), r | (g << 21u),
               (g >> 11u) | (b << 10u));
}

rsm_texel unpack_rsm_texel(uvec4 bits, ivec2 texel, rsm_unprojection light) {
  rsm_texel outv;
  outv.eye_depth = uintBitsToFloat(bits.x);
  outv.normal = octahedral_decode(vec2(dequantize_signed_16(bits.y & 0xFFFFu), dequantize_signed_16(bits.y >> 16u)));
  outv.flux = vec3(flux_from_bits_21(bits.z & 0x1FFFFFu), flux_from_bits_21((bits.z >> 21u) | ((bits.w & 0x3FFu) << 11u)),
                   flux_from_bits_21(bits.w >> 10u));
  vec2 ndc = (vec2(texel) + 0.5) / vec2(light.size) * 2.0 - 1.0;
  vec2 eye_xy = light.perspective != 0 ? ndc * light.scale * -outv.eye_depth : ndc * light.scale;
  outv.position = transform_point(light.inverse_light_view, vec3(eye_xy, outv.eye_depth));
  return outv;
}

#endif
