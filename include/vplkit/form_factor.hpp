// Form factors for diffuse final gathering ([FG], Umenhoffer and Szirmay-Kalos 2007).
//
// point_form_factor(x, n, y, ny): the differential kernel max(0, cos_x) max(0, cos_y) / (pi r^2)
// per unit area at y: a virtual point light of area A at y gives x the form factor ~ A times it.
// It is singular as y approaches x: the bright spikes of the paper's Fig. 4.
//
// polygon_form_factor(x, n, c0, c1, c2, c3): the form factor F in [0, 1] from the differential
// area (x, n) to the planar quad c0..c3 (either winding), by Lambert's formula for polygons:
//   F = 1 / (2 pi) | sum over edges l of gamma_l <n, unit(R_l x R_l+1)> |,
// R_l = c_l - x, gamma_l the angle between R_l and R_l+1 (atan2 of |R_l x R_l+1| and
// R_l . R_l+1: accurate at small angles, where acos is not). The quad is first clipped against
// the tangent plane of x (Sutherland-Hodgman): the part below cannot be seen, and without the
// clip Lambert's formula counts it with the wrong sign. The result is exact for convex planar
// quads, for either winding. irradiance = pi * radiance * F.
//
// polygon_form_factor_unclipped: the paper's variant, kept under its own name: the same sum
// with no clipping, for the winding the paper assumes (counter-clockwise seen from x) and the
// sum clamped at 0 ("max(ff, 0)"). It uses the per-edge angle, not the printed listing's
// dot(r1, r2) on every edge (docs/errata.md, FG-1).
//
// GLSL twin: shaders/lib/form_factor.glsl.
#pragma once

#include <cmath>

#include <glm/glm.hpp>

namespace vplkit {

/// max(0, cos_x) max(0, cos_y) / (pi r^2): per unit area at y. 0 for coincident points.
template <typename T, glm::qualifier Q>
T point_form_factor(const glm::vec<3, T, Q>& x, const glm::vec<3, T, Q>& n, const glm::vec<3, T, Q>& y, const glm::vec<3, T, Q>& ny) {
  const glm::vec<3, T, Q> d = y - x;
  const T r2 = glm::dot(d, d);
  if (!(r2 > T(0))) return T(0);
  const T cos_x = glm::max(T(0), glm::dot(n, d));
  const T cos_y = glm::max(T(0), -glm::dot(ny, d));
  return (cos_x / r2) * (cos_y / r2) * T(0.318309886183790671538);  // (d.n)(-d.ny) / r^4 / pi
}

namespace detail {

/// gamma <n, unit(a x b)> for one edge seen from the origin: gamma * <n, a x b> / |a x b|.
template <typename T, glm::qualifier Q>
T lambert_edge(const glm::vec<3, T, Q>& a, const glm::vec<3, T, Q>& b, const glm::vec<3, T, Q>& n) {
  const glm::vec<3, T, Q> c = glm::cross(a, b);
  const T sine = glm::length(c);
  if (!(sine > T(0))) return T(0);  // an edge through x or a degenerate edge: no angle
  const T gamma = std::atan2(sine, glm::dot(a, b));
  return gamma * (glm::dot(n, c) / sine);
}

}  // namespace detail

/// F from (x, n) to the quad c0..c3, clipped at the tangent plane of x. See the top comment.
template <typename T, glm::qualifier Q>
T polygon_form_factor(const glm::vec<3, T, Q>& x, const glm::vec<3, T, Q>& n, const glm::vec<3, T, Q>& c0, const glm::vec<3, T, Q>& c1,
                      const glm::vec<3, T, Q>& c2, const glm::vec<3, T, Q>& c3) {
  const glm::vec<3, T, Q> corners[4] = {c0 - x, c1 - x, c2 - x, c3 - x};
  // Sutherland-Hodgman against the plane <n, p> = 0, keeping <n, p> >= 0. Each edge adds at most
  // 2 vertices: 8 when a non-convex or non-planar quad crosses the plane 4 times (a convex quad
  // crosses it at most twice: 5). The finite-output test found the overflow of a 5-array.
  glm::vec<3, T, Q> clipped[8];
  int count = 0;
  for (int k = 0; k < 4; ++k) {
    const glm::vec<3, T, Q>& p = corners[k];
    const glm::vec<3, T, Q>& q = corners[(k + 1) % 4];
    const T hp = glm::dot(n, p), hq = glm::dot(n, q);
    if (hp >= T(0)) clipped[count++] = p;
    if ((hp >= T(0)) != (hq >= T(0))) clipped[count++] = p + (q - p) * (hp / (hp - hq));
  }
  T sum = T(0);
  for (int k = 0; k < count; ++k) sum += detail::lambert_edge(clipped[k], clipped[(k + 1) % count], n);
  return glm::min(T(1), std::abs(sum) * T(0.159154943091895335769));  // 1 / (2 pi)
}

/// The paper's variant: no clipping, counter-clockwise quads seen from x, the sum clamped at 0.
template <typename T, glm::qualifier Q>
T polygon_form_factor_unclipped(const glm::vec<3, T, Q>& x, const glm::vec<3, T, Q>& n, const glm::vec<3, T, Q>& c0,
                                const glm::vec<3, T, Q>& c1, const glm::vec<3, T, Q>& c2, const glm::vec<3, T, Q>& c3) {
  const glm::vec<3, T, Q> r[4] = {c0 - x, c1 - x, c2 - x, c3 - x};
  T sum = T(0);
  for (int k = 0; k < 4; ++k) sum += detail::lambert_edge(r[k], r[(k + 1) % 4], n);
  // Counter-clockwise seen from x makes each <n, R_l x R_l+1> negative for a quad above the
  // plane: the paper's sign convention is the opposite of the cross product's.
  return glm::max(T(0), -sum) * T(0.159154943091895335769);
}

}  // namespace vplkit
