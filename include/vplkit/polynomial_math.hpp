// Sine and cosine from +, -, * and floor only, so that GLSL and C++ compute the same bits.
//
// GPU sin/cos (and llvmpipe's) are approximations that differ from the C library in the last
// bits. The sampling patterns of [RSMV] turn angles into RSM texel offsets, and a texel index
// taken with floor() flips when its offset moves by one ulp across an integer: with builtin
// trigonometry, about 2% of gathered pixels would fetch a different pixel light on the GPU than
// on the CPU. These polynomials are accurate to a few 1e-7 (float), more than the patterns
// need, and are the same arithmetic on both sides.
//
// GLSL twin: shaders/lib/polynomial_math.glsl.
#pragma once

#include <cmath>

#include <glm/glm.hpp>

namespace vplkit {

/// (cos 2 pi turns, sin 2 pi turns) for any finite angle in turns. The angle is reduced to half
/// a turn either way, halved to [-pi/2, pi/2], where Taylor polynomials of degree 13 (sin) and
/// 14 (cos) are exact to 1e-9, and doubled back: cos = c^2 - s^2, sin = 2 s c.
/// Callers pass turns rather than radians where they can: a shader compiler may fold a chain
/// of constant multiplies (2 pi * x * 1 / (2 pi)) that C++ rounds step by step (GLSL allows it),
/// and then the two sides differ by an ulp of the angle.
/// (Declared inline: GCC's size limit for inlining an undeclared template kept it out of
/// rsm_gather_batch.hpp's lane loop, which then did not vectorise.)
template <typename T>
inline glm::vec<2, T> direction_from_turns(T turns) {
  const T reduced_turns = turns - std::floor(turns + T(0.5));
  const T half_angle = reduced_turns * T(3.14159265358979323846);  // (2 pi * reduced) / 2
  const T h2 = half_angle * half_angle;
  const T s = half_angle * (T(1) - h2 * T(0.166666666666666667) *
                                 (T(1) - h2 * T(0.05) *
                                             (T(1) - h2 * T(0.0238095238095238095) *
                                                         (T(1) - h2 * T(0.0138888888888888889) *
                                                                     (T(1) - h2 * T(0.00909090909090909091) *
                                                                                 (T(1) - h2 * T(0.00641025641025641026)))))));
  const T c = T(1) - h2 * T(0.5) *
                         (T(1) - h2 * T(0.0833333333333333333) *
                                     (T(1) - h2 * T(0.0333333333333333333) *
                                                 (T(1) - h2 * T(0.0178571428571428571) *
                                                             (T(1) - h2 * T(0.0111111111111111111) *
                                                                         (T(1) - h2 * T(0.00757575757575757576) *
                                                                                     (T(1) - h2 * T(0.00549450549450549451)))))));
  return {c * c - s * s, T(2) * s * c};
}

/// (cos angle, sin angle) for an angle in radians: direction_from_turns(angle / (2 pi)).
template <typename T>
glm::vec<2, T> direction_from_angle(T angle) {
  return direction_from_turns(angle * T(0.159154943091895335769));
}

}  // namespace vplkit
