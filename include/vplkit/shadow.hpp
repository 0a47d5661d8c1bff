// Shadow density ([RSMV], Alg. 4): the fraction of a kernelSize x kernelSize window of RSM
// depths around the receiver's projection that do not hide the receiver. 1 = fully lit,
// 0 = fully in shadow; the G-buffer stores it and the post pass multiplies direct light by it.
//
// Depth convention. Depths are OpenGL eye-space z of the light: negative in front of it. Alg. 4
// prints "lit if RSM.depth - zBias >= p.depth" and says the bias "shifts all depth values on RSM
// a little bit farther along the z-axis". With eye-space z, farther is more negative, and a
// stored surface pushed farther by the bias that is still in front of the receiver must shadow
// it, so the test that does what the thesis describes is
//     lit  <=>  RSM.depth - zBias <= p.depth
// (the printed >= would light every receiver behind an occluder and shadow every receiver by
// its own surface). docs/errata.md (RSMV-4) records the printed form; the discrepancy is decided by the
// thesis's own description and tested on a synthetic occluder. Texels outside the RSM count as
// not lit (Alg. 4, line 5); empty texels (depth >= 0, nothing there) hide nothing.
//
// Receiver-plane bias (an addition to Alg. 4). With a constant zBias and a window wider than one
// texel, a surface at a grazing angle to the light shadows itself: its own depth changes across
// the window by more than the bias (seen as stripes on the Cornell box's walls at kernel 4).
// Each window texel is therefore compared with the depth the receiver's tangent plane has at
// that texel, receiver_depth + <depth_gradient, texel centre - projection>, where
// depth_gradient is the change of the receiver's light eye depth per RSM texel (the G-buffer
// pass takes it from screen-space derivatives; 0 gives the thesis's Alg. 4 exactly).
//
// Slope-scaled and normal-offset bias (an addition, [RSMV] gives a constant zBias only). One RSM
// texel covers footprint = 2 |w| / (|P00| size) scene units at the receiver, w = P23 z + P33 the
// clip w of the light's projection P at the receiver's eye depth z (a spot: 2 |z| tan(fov/2) /
// size; a sun's orthographic map: its width / size). A receiver whose normal makes the angle theta
// with the direction to the light
//   - is looked up from p + n normal_offset footprint sin(theta): moved off its own surface by up
//     to normal_offset texels, the most where the surface grazes the light (its own depth changes
//     fastest across a texel) and not at all where it faces it;
//   - is compared with the bias depth_bias + slope_scale footprint min(tan(theta), max_slope):
//     the change of its own depth across slope_scale texels.
// Both are in the receiver's own texel footprint, so they shrink with the map's resolution and
// grow with the distance to the light; an object standing on a floor keeps its contact shadow
// as long as the offset (a texel or two) is small against the object. The receiver-plane
// gradient's clamp (the G-buffer pass) is max_slope footprints per texel, for the same reason.
//
// GLSL twin: shaders/lib/shadow.glsl; the including shader defines
// `float rsm_depth_fetch(ivec2 texel)`.
#pragma once

#include <glm/glm.hpp>

#include <vplkit/settings.hpp>

namespace vplkit {

/// Settings of Alg. 4 (the thesis gives neither value). GLSL twin: struct shadow_density_settings.
template <typename T = float>
struct shadow_density_settings {
  int kernel_size = 4;      ///< kernelSize (>= 1): window of kernelSize^2 RSM texels
  T depth_bias = T(0.02);   ///< zBias in scene units (>= 0), against self-shadowing
  T normal_offset = T(1);   ///< normal offset in texel footprints (>= 0) at a grazing angle
  T slope_scale = T(1);     ///< slope-scaled bias in texel footprints (>= 0) per unit of tan(theta)
  T max_slope = T(10);      ///< tan(theta) is clamped at this (> 0): 84 degrees
};

template <typename T>
struct settings_description<shadow_density_settings<T>> {
  using S = shadow_density_settings<T>;
  static constexpr const char* name = "shadow_density_settings";
  static constexpr bool glsl_twin = true;
  static constexpr auto fields() {
    return std::make_tuple(schema::field(&S::kernel_size, "kernel_size", schema::closed_range(1, 32), "RSM texels", "Alg. 4's window: kernel_size^2 RSM texels"),
                           schema::field(&S::depth_bias, "depth_bias", schema::at_least(0.0), "scene units", "Alg. 4's zBias, against self-shadowing"),
                           schema::field(&S::normal_offset, "normal_offset", schema::closed_range(0.0, 64.0), "texel footprints",
                                 "the lookup moved along the normal by this times sin(theta)"),
                           schema::field(&S::slope_scale, "slope_scale", schema::closed_range(0.0, 64.0), "texel footprints",
                                 "the slope-scaled bias: this times tan(theta) footprints"),
                           schema::field(&S::max_slope, "max_slope", schema::open_closed_range(0.0, 1000.0), "tan(theta)",
                                 "tan(theta) clamped at this in the bias and the receiver-plane gradient"));
  }
  static setting_problem rules(const S& settings) { return schema::no_rules(settings); }
};

/// Scene units one texel of a shadow map covers at a receiver of eye depth `eye_depth` (< 0 in
/// front of the light), for the map's projection `projection` over `map_size` texels per side.
template <typename T>
T shadow_texel_footprint(const glm::mat<4, 4, T>& projection, T eye_depth, int map_size) {
  const T w = projection[2][3] * eye_depth + projection[3][3];
  return T(2) * glm::abs(w) / (glm::abs(projection[0][0]) * T(map_size));
}

/// The receiver's position for its shadow lookup: `position` moved along its unit normal `normal`
/// by normal_offset footprints times sin(theta), theta between `normal` and `to_light` (unit).
template <typename T>
glm::vec<3, T> shadow_normal_offset(const glm::vec<3, T>& position, const glm::vec<3, T>& normal, const glm::vec<3, T>& to_light, T footprint,
                                    const shadow_density_settings<T>& settings) {
  const T cos_theta = glm::clamp(glm::dot(normal, to_light), T(0), T(1));
  const T sin_theta = glm::sqrt(T(1) - cos_theta * cos_theta);
  return position + normal * (settings.normal_offset * footprint * sin_theta);
}

/// The depth bias for a receiver at the angle theta to the light (cos_theta = <n, to_light>, a
/// receiver facing away taken at max_slope): depth_bias + slope_scale footprint min(tan, max_slope).
template <typename T>
T shadow_slope_bias(T cos_theta, T footprint, const shadow_density_settings<T>& settings) {
  const T c = glm::clamp(cos_theta, T(0), T(1));
  const T tan_theta = c * settings.max_slope > glm::sqrt(T(1) - c * c) ? glm::sqrt(T(1) - c * c) / c : settings.max_slope;
  return settings.depth_bias + settings.slope_scale * footprint * tan_theta;
}

/// Alg. 4 for a receiver whose projection on the RSM is `rsm_coordinate` (texels, continuous),
/// whose light eye-space depth is `receiver_depth`, changing by `depth_gradient` per RSM texel.
/// `fetch_depth(glm::ivec2) -> T`.
template <typename T, typename FetchDepth>
T shadow_density(const glm::vec<2, T>& rsm_coordinate, T receiver_depth, const glm::vec<2, T>& depth_gradient,
                 FetchDepth&& fetch_depth, const glm::ivec2& rsm_size, const shadow_density_settings<T>& settings) {
  const glm::ivec2 centre = glm::ivec2(glm::floor(rsm_coordinate));
  const int half_size = settings.kernel_size / 2;
  int lit = 0;
  for (int i = -half_size; i < settings.kernel_size - half_size; ++i) {
    for (int j = -half_size; j < settings.kernel_size - half_size; ++j) {
      const glm::ivec2 texel = centre + glm::ivec2(i, j);
      if (texel.x < 0 || texel.y < 0 || texel.x >= rsm_size.x || texel.y >= rsm_size.y) continue;
      const T stored = fetch_depth(texel);
      const T plane_depth = receiver_depth + glm::dot(depth_gradient, glm::vec<2, T>(texel) + T(0.5) - rsm_coordinate);
      if (!(stored < T(0)) || stored - settings.depth_bias <= plane_depth) ++lit;
    }
  }
  return T(lit) / T(settings.kernel_size * settings.kernel_size);
}

}  // namespace vplkit
