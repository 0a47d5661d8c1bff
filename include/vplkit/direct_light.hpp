// Direct irradiance from a spot light: the primary light of the RSM pipeline (paper 000, chapter
// 4 renders an RSM from a spot or directional light) and of vplkit's direct pass.
//
//   E(x, n) = I * cone(cos_axis) * max(0, <n, l>) / max(|p - x|, min_distance)^2
// with l the unit direction from x to the light at p, I the radiant intensity on the axis, and
// cone() a smoothstep from cos_outer (0) to cos_inner (1) of the angle off the axis.
// The distance clamp is the one of pixel_light_irradiance (irradiance_settings::min_distance).
//
// GLSL twin: shaders/lib/direct_light.glsl.
#pragma once

#include <cmath>

#include <glm/glm.hpp>

#include <vplkit/irradiance.hpp>

namespace vplkit {

/// A spot light. GLSL twin: struct spot_light.
template <typename T>
struct spot_light {
  glm::vec<3, T> position = glm::vec<3, T>(0);
  /// Unit vector along the cone axis (the direction the light shines).
  glm::vec<3, T> direction = glm::vec<3, T>(0, -1, 0);
  /// Radiant intensity on the axis per colour channel (W/sr).
  glm::vec<3, T> intensity = glm::vec<3, T>(1);
  /// Cosines of the half-angles where the cone starts to fall off (inner) and reaches 0 (outer);
  /// cos_inner > cos_outer.
  T cos_inner = T(0.9);
  T cos_outer = T(0.8);
};

/// Returns nullptr when the light is usable, else a message naming the bad field.
template <typename T>
const char* validate(const spot_light<T>& light) {
  if (!(std::abs(glm::length(light.direction) - T(1)) < T(1e-3))) return "spot_light::direction must be a unit vector";
  if (!(light.cos_inner > light.cos_outer)) return "spot_light: cos_inner must be greater than cos_outer";
  if (!(light.cos_outer >= T(-1) && light.cos_inner <= T(1))) return "spot_light: cone cosines must lie in [-1, 1]";
  return nullptr;
}

/// Irradiance at (x, n) from the spot light, without visibility.
template <typename T, glm::qualifier Q, typename S = T>
glm::vec<3, T, Q> spot_light_irradiance(const glm::vec<3, T, Q>& x, const glm::vec<3, T, Q>& n,
                                        const spot_light<T>& light,
                                        const irradiance_settings<S>& settings = {}) {
  const glm::vec<3, T, Q> to_light = light.position - x;
  const T min_distance = T(settings.min_distance);
  const T distance_squared = glm::max(glm::dot(to_light, to_light), min_distance * min_distance);
  const glm::vec<3, T, Q> direction_to_light = to_light / std::sqrt(distance_squared);
  const T cos_receiver = glm::max(T(0), glm::dot(n, direction_to_light));
  const T cos_axis = -glm::dot(light.direction, direction_to_light);
  const T t = glm::clamp((cos_axis - light.cos_outer) / (light.cos_inner - light.cos_outer), T(0), T(1));
  const T cone = t * t * (T(3) - T(2) * t);
  return light.intensity * (cone * cos_receiver / distance_squared);
}

}  // namespace vplkit
