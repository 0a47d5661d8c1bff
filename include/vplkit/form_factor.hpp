// Form factors for diffuse final gathering ([FG], Umenhoffer and Szirmay-Kalos 2007).
//
// point_form_factor(x, n, y, ny): the differential kernel max(0, cos_x) max(0, cos_y) / (pi r^2)
// per unit area at y: a virtual point light of area A at y gives x the form factor ~ A times it.
// It is singular as y approaches x: the bright spikes of the paper's Fig. 4.
//
// polygon_form_factor(x, n, c0, c1, c2, c3): the form factor F in [0, 1] from the differential
// area (x, n) to the planar quad c0..c3 (either winding), by Lambert's formula for polygons:
//   F = 1 / (2 pi) | sum over edges l of gamma_l <n, unit(R_l x R_l+1)> |,
// R_l = c_l - x, gamma_l the angle between R_l and R_l+1. The quad is first clipped against
// the tangent plane of x (Sutherland-Hodgman): the part below cannot be seen, and without the
// clip Lambert's formula counts it with the wrong sign. gamma_l / sin(gamma_l) comes from a
// polynomial in cos(gamma_l) (detail::lambert_edge: no atan2, accurate at small angles), which
// costs at most 2.1e-8 of F against the exact form, polygon_form_factor_exact (atan2 and
// Sutherland-Hodgman's vertex list, the tests' ground truth). For convex planar quads, either winding. irradiance = pi *
// radiance * F.
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

/// acos(x) / sqrt(1 - x) for x in [0, 1]: Abramowitz and Stegun 4.4.46, a degree-7 polynomial
/// with |sqrt(1 - x) P(x) - acos(x)| <= 2.2e-8 over [0, 1] (A&S print 2e-8; their rounded
/// a0 = 1.5707963050 makes it 2.18e-8 at x = 0: test_form_factor.cpp checks the bound densely).
template <typename T>
T acos_over_sqrt_one_minus(T x) {
  return T(1.5707963050) +
         x * (T(-0.2145988016) +
              x * (T(0.0889789874) +
                   x * (T(-0.0501743046) + x * (T(0.0308918810) + x * (T(-0.0170881256) + x * (T(0.0066700901) + x * T(-0.0012624911)))))));
}

/// gamma <n, unit(a x b)> for one edge seen from the origin, given 1/|a| and 1/|b| (0 for a zero
/// vector: the edge then adds nothing). With the unit vectors u = a/|a| and v = b/|b|, Lambert's
/// term is gamma / sin(gamma) times <n, u x v>, and with x = cos(gamma) = <u, v>:
///   x >= 0: gamma / sin(gamma) = sqrt(1 - x) P(x) / sqrt(1 - x^2) = P(x) / sqrt(1 + x),
///   x <  0: gamma = pi - sqrt(1 + x) P(-x), so gamma / sin(gamma) = (pi / sqrt(1 + x) - P(-x)) / sqrt(1 - x),
/// with P = acos_over_sqrt_one_minus: no atan2 and no sqrt of 1 - x, whose cancellation at small
/// angles makes acos inaccurate there (a small angle's x only enters through 1 + x). 1 + x is
/// |u + v|^2 / 2, which keeps its relative accuracy as the edge turns antipodal (x -> -1), where
/// 1 + <u, v> would cancel. The error against the exact term is the polynomial's in gamma times
/// |<n, unit(a x b)>| <= 1: at most 2.2e-8 rad per edge, plus rounding. An edge through the
/// origin (x = -1) has no defined term (its unit normal is rounding noise, in any form); it is
/// kept in [-pi, pi], the range of the exact term.
template <typename T, glm::qualifier Q>
T lambert_edge(const glm::vec<3, T, Q>& a, T inverse_length_a, const glm::vec<3, T, Q>& b, T inverse_length_b, const glm::vec<3, T, Q>& n) {
  const glm::vec<3, T, Q> u = a * inverse_length_a, v = b * inverse_length_b, half_sum = (u + v) * T(0.5);
  const T x = glm::clamp(glm::dot(u, v), T(-1), T(1));
  const T ax = std::abs(x);
  const T p = acos_over_sqrt_one_minus(ax);
  // 2 |(u + v) / 2|^2 = 1 + x, off 0 so that an antipodal edge's factor stays finite.
  const T inverse_sqrt_one_plus_x = T(1) / std::sqrt(glm::max(T(2) * glm::dot(half_sum, half_sum), T(1e-30)));
  const T inverse_sqrt_one_plus_ax = T(1) / std::sqrt(T(1) + ax);  // 1 / sqrt(1 - x) for x < 0
  const T gamma_over_sine = x >= T(0) ? p * inverse_sqrt_one_plus_x
                                      : (T(3.14159265358979323846) * inverse_sqrt_one_plus_x - p) * inverse_sqrt_one_plus_ax;
  const T term = gamma_over_sine * glm::dot(n, glm::cross(u, v));
  return glm::clamp(term, T(-3.14159265358979323846), T(3.14159265358979323846));
}

/// 1 / |v|, 0 for the zero vector.
template <typename T, glm::qualifier Q>
T inverse_length(const glm::vec<3, T, Q>& v) {
  const T length_squared = glm::dot(v, v);
  return length_squared > T(0) ? T(1) / std::sqrt(length_squared) : T(0);
}

/// The exact term: gamma from atan2 of |a x b| and a . b (accurate at small angles, where acos is
/// not). polygon_form_factor_exact's, the ground truth the tests hold lambert_edge to.
template <typename T, glm::qualifier Q>
T lambert_edge_exact(const glm::vec<3, T, Q>& a, const glm::vec<3, T, Q>& b, const glm::vec<3, T, Q>& n) {
  const glm::vec<3, T, Q> c = glm::cross(a, b);
  const T sine = glm::length(c);
  if (!(sine > T(0))) return T(0);  // an edge through x or a degenerate edge: no angle
  const T gamma = std::atan2(sine, glm::dot(a, b));
  return gamma * (glm::dot(n, c) / sine);
}

}  // namespace detail

/// F from (x, n) to the quad c0..c3, clipped at the tangent plane of x. See the top comment.
///
/// The clipped polygon's edges are each original edge's part above the plane plus, where the
/// quad crosses the plane, the closing edges along it from each exit point to the next entry
/// point: Sutherland-Hodgman's polygon, summed edge by edge without building its vertex list (a
/// list indexed by a running count is a scratch array on a GPU, the slowest part of the old
/// kernel on llvmpipe). Crossings alternate exit and entry around the quad: two for a convex
/// quad, four at most for a non-convex or non-planar one. Exact but for lambert_edge's bound:
/// |F - polygon_form_factor_exact| <= 6 x 2.2e-8 / (2 pi) = 2.1e-8 plus rounding (at most 4 + 2 edges).
template <typename T, glm::qualifier Q>
T polygon_form_factor(const glm::vec<3, T, Q>& x, const glm::vec<3, T, Q>& n, const glm::vec<3, T, Q>& c0, const glm::vec<3, T, Q>& c1,
                      const glm::vec<3, T, Q>& c2, const glm::vec<3, T, Q>& c3) {
  const glm::vec<3, T, Q> corners[4] = {c0 - x, c1 - x, c2 - x, c3 - x};
  const T heights[4] = {glm::dot(n, corners[0]), glm::dot(n, corners[1]), glm::dot(n, corners[2]), glm::dot(n, corners[3])};
  // Below the horizon: nothing to clip or sum (half of a cube map's texels for any receiver).
  // (The GLSL twin writes this and the closing edges' test as loops: see there why.)
  if (heights[0] < T(0) && heights[1] < T(0) && heights[2] < T(0) && heights[3] < T(0)) return T(0);
  const T inverse_lengths[4] = {detail::inverse_length(corners[0]), detail::inverse_length(corners[1]), detail::inverse_length(corners[2]),
                                detail::inverse_length(corners[3])};
  T sum = T(0);
  // The crossing points in order (exit0, exit1; entry0, entry1); which came first decides the pairing.
  glm::vec<3, T, Q> exit0(T(0)), exit1(T(0)), entry0(T(0)), entry1(T(0));
  int exit_count = 0, entry_count = 0;
  bool exit_first = false;
  for (int k = 0; k < 4; ++k) {
    // Branch-free, one edge term each: a GPU running SIMD lanes in lock step would otherwise
    // evaluate every branch's term.
    const int next = (k + 1) & 3;
    const glm::vec<3, T, Q>& p = corners[k];
    const glm::vec<3, T, Q>& q = corners[next];
    const bool p_above = heights[k] >= T(0), q_above = heights[next] >= T(0);
    const bool crosses = p_above != q_above;
    const glm::vec<3, T, Q> m = p + (q - p) * (crosses ? heights[k] / (heights[k] - heights[next]) : T(0));
    const T inverse_length_m = detail::inverse_length(m);
    // The edge's part above the plane: from p or the crossing point to q or the crossing point.
    const T term = detail::lambert_edge(p_above ? p : m, p_above ? inverse_lengths[k] : inverse_length_m, q_above ? q : m,
                                        q_above ? inverse_lengths[next] : inverse_length_m, n);
    sum += (p_above || q_above) ? term : T(0);
    const bool leaves = crosses && p_above, enters = crosses && q_above;
    exit_first = exit_first || (leaves && exit_count == 0 && entry_count == 0);
    exit1 = leaves && exit_count == 1 ? m : exit1;
    exit0 = leaves && exit_count == 0 ? m : exit0;
    entry1 = enters && entry_count == 1 ? m : entry1;
    entry0 = enters && entry_count == 0 ? m : entry0;
    exit_count += leaves ? 1 : 0;
    entry_count += enters ? 1 : 0;
  }
  // Each exit closes to the next entry around the quad: with two crossings the one pair; with
  // four, exit i to entry i when an exit came first, else exit 0 to entry 1 and exit 1 to entry 0.
  for (int c = 0; c < exit_count; ++c) {
    const glm::vec<3, T, Q> from = c == 0 ? exit0 : exit1;
    const glm::vec<3, T, Q> to = (c == 0) == (exit_first || exit_count == 1) ? entry0 : entry1;
    sum += detail::lambert_edge(from, detail::inverse_length(from), to, detail::inverse_length(to), n);
  }
  return glm::min(T(1), std::abs(sum) * T(0.159154943091895335769));  // 1 / (2 pi)
}

/// The same form factor with Sutherland-Hodgman's vertex list and the exact edge term (atan2):
/// the ground truth for polygon_form_factor's stated accuracy (GLSL twin too).
template <typename T, glm::qualifier Q>
T polygon_form_factor_exact(const glm::vec<3, T, Q>& x, const glm::vec<3, T, Q>& n, const glm::vec<3, T, Q>& c0, const glm::vec<3, T, Q>& c1,
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
  for (int k = 0; k < count; ++k) sum += detail::lambert_edge_exact(clipped[k], clipped[(k + 1) % count], n);
  return glm::min(T(1), std::abs(sum) * T(0.159154943091895335769));  // 1 / (2 pi)
}

/// The paper's variant: no clipping, counter-clockwise quads seen from x, the sum clamped at 0.
template <typename T, glm::qualifier Q>
T polygon_form_factor_unclipped(const glm::vec<3, T, Q>& x, const glm::vec<3, T, Q>& n, const glm::vec<3, T, Q>& c0,
                                const glm::vec<3, T, Q>& c1, const glm::vec<3, T, Q>& c2, const glm::vec<3, T, Q>& c3) {
  const glm::vec<3, T, Q> r[4] = {c0 - x, c1 - x, c2 - x, c3 - x};
  T sum = T(0);
  for (int k = 0; k < 4; ++k) sum += detail::lambert_edge(r[k], detail::inverse_length(r[k]), r[(k + 1) % 4], detail::inverse_length(r[(k + 1) % 4]), n);
  // Counter-clockwise seen from x makes each <n, R_l x R_l+1> negative for a quad above the
  // plane: the paper's sign convention is the opposite of the cross product's.
  return glm::max(T(0), -sum) * T(0.159154943091895335769);
}

}  // namespace vplkit
