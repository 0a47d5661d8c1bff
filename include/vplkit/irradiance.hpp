// Irradiance at a receiver due to one pixel light (a VPL) of a reflective shadow map.
//
// [RSMV] (reflective shadow maps with a visibility approximation, docs/papers.md), Eq. 3.2:
//   E_p(x, n) = Phi_p * max(0, <n_p, x - x_p>) * max(0, <n, x_p - x>) / |x - x_p|^4
// The equation is singular as x_p approaches x. The thesis is silent about it; every public RSM
// implementation clamps the distance, and so does this one, through an explicit setting
// (irradiance_settings::min_distance) that the GLSL twin shares.
//
// Evaluated as (emit / d^2) * (receive / d^2) rather than emit * receive / d^4: each factor is
// bounded by 1 / d, so the result stays finite for any finite input in float (d^4 alone overflows
// once |x - x_p| > 1.8e19, and emit * receive / d^4 then gives inf / inf = NaN).
//
// GLSL twin: shaders/lib/irradiance.glsl.
#pragma once

#include <glm/glm.hpp>

#include <vplkit/settings.hpp>

namespace vplkit {

/// Settings of pixel_light_irradiance. GLSL twin: struct irradiance_settings.
template <typename T = float>
struct irradiance_settings {
  /// Distances |x - x_p| below this are clamped to it (scene units; must be > 0). It bounds the
  /// 1/r^2 singularity of Eq. 3.2. 0.01 suits scenes a few units across, as the built-in ones;
  /// a good value is about the footprint of one RSM texel on the lit surfaces.
  T min_distance = T(0.01);
};

template <typename T>
struct settings_description<irradiance_settings<T>> {
  static constexpr const char* name = "irradiance_settings";
  static constexpr bool glsl_twin = true;
  static constexpr auto fields() {
    return std::make_tuple(schema::field(&irradiance_settings<T>::min_distance, "min_distance", schema::above(0.0), "scene units",
                                 "distance clamp of the light terms (Eq. 3.2): it bounds the 1/r^2 singularity"));
  }
  static setting_problem rules(const irradiance_settings<T>& settings) { return schema::no_rules(settings); }
};

/// Eq. 3.2. x, n: receiver position and unit normal; xp, np: pixel-light position and unit normal;
/// flux: the pixel light's flux. Returns irradiance (flux per area, per colour channel).
template <typename T, glm::qualifier Q, typename S = T>
glm::vec<3, T, Q> pixel_light_irradiance(const glm::vec<3, T, Q>& x, const glm::vec<3, T, Q>& n,
                                         const glm::vec<3, T, Q>& xp, const glm::vec<3, T, Q>& np,
                                         const glm::vec<3, T, Q>& flux,
                                         const irradiance_settings<S>& settings = {}) {
  const glm::vec<3, T, Q> light_to_receiver = x - xp;
  const T min_distance = T(settings.min_distance);
  const T distance_squared =
      glm::max(glm::dot(light_to_receiver, light_to_receiver), min_distance * min_distance);
  const T emit = glm::max(T(0), glm::dot(np, light_to_receiver));
  const T receive = glm::max(T(0), -glm::dot(n, light_to_receiver));
  return flux * ((emit / distance_squared) * (receive / distance_squared));
}

}  // namespace vplkit
