// The primary lights of the RSM pipeline ([RSMV] renders its RSM from a spot or a
// directional light): direct irradiance, and the flux an RSM texel reflects.
//
// Spot light:  E(x, n) = I * cone(cos_axis) * max(0, <n, l>) / max(|p - x|, min_distance)^2
// with l the unit direction from x to the light at p, I the radiant intensity on the axis, and
// cone() a smoothstep from cos_outer (0) to cos_inner (1) of the angle off the axis. The distance
// clamp is the one of pixel_light_irradiance (irradiance_settings::min_distance).
// Directional light:  E(x, n) = E_perpendicular * max(0, <n, -direction>).
// Point light:  E(x, n) = I * max(0, <n, l>) / max(|p - x|, min_distance)^2, the spot without its
// cone (KHR_lights_punctual's point light: intensity in candela, W/sr here, the same in every
// direction).
//
// RSM flux (Dachsbacher and Stamminger 2005: "the flux of each pixel light is the flux of the
// light through the pixel, times the reflectance"): a texel of a perspective RSM with half-angle
// tangent t and W x H texels covers the solid angle (2t/W)(2t/H) cos^3(theta) around its
// direction (theta off the axis); the spot light sends I * cone * that solid angle through it. A
// texel of an orthographic RSM covers the area (width/W)(height/H) across the light's direction.
// A point light's RSM is a cube of six perspective faces (tan_half_fov = 1): a face texel's flux
// is the spot's without the cone.
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

template <typename T>
struct settings_description<spot_light<T>> {
  using S = spot_light<T>;
  static constexpr const char* name = "spot_light";
  static constexpr bool glsl_twin = true;
  static constexpr auto fields() {
    return std::make_tuple(schema::field(&S::position, "position", schema::any_finite(), "scene units", "where the light is"),
                           schema::field(&S::direction, "direction", schema::closed_range(-1, 1), "", "unit vector along the cone's axis"),
                           schema::field(&S::intensity, "intensity", schema::at_least(0.0), "W/sr", "radiant intensity on the axis per colour channel"),
                           schema::field(&S::cos_inner, "cos_inner", schema::closed_range(-1, 1), "", "cosine of the half-angle where the cone starts to fall off"),
                           schema::field(&S::cos_outer, "cos_outer", schema::closed_range(-1, 1), "", "cosine of the half-angle where the cone reaches 0"));
  }
  static setting_problem rules(const S& light) {
    if (!(std::abs(glm::length(light.direction) - T(1)) < T(1e-3))) return setting_problem("spot_light::direction must be a unit vector");
    if (!(light.cos_inner > light.cos_outer)) return setting_problem("spot_light: cos_inner must be greater than cos_outer");
    return {};
  }
};

/// The cone's falloff for the cosine of the angle off the axis: a smoothstep from cos_outer (0)
/// to cos_inner (1).
template <typename T>
T spot_light_cone(const spot_light<T>& light, T cos_axis) {
  const T t = glm::clamp((cos_axis - light.cos_outer) / (light.cos_inner - light.cos_outer), T(0), T(1));
  return t * t * (T(3) - T(2) * t);
}

/// The unit direction from x to a light at `position`, and the squared distance clamped below at
/// min_distance^2 (the clamp of pixel_light_irradiance), which spot and point lights divide by.
template <typename T, glm::qualifier Q>
glm::vec<3, T, Q> direction_to_light_at(const glm::vec<3, T, Q>& x, const glm::vec<3, T>& position, T min_distance,
                                        T& distance_squared) {
  const glm::vec<3, T, Q> to_light = position - x;
  distance_squared = glm::max(glm::dot(to_light, to_light), min_distance * min_distance);
  return to_light / std::sqrt(distance_squared);
}

/// Irradiance at (x, n) from the spot light, without visibility.
template <typename T, glm::qualifier Q, typename S = T>
glm::vec<3, T, Q> spot_light_irradiance(const glm::vec<3, T, Q>& x, const glm::vec<3, T, Q>& n,
                                        const spot_light<T>& light,
                                        const irradiance_settings<S>& settings = {}) {
  T distance_squared;
  const glm::vec<3, T, Q> direction_to_light = direction_to_light_at(x, light.position, T(settings.min_distance), distance_squared);
  const T cos_receiver = glm::max(T(0), glm::dot(n, direction_to_light));
  const T cone = spot_light_cone(light, -glm::dot(light.direction, direction_to_light));
  return light.intensity * (cone * cos_receiver / distance_squared);
}

/// A directional light. GLSL twin: struct directional_light.
template <typename T>
struct directional_light {
  /// Unit vector the light travels along.
  glm::vec<3, T> direction = glm::vec<3, T>(0, -1, 0);
  /// Irradiance on a surface perpendicular to the light, per colour channel (W/m^2).
  glm::vec<3, T> irradiance = glm::vec<3, T>(1);
};

template <typename T>
struct settings_description<directional_light<T>> {
  using S = directional_light<T>;
  static constexpr const char* name = "directional_light";
  static constexpr bool glsl_twin = true;
  static constexpr auto fields() {
    return std::make_tuple(schema::field(&S::direction, "direction", schema::closed_range(-1, 1), "", "unit vector the light travels along"),
                           schema::field(&S::irradiance, "irradiance", schema::at_least(0.0), "W/m^2", "irradiance on a surface facing the light, per colour channel"));
  }
  static setting_problem rules(const S& light) {
    if (!(std::abs(glm::length(light.direction) - T(1)) < T(1e-3))) return setting_problem("directional_light::direction must be a unit vector");
    return {};
  }
};

template <typename T, glm::qualifier Q>
glm::vec<3, T, Q> directional_light_irradiance(const glm::vec<3, T, Q>& n, const directional_light<T>& light) {
  return light.irradiance * glm::max(T(0), -glm::dot(n, light.direction));
}

/// A point light: the same radiant intensity in every direction. GLSL twin: struct point_light.
template <typename T>
struct point_light {
  glm::vec<3, T> position = glm::vec<3, T>(0);
  /// Radiant intensity per colour channel (W/sr), in every direction.
  glm::vec<3, T> intensity = glm::vec<3, T>(1);
};

template <typename T>
struct settings_description<point_light<T>> {
  using S = point_light<T>;
  static constexpr const char* name = "point_light";
  static constexpr bool glsl_twin = true;
  static constexpr auto fields() {
    return std::make_tuple(schema::field(&S::position, "position", schema::any_finite(), "scene units", "where the light is"),
                           schema::field(&S::intensity, "intensity", schema::at_least(0.0), "W/sr", "radiant intensity per colour channel, in every direction"));
  }
  static setting_problem rules(const S&) { return {}; }
};

/// Irradiance at (x, n) from the point light, without visibility.
template <typename T, glm::qualifier Q, typename S = T>
glm::vec<3, T, Q> point_light_irradiance(const glm::vec<3, T, Q>& x, const glm::vec<3, T, Q>& n,
                                         const point_light<T>& light,
                                         const irradiance_settings<S>& settings = {}) {
  T distance_squared;
  const glm::vec<3, T, Q> direction_to_light = direction_to_light_at(x, light.position, T(settings.min_distance), distance_squared);
  const T cos_receiver = glm::max(T(0), glm::dot(n, direction_to_light));
  return light.intensity * (cos_receiver / distance_squared);
}

/// Solid angle of the texel at normalised device coordinate `ndc` of a W x H perspective map
/// with tangent of the half field of view `tan_half_fov` (square frustum).
template <typename T>
T perspective_texel_solid_angle(const glm::vec<2, T>& ndc, T tan_half_fov, const glm::ivec2& size) {
  const glm::vec<2, T> on_plane = ndc * tan_half_fov;  // image plane at distance 1
  const T cos_theta = T(1) / std::sqrt(T(1) + glm::dot(on_plane, on_plane));
  const T texel_area = (T(2) * tan_half_fov / T(size.x)) * (T(2) * tan_half_fov / T(size.y));
  return texel_area * (cos_theta * cos_theta * cos_theta);
}

/// Flux reflected by the surface (position, normal) seen in an RSM texel of a spot light:
/// albedo * I * cone * solid angle, and 0 when the surface faces away from the light (its back
/// is lit, and its pixel light would shine from the wrong side).
template <typename T, glm::qualifier Q>
glm::vec<3, T, Q> spot_light_texel_flux(const glm::vec<3, T, Q>& albedo, const glm::vec<3, T, Q>& position,
                                        const glm::vec<3, T, Q>& normal, const spot_light<T>& light,
                                        const glm::vec<2, T>& ndc, T tan_half_fov, const glm::ivec2& size) {
  const glm::vec<3, T, Q> from_light = glm::normalize(position - light.position);
  const T cone = spot_light_cone(light, glm::dot(light.direction, from_light));
  const T facing = glm::dot(normal, from_light) < T(0) ? T(1) : T(0);
  return albedo * light.intensity * (facing * cone * perspective_texel_solid_angle(ndc, tan_half_fov, size));
}

/// Flux reflected by the surface (position, normal) seen in a texel of one face of a point light's
/// cube RSM (a square frustum of 90 degrees, tan_half_fov = 1): albedo * I * solid angle, and 0
/// when the surface faces away from the light.
template <typename T, glm::qualifier Q>
glm::vec<3, T, Q> point_light_texel_flux(const glm::vec<3, T, Q>& albedo, const glm::vec<3, T, Q>& position,
                                         const glm::vec<3, T, Q>& normal, const point_light<T>& light,
                                         const glm::vec<2, T>& ndc, const glm::ivec2& size) {
  const glm::vec<3, T, Q> from_light = position - light.position;
  const T facing = glm::dot(normal, from_light) < T(0) ? T(1) : T(0);
  return albedo * light.intensity * (facing * perspective_texel_solid_angle(ndc, T(1), size));
}

/// Flux reflected by the surface seen in a texel of an orthographic RSM whose texels cover
/// `texel_area` across the light's direction: albedo * E_perpendicular * area (0 facing away).
template <typename T, glm::qualifier Q>
glm::vec<3, T, Q> directional_light_texel_flux(const glm::vec<3, T, Q>& albedo, const glm::vec<3, T, Q>& normal,
                                               const directional_light<T>& light, T texel_area) {
  const T facing = glm::dot(normal, light.direction) < T(0) ? T(1) : T(0);
  return albedo * light.irradiance * (facing * texel_area);
}

}  // namespace vplkit
