// One RSM texel in one 128-bit texel (RGBA32UI), so that a gather can read one texture per pixel
// light instead of three ([RSMV] stores position, normal and flux in three RGBA16F targets,
// Fig. 4.2). The RSM pipeline does not use it yet: on llvmpipe, decoding a world-space position
// per sample (the centre ray and a 4x3 transform) cost more than the two fetches it saved. Every field is encoded with integer and float operations that GLSL 3.30 has and
// that round the same way on both sides, so the C++ twin decodes the same bits:
//
//   x: the light eye-space depth, the float's own bits (exact);
//   y: the normal, octahedral (Cigolle et al. 2014), each coordinate in 16 bits,
//      q = floor((v * 0.5 + 0.5) * 65535 + 0.5);
//   z, w: the flux, each channel's float bits 30..10 (8 exponent and 13 mantissa bits, the sign
//      dropped: flux is >= 0), 3 x 21 bits: relative error < 2^-13, truncated towards 0.
//
// The position is not stored: it lies on the texel's centre ray at the stored depth, so it is
// reconstructed from the texel and the light's projection (perspective for a spot light: eye.xy =
// ndc * tan_half_fov * -depth; orthographic for a directional light: eye.xy = ndc * half_extent)
// and the inverse of the light's view. An empty texel (depth >= 0) decodes to depth 0, flux 0.
//
// GLSL twin: shaders/lib/rsm_packing.glsl.
#pragma once

#include <cmath>
#include <cstdint>
#include <cstring>

#include <glm/glm.hpp>

#include <vplkit/rsm_gather.hpp>
#include <vplkit/transform.hpp>

namespace vplkit {

/// How a texel's centre ray leaves the light: what unpack_rsm_texel needs to rebuild positions.
template <typename T>
struct rsm_unprojection {
  glm::mat<4, 4, T> inverse_light_view{1};  ///< light eye space -> world
  T scale = T(1);            ///< tan(half field of view) (perspective) or half the extent (orthographic)
  int perspective = 1;       ///< 1: spot light (perspective RSM), 0: directional (orthographic)
  glm::ivec2 size{1};        ///< RSM size in texels
};

inline std::uint32_t float_bits(float value) {
  std::uint32_t bits;
  std::memcpy(&bits, &value, sizeof bits);
  return bits;
}

inline float float_from_bits(std::uint32_t bits) {
  float value;
  std::memcpy(&value, &bits, sizeof value);
  return value;
}

/// A unit vector on the octahedron, unfolded to [-1, 1]^2.
inline glm::vec2 octahedral_encode(const glm::vec3& n) {
  const float l1 = std::fabs(n.x) + std::fabs(n.y) + std::fabs(n.z);
  glm::vec2 p = glm::vec2(n.x, n.y) / l1;
  if (n.z < 0.0f) {
    const glm::vec2 folded = glm::vec2(1.0f) - glm::abs(glm::vec2(p.y, p.x));
    p = glm::vec2(p.x >= 0.0f ? folded.x : -folded.x, p.y >= 0.0f ? folded.y : -folded.y);
  }
  return p;
}

inline glm::vec3 octahedral_decode(const glm::vec2& p) {
  glm::vec3 n(p.x, p.y, 1.0f - std::fabs(p.x) - std::fabs(p.y));
  if (n.z < 0.0f) {
    const glm::vec2 folded = glm::vec2(1.0f) - glm::abs(glm::vec2(n.y, n.x));
    n.x = n.x >= 0.0f ? folded.x : -folded.x;
    n.y = n.y >= 0.0f ? folded.y : -folded.y;
  }
  return glm::normalize(n);
}

/// [-1, 1] in 16 bits and back.
inline std::uint32_t quantize_signed_16(float v) {
  return static_cast<std::uint32_t>(std::floor(glm::clamp(v * 0.5f + 0.5f, 0.0f, 1.0f) * 65535.0f + 0.5f));
}
inline float dequantize_signed_16(std::uint32_t q) { return static_cast<float>(q) / 65535.0f * 2.0f - 1.0f; }

/// The 21 bits of a non-negative float that the packing keeps (its bits 30..10).
inline std::uint32_t flux_bits_21(float value) { return (float_bits(glm::max(value, 0.0f)) >> 10u) & 0x1FFFFFu; }
inline float flux_from_bits_21(std::uint32_t bits) { return float_from_bits(bits << 10u); }

/// An RSM texel as 128 bits (float instantiation: the GPU stores floats).
inline glm::uvec4 pack_rsm_texel(float eye_depth, const glm::vec3& normal, const glm::vec3& flux) {
  const glm::vec2 oct = octahedral_encode(normal);
  const std::uint32_t r = flux_bits_21(flux.r), g = flux_bits_21(flux.g), b = flux_bits_21(flux.b);
  return glm::uvec4(float_bits(eye_depth), quantize_signed_16(oct.x) | (quantize_signed_16(oct.y) << 16u), r | (g << 21u),
                    (g >> 11u) | (b << 10u));
}

/// The texel back, its world position rebuilt on the centre ray of `texel`.
inline rsm_texel<float> unpack_rsm_texel(const glm::uvec4& bits, const glm::ivec2& texel, const rsm_unprojection<float>& light) {
  rsm_texel<float> out;
  out.eye_depth = float_from_bits(bits.x);
  out.normal = octahedral_decode(glm::vec2(dequantize_signed_16(bits.y & 0xFFFFu), dequantize_signed_16(bits.y >> 16u)));
  out.flux = glm::vec3(flux_from_bits_21(bits.z & 0x1FFFFFu), flux_from_bits_21((bits.z >> 21u) | ((bits.w & 0x3FFu) << 11u)),
                       flux_from_bits_21(bits.w >> 10u));
  const glm::vec2 ndc = (glm::vec2(texel) + 0.5f) / glm::vec2(light.size) * 2.0f - 1.0f;
  const glm::vec2 eye_xy = light.perspective != 0 ? ndc * light.scale * -out.eye_depth : ndc * light.scale;
  out.position = transform_point(light.inverse_light_view, glm::vec3(eye_xy, out.eye_depth));
  return out;
}

}  // namespace vplkit
