// The micro linear buffer of [RSMV] (section 3.3): approximate visibility of the pixel lights
// sampled along one path of the radial pattern, near to far, as seen from one shading point.
//
// Both points are in the light's eye space (xy is the horizontal plane). The elevation of the
// pixel light seen from the shading point, phi = atan(dz / |dxy|) in [-pi/2, pi/2], falls in one
// of B equal slots (elevation_bucket). A nearer sample on the same path in the same slot lies in
// the same direction from the shading point and so hides the farther one.
//   Alg. 2  slot empty -> visible, mark it; else occluded.
//   Alg. 3  as Alg. 2, but a sample in the same slot as its predecessor repeats the
//           predecessor's verdict and leaves the buffer alone (one smooth surface, Fig. 3.4).
//   Alg. 6  branch-free Alg. 3: slots are numbers initialised to 1; nu = slot, slot -= 1; the
//           caller multiplies the contribution by clamp(nu, 0, 1) (Alg. 5, line 12).
// Alg. 6 and Alg. 3 give the same verdict for every sequence (tested exhaustively).
//
// The bucket is found without atan: phi >= phi_k  <=>  dz >= tan(phi_k) * |dxy| for |dxy| > 0,
// so the slot index is the number of interior boundaries k with dz >= tan(phi_k) * |dxy|. The
// tangents are derived once, in double, by make_elevation_slots (C++) and handed to GLSL as a
// uniform, so both sides make the same decision from the same inputs with IEEE-exact operations
// (multiply, add, sqrt, compare) instead of two different atan approximations.
// Points straight above (dz > 0, dxy = 0) fall in the top slot, straight below in the bottom one.
//
// The variant alg6_ray (rsm_gather.hpp's rsm_visibility::alg6_ray, docs/errata.md RSMV-12):
// - elevation_bucket_about measures the elevation above the plane perpendicular to a unit vector
//   `up` instead of the light's xy plane: dz becomes <d, up> and |dxy| the length of d less that
//   component; with up = (0, 0, 1) it is elevation_bucket. The gather takes the direction from the
//   receiver towards a perspective light as `up`: a path of the radial pattern lies in a plane
//   through the light and the receiver, and in that plane this elevation orders the directions
//   from the receiver the way the thesis's elevation does for an orthographic light, where every
//   such plane is vertical.
// - alg6_ray_in_front: only samples in front of the receiver's tangent plane enter the buffer.
// - micro_linear_buffer_alg6_ray: Alg. 3's same-slot rule (repeat the predecessor's verdict)
//   holds only when the predecessor faces the receiver and the sample does not lie behind the
//   predecessor's surface. Consecutive samples of one smooth surface still share a verdict; a
//   surface seen from behind (the far face of a wall) or a surface the sample lies behind (a panel
//   before the floor) no longer passes "visible" on to what it hides in its slot.
//
// Storage, chosen so that the whole buffer lives in registers: indexing a local array by a
// run-time index makes llvmpipe (and many GPU compilers) keep the array in memory, which cost
// 2.8x the gather without visibility instead of 1.17x (the RSM sweep of bench/, 512^2, Cornell box).
// - Alg. 2 and 3 keep a "visible"/"occluded" flag per slot: one bit per slot of `occluded`.
// - Alg. 6 keeps a real number per slot, 1 at the start and decremented by each claim, so its
//   values are the integers 1, 0, -1, ...: stored as claim counts, 8 bits per slot in the four
//   words of `claims`, the slot's value being 1 - count. The arithmetic (nu = value, value -= 1,
//   multiply by clamp(nu, 0, 1), no branch) is the thesis's; a count saturates at 255, which
//   changes no clamped verdict.
//
// GLSL twin: shaders/lib/micro_linear_buffer.glsl.
#pragma once

#include <cmath>
#include <cstdint>

#include <glm/glm.hpp>

#include <vplkit/settings.hpp>

namespace vplkit {

/// Largest slot count B supported (array sizes on both sides). GLSL: VPLKIT_MAX_SLOTS.
inline constexpr int micro_linear_buffer_max_slots = 16;

/// The slot layout for B slots: the tangents of the B - 1 interior slot boundaries, ascending.
/// GLSL twin: struct elevation_slots (upload with one uniform struct).
template <typename T>
struct elevation_slots {
  int count = 0;
  T boundary_tangent[micro_linear_buffer_max_slots - 1] = {};
};

template <typename T>
struct settings_description<elevation_slots<T>> {
  using S = elevation_slots<T>;
  static constexpr const char* name = "elevation_slots";
  static constexpr bool glsl_twin = true;
  static constexpr auto fields() {
    return std::make_tuple(schema::field(&S::count, "count", schema::closed_range(1, micro_linear_buffer_max_slots), "",
                                 "B: micro linear buffer slots, equal bands of elevation (Alg. 1)"),
                           schema::field(&S::boundary_tangent, "boundary_tangent", schema::any_finite(), "", "tan of the B - 1 interior slot boundaries, ascending"));
  }
  static setting_problem rules(const S& slots) {
    for (int k = 0; k + 1 < slots.count - 1; ++k)
      if (!(slots.boundary_tangent[k] < slots.boundary_tangent[k + 1]))
        return setting_problem("elevation_slots::boundary_tangent must ascend (make_elevation_slots derives it)");
    return {};
  }
};

/// The problem with `count` as a slot count, if any.
template <typename T = float>
setting_problem validate_slot_count(int count) {
  return validate_field(&elevation_slots<T>::count, count);
}

/// The constants both sides need for B = count slots. Boundary k (1..B-1) is at elevation
/// phi_k = pi * (k / B - 1/2); computed in double so every float tangent is correctly rounded.
/// `count` must pass validate_slot_count (it is clamped into range otherwise).
template <typename T>
elevation_slots<T> make_elevation_slots(int count) {
  elevation_slots<T> slots;
  slots.count = glm::clamp(count, 1, micro_linear_buffer_max_slots);
  const double pi = 3.14159265358979323846;
  for (int k = 1; k < slots.count; ++k) {
    const double fraction = static_cast<double>(k) / static_cast<double>(slots.count) - 0.5;
    slots.boundary_tangent[k - 1] = static_cast<T>(std::tan(pi * fraction));
  }
  return slots;
}

/// Slot index in [0, slots.count) of a direction with vertical component `dz` and horizontal
/// length `horizontal` (>= 0) in the light's eye space.
template <typename T>
int elevation_slot(T dz, T horizontal, const elevation_slots<T>& slots) {
  int index = 0;
  for (int k = 0; k < slots.count - 1; ++k) index += (dz >= slots.boundary_tangent[k] * horizontal) ? 1 : 0;
  return index;
}

/// Slot index in [0, slots.count) of the elevation of xp_eye seen from x_eye (light eye space).
template <typename T, glm::qualifier Q>
int elevation_bucket(const glm::vec<3, T, Q>& x_eye, const glm::vec<3, T, Q>& xp_eye,
                     const elevation_slots<T>& slots) {
  const T dx = xp_eye.x - x_eye.x;
  const T dy = xp_eye.y - x_eye.y;
  const T dz = xp_eye.z - x_eye.z;
  return elevation_slot(dz, std::sqrt(dx * dx + dy * dy), slots);
}

/// Slot index in [0, slots.count) of the elevation of xp_eye seen from x_eye above the plane
/// perpendicular to the unit vector `up` (light eye space).
template <typename T, glm::qualifier Q>
int elevation_bucket_about(const glm::vec<3, T, Q>& x_eye, const glm::vec<3, T, Q>& xp_eye, const glm::vec<3, T, Q>& up,
                           const elevation_slots<T>& slots) {
  const glm::vec<3, T, Q> d = xp_eye - x_eye;
  const T vertical = d.x * up.x + d.y * up.y + d.z * up.z;
  const glm::vec<3, T, Q> across = d - vertical * up;
  return elevation_slot(vertical, std::sqrt(across.x * across.x + across.y * across.y + across.z * across.z), slots);
}

/// Convenience form of the public contract elevation_bucket(x_eye, xp_eye, slots) with an int
/// slot count (C++ only: in a shader, pass the elevation_slots uniform instead).
template <typename T, glm::qualifier Q>
int elevation_bucket(const glm::vec<3, T, Q>& x_eye, const glm::vec<3, T, Q>& xp_eye, int slots) {
  return elevation_bucket(x_eye, xp_eye, make_elevation_slots<T>(slots));
}

/// Per-path visibility state. GLSL twin: struct micro_linear_buffer.
template <typename T>
struct micro_linear_buffer {
  /// Alg. 2 and 3: bit i set = slot i "occluded" (an earlier sample of this path claimed it).
  std::uint32_t occluded = 0u;
  /// Alg. 6: slot i's value is 1 - (byte i % 4 of word i / 4), the number of claims so far.
  glm::uvec4 claims = glm::uvec4(0u);
  /// idx_{-1} of Alg. 3 and 6: the slot of the last sample that was tested, -1 before the first.
  int previous_index = -1;
  /// nu_{-1}: the verdict (Alg. 3) or unclamped slot value (Alg. 6) of that sample.
  T previous_visibility = T(1);
  /// alg6_ray: that sample's position and normal (light eye space).
  glm::vec<3, T> previous_position{T(0)};
  glm::vec<3, T> previous_normal{T(0)};
};

/// Start a new path: every slot visible, no predecessor. (The buffer is reset for every path.)
/// Every slot starts visible; `slot_count` is the number in use (indices are below it).
template <typename T>
void micro_linear_buffer_reset(micro_linear_buffer<T>& linear_buffer, int slot_count) {
  (void)slot_count;
  linear_buffer.claims = glm::uvec4(0u);
  linear_buffer.occluded = 0u;
  linear_buffer.previous_index = -1;
  linear_buffer.previous_visibility = T(1);
  linear_buffer.previous_position = glm::vec<3, T>(T(0));
  linear_buffer.previous_normal = glm::vec<3, T>(T(0));
}

/// Alg. 2: returns 1 (visible) or 0 (occluded).
template <typename T>
T micro_linear_buffer_alg2(micro_linear_buffer<T>& linear_buffer, int index) {
  const std::uint32_t bit = 1u << static_cast<std::uint32_t>(index);
  const T visibility = (linear_buffer.occluded & bit) == 0u ? T(1) : T(0);
  linear_buffer.occluded |= bit;
  linear_buffer.previous_index = index;
  linear_buffer.previous_visibility = visibility;
  return visibility;
}

/// Alg. 3: returns 1 (visible) or 0 (occluded).
template <typename T>
T micro_linear_buffer_alg3(micro_linear_buffer<T>& linear_buffer, int index) {
  T visibility = linear_buffer.previous_visibility;
  if (index != linear_buffer.previous_index) {
    const std::uint32_t bit = 1u << static_cast<std::uint32_t>(index);
    visibility = (linear_buffer.occluded & bit) == 0u ? T(1) : T(0);
    linear_buffer.occluded |= bit;
  }
  linear_buffer.previous_index = index;
  linear_buffer.previous_visibility = visibility;
  return visibility;
}

/// Alg. 6: returns nu unclamped (1, 0, -1, ...); the caller applies clamp(nu, 0, 1) (Alg. 5).
template <typename T>
T micro_linear_buffer_alg6(micro_linear_buffer<T>& linear_buffer, int index) {
  // The thesis keeps this one branch (Alg. 6, line 3); a select compiles to the same on GPUs.
  const bool same_as_previous = index == linear_buffer.previous_index;
  const std::uint32_t word = static_cast<std::uint32_t>(index) >> 2u;
  const std::uint32_t shift = (static_cast<std::uint32_t>(index) & 3u) * 8u;
  const glm::uvec4 in_word(word == 0u ? 1u : 0u, word == 1u ? 1u : 0u, word == 2u ? 1u : 0u, word == 3u ? 1u : 0u);
  const std::uint32_t claims_word = word == 0u ? linear_buffer.claims.x : word == 1u ? linear_buffer.claims.y : word == 2u ? linear_buffer.claims.z : linear_buffer.claims.w;
  const std::uint32_t count = (claims_word >> shift) & 255u;
  const T slot_value = T(1) - T(count);
  const T visibility = same_as_previous ? linear_buffer.previous_visibility : slot_value;
  const std::uint32_t claim = same_as_previous || count == 255u ? 0u : 1u;  // value -= 1, saturating
  linear_buffer.claims += in_word * (claim << shift);
  linear_buffer.previous_index = index;
  linear_buffer.previous_visibility = visibility;
  return visibility;
}

/// alg6_ray's tolerances. A sample enters the buffer only when its offset d from the receiver
/// (normal n) has <n, d> > alg6_ray_tangent_slope |d| + min_distance: within about a degree of
/// the tangent plane (and Eq. 3.2's distance clamp, about the precision of the G-buffer's and the
/// RSM's positions) a sample is the receiver's own surface or below its horizon: it lights the
/// receiver at most 2 % of what it would face-on and hides nothing in front of it. A sample lies
/// behind its predecessor's surface when its offset s from it has <n_previous, s> <
/// -alg6_ray_behind_slope |s| (about 11 degrees: the same surface, seen through the positions'
/// precision and a slightly curved or jittered path, stays in front).
inline constexpr double alg6_ray_tangent_slope = 0.02;
inline constexpr double alg6_ray_behind_slope = 0.2;

/// Whether a sample at xp enters alg6_ray's buffer for the receiver at x with unit normal n (light
/// eye space): it lies in front of the receiver's tangent plane.
template <typename T, glm::qualifier Q>
bool alg6_ray_in_front(const glm::vec<3, T, Q>& x, const glm::vec<3, T, Q>& n, const glm::vec<3, T, Q>& xp, T min_distance) {
  const glm::vec<3, T, Q> d = xp - x;
  const T facing = n.x * d.x + n.y * d.y + n.z * d.z;
  const T length = std::sqrt(d.x * d.x + d.y * d.y + d.z * d.z);
  return facing > T(alg6_ray_tangent_slope) * length + min_distance;
}

/// alg6_ray: Alg. 6 for the sample at `position` with unit `normal` in slot `index`, seen from the
/// receiver at `receiver` (light eye space). The predecessor's verdict is repeated (Alg. 3's
/// same-slot rule) only when the predecessor faces the receiver and the sample does not lie behind
/// the predecessor's surface; otherwise the slot decides. Returns nu unclamped, like Alg. 6.
template <typename T>
T micro_linear_buffer_alg6_ray(micro_linear_buffer<T>& linear_buffer, int index, const glm::vec<3, T>& receiver, const glm::vec<3, T>& position,
                               const glm::vec<3, T>& normal) {
  const glm::vec<3, T> to_receiver = receiver - linear_buffer.previous_position;
  const glm::vec<3, T> step = position - linear_buffer.previous_position;
  const T faces = linear_buffer.previous_normal.x * to_receiver.x + linear_buffer.previous_normal.y * to_receiver.y + linear_buffer.previous_normal.z * to_receiver.z;
  const T ahead = linear_buffer.previous_normal.x * step.x + linear_buffer.previous_normal.y * step.y + linear_buffer.previous_normal.z * step.z;
  const T step_length = std::sqrt(step.x * step.x + step.y * step.y + step.z * step.z);
  if (!(faces > T(0)) || ahead < -T(alg6_ray_behind_slope) * step_length) linear_buffer.previous_index = -1;
  const T visibility = micro_linear_buffer_alg6(linear_buffer, index);
  linear_buffer.previous_position = position;
  linear_buffer.previous_normal = normal;
  return visibility;
}

}  // namespace vplkit
