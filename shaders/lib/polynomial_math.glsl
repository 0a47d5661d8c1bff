// GLSL twin of include/vplkit/polynomial_math.hpp: sine and cosine from +, -, *, floor only.
#ifndef VPLKIT_POLYNOMIAL_MATH_GLSL
#define VPLKIT_POLYNOMIAL_MATH_GLSL

vec2 direction_from_turns(float turns) {
  float reduced_turns = turns - floor(turns + 0.5);
  float half_angle = reduced_turns * 3.14159265358979323846;
  float h2 = half_angle * half_angle;
  float s = half_angle * (1.0 - h2 * 0.166666666666666667 *
                                    (1.0 - h2 * 0.05 *
                                               (1.0 - h2 * 0.0238095238095238095 *
                                                          (1.0 - h2 * 0.0138888888888888889 *
                                                                     (1.0 - h2 * 0.00909090909090909091 *
                                                                                (1.0 - h2 * 0.00641025641025641026))))));
  float c = 1.0 - h2 * 0.5 *
                      (1.0 - h2 * 0.0833333333333333333 *
                                 (1.0 - h2 * 0.0333333333333333333 *
                                            (1.0 - h2 * 0.0178571428571428571 *
                                                       (1.0 - h2 * 0.0111111111111111111 *
                                                                  (1.0 - h2 * 0.00757575757575757576 *
                                                                             (1.0 - h2 * 0.00549450549450549451))))));
  return vec2(c * c - s * s, 2.0 * s * c);
}

vec2 direction_from_angle(float angle) { return direction_from_turns(angle * 0.159154943091895335769); }

#endif
