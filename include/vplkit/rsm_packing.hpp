// One RSM texel in one 128-bit texel (RGBA32UI), so that the gather reads one texture per pixel
// light instead of three ([RSMV] stores position, normal and flux in three RGBA16F targets,
// Fig. 4.2). Everything is in the light's eye space, where the gather works
// (vplkit/rsm_gather.hpp), and every field decodes in a few integer and float operations: on
// llvmpipe the decode is paid per sample, and an octahedral normal (a fold and a normalize) or
// a matrix per sample cost more than the two fetches they saved (docs/rsm-study.md, "One fetch").
//
//   x      the light eye-space depth z, the float's own bits: exact;
//   y, z   the normal's x, y (y) and z (low half of z), each as a signed 16-bit fixed-point
//          number, q = floor(v * 32767 + 0.5): error <= 2^-16 per coordinate;
//   z, w   the flux's r (high half of z), g and b (w), each as bits 30..15 of the float
//          (8 exponent and 8 mantissa bits; the sign is 0, flux is >= 0), rounded to nearest:
//          relative error <= 2^-9.
//
// Against the RGBA16F targets of the thesis (11 significant bits): position and normal are finer,
// the flux is 4x coarser per texel and unbiased (rounded); a gather averages hundreds of texels.
//
// The position is not stored: it lies on the texel's centre ray at the stored depth. The ray is
// ray_origin + texel * ray_step (make_rsm_unprojection derives both from the light's frustum),
// and the eye-space point is (ray * -z, z) for a spot light (perspective) or (ray, z) for a
// directional light (orthographic). An empty texel (all bits 0: the cleared target) decodes to
// z = 0, which the gather skips.
//
// GLSL twin: shaders/lib/rsm_packing.glsl.
#pragma once

#include <cmath>
#include <cstdint>
#include <cstring>

#include <glm/glm.hpp>

#include <vplkit/rsm_gather.hpp>

namespace vplkit {

/// How a texel's centre ray leaves the light: what unpack_rsm_texel needs to rebuild positions.
/// Derived by make_rsm_unprojection.
template <typename T>
struct rsm_unprojection {
  glm::vec<2, T> ray_origin{T(0)};  ///< the ray of texel (0, 0) (its xy per unit of -z, or its xy)
  glm::vec<2, T> ray_step{T(0)};    ///< the ray's change per texel
  int perspective = 1;               ///< 1: spot light (perspective RSM), 0: directional (orthographic)
};

template <typename T>
struct settings_description<rsm_unprojection<T>> {
  using S = rsm_unprojection<T>;
  static constexpr const char* name = "rsm_unprojection";
  static constexpr bool glsl_twin = true;
  static constexpr auto fields() {
    return std::make_tuple(schema::field(&S::ray_origin, "ray_origin", schema::any_finite(), "", "the centre ray of texel (0, 0)"),
                           schema::field(&S::ray_step, "ray_step", schema::any_finite(), "", "the centre ray's change per texel"),
                           schema::field(&S::perspective, "perspective", schema::closed_range(0, 1), "", "1: spot light (perspective RSM), 0: directional (orthographic)"));
  }
  static setting_problem rules(const S& settings) { return schema::no_rules(settings); }
};

/// The unprojection of an RSM of `size` texels whose frustum is symmetric with half-width `scale`
/// at unit distance (perspective: tan of the half field of view) or half-width `scale`
/// (orthographic): texel t's centre has ndc = (t + 0.5) / size * 2 - 1, and its ray is ndc * scale.
template <typename T>
rsm_unprojection<T> make_rsm_unprojection(T scale, bool perspective, glm::ivec2 size) {
  rsm_unprojection<T> light;
  light.ray_step = T(2) * scale / glm::vec<2, T>(size);
  light.ray_origin = (T(1) / glm::vec<2, T>(size) - T(1)) * scale;
  light.perspective = perspective ? 1 : 0;
  return light;
}

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

/// A coordinate in [-1, 1] as a signed 16-bit fixed-point number (in the low 16 bits), and back.
inline std::uint32_t snorm16_bits(float v) {
  return static_cast<std::uint32_t>(static_cast<std::int32_t>(std::floor(glm::clamp(v, -1.0f, 1.0f) * 32767.0f + 0.5f))) & 0xFFFFu;
}
/// The low 16 bits of `bits` as a signed fixed-point number; `bits << 16` then an arithmetic shift.
inline float snorm16_low(std::uint32_t bits) {
  return static_cast<float>(static_cast<std::int32_t>(bits << 16u) >> 16) * (1.0f / 32767.0f);
}
inline float snorm16_high(std::uint32_t bits) { return static_cast<float>(static_cast<std::int32_t>(bits) >> 16) * (1.0f / 32767.0f); }

/// Bits 30..15 of a non-negative float, rounded to nearest (low 16 bits); negatives, -0 and NaN
/// give 0, and the largest value stays finite.
inline std::uint32_t flux16_bits(float value) {
  const std::uint32_t bits = float_bits(glm::max(value, 0.0f)) & 0x7FFFFFFFu;
  return bits >= 0x7F800000u ? (bits == 0x7F800000u ? 0xFEFFu : 0u) : glm::min((bits + 0x4000u) >> 15u, 0xFEFFu);
}
inline float flux16_low(std::uint32_t bits) { return float_from_bits((bits << 15u) & 0x7FFF8000u); }
inline float flux16_high(std::uint32_t bits) { return float_from_bits((bits >> 1u) & 0x7FFF8000u); }

/// An RSM texel as 128 bits: its light eye-space depth, its eye-space normal (unit) and its flux.
inline glm::uvec4 pack_rsm_texel(float eye_depth, const glm::vec3& normal, const glm::vec3& flux) {
  return glm::uvec4(float_bits(eye_depth), snorm16_bits(normal.x) | (snorm16_bits(normal.y) << 16u),
                    snorm16_bits(normal.z) | (flux16_bits(flux.r) << 16u), flux16_bits(flux.g) | (flux16_bits(flux.b) << 16u));
}

/// The texel back in the light's eye space, its position rebuilt on the centre ray of `texel`.
inline rsm_texel<float> unpack_rsm_texel(const glm::uvec4& bits, const glm::ivec2& texel, const rsm_unprojection<float>& light) {
  const float z = float_from_bits(bits.x);
  const glm::vec2 ray = light.ray_origin + glm::vec2(texel) * light.ray_step;
  const glm::vec2 xy = light.perspective != 0 ? ray * -z : ray;
  return {glm::vec3(xy, z), glm::vec3(snorm16_low(bits.y), snorm16_high(bits.y), snorm16_low(bits.z)),
          glm::vec3(flux16_high(bits.z), flux16_low(bits.w), flux16_high(bits.w))};
}

}  // namespace vplkit
