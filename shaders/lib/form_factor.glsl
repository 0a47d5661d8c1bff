// GLSL twin of include/vplkit/form_factor.hpp: point-to-point and polygon-to-point form factors
// ([FG]), the polygon clipped at the tangent plane, and the exact form it is held to.
#ifndef VPLKIT_FORM_FACTOR_GLSL
#define VPLKIT_FORM_FACTOR_GLSL

float point_form_factor(vec3 x, vec3 n, vec3 y, vec3 ny) {
  vec3 d = y - x;
  float r2 = dot(d, d);
  if (!(r2 > 0.0)) return 0.0;
  float cos_x = max(0.0, dot(n, d));
  float cos_y = max(0.0, -dot(ny, d));
  return (cos_x / r2) * (cos_y / r2) * 0.318309886183790671538;
}

// acos(x) / sqrt(1 - x) on [0, 1]: Abramowitz and Stegun 4.4.46 (see the C++ twin for the bound).
float acos_over_sqrt_one_minus(float x) {
  return 1.5707963050 +
         x * (-0.2145988016 +
              x * (0.0889789874 + x * (-0.0501743046 + x * (0.0308918810 + x * (-0.0170881256 + x * (0.0066700901 + x * -0.0012624911))))));
}

// gamma <n, unit(a x b)> from cos(gamma), without atan2 (see the C++ twin).
float lambert_edge(vec3 a, float inverse_length_a, vec3 b, float inverse_length_b, vec3 n) {
  vec3 u = a * inverse_length_a, v = b * inverse_length_b, half_sum = (u + v) * 0.5;
  float x = clamp(dot(u, v), -1.0, 1.0);
  float ax = abs(x);
  float p = acos_over_sqrt_one_minus(ax);
  float inverse_sqrt_one_plus_x = 1.0 / sqrt(max(2.0 * dot(half_sum, half_sum), 1e-30));
  float inverse_sqrt_one_plus_ax = 1.0 / sqrt(1.0 + ax);
  float gamma_over_sine = x >= 0.0 ? p * inverse_sqrt_one_plus_x
                                   : (3.14159265358979323846 * inverse_sqrt_one_plus_x - p) * inverse_sqrt_one_plus_ax;
  float term = gamma_over_sine * dot(n, cross(u, v));
  return clamp(term, -3.14159265358979323846, 3.14159265358979323846);
}

float inverse_length(vec3 v) {
  float length_squared = dot(v, v);
  return length_squared > 0.0 ? 1.0 / sqrt(length_squared) : 0.0;
}

// Sutherland-Hodgman's clipped polygon summed edge by edge, without its vertex list (see the C++
// twin): each edge's part above the plane, then the closing edges from each exit to the next entry.
// The same arithmetic as the C++ twin; two forms differ for SIMD rasterisers such as llvmpipe,
// which run an `if` under a lane mask whatever the lanes decide but leave a loop once no lane
// needs another trip: the quad's edges run in a loop of `any_above ? 1 : 0` trips, the closing
// edges in a loop of `exit_count` trips, so that a quad below the horizon, or one that does not
// cross it, costs none of their terms when its neighbouring fragments agree (they mostly do).
float polygon_form_factor(vec3 x, vec3 n, vec3 c0, vec3 c1, vec3 c2, vec3 c3) {
  vec3 corners[4] = vec3[4](c0 - x, c1 - x, c2 - x, c3 - x);
  float heights[4] = float[4](dot(n, corners[0]), dot(n, corners[1]), dot(n, corners[2]), dot(n, corners[3]));
  bool any_above = heights[0] >= 0.0 || heights[1] >= 0.0 || heights[2] >= 0.0 || heights[3] >= 0.0;
  float sum = 0.0;
  for (int once = 0; once < (any_above ? 1 : 0); ++once) {
    float inverse_lengths[4] = float[4](inverse_length(corners[0]), inverse_length(corners[1]), inverse_length(corners[2]), inverse_length(corners[3]));
    vec3 exit0 = vec3(0.0), exit1 = vec3(0.0), entry0 = vec3(0.0), entry1 = vec3(0.0);
    int exit_count = 0, entry_count = 0;
    bool exit_first = false;
    for (int k = 0; k < 4; ++k) {
      int next = (k + 1) & 3;
      vec3 p = corners[k];
      vec3 q = corners[next];
      bool p_above = heights[k] >= 0.0, q_above = heights[next] >= 0.0;
      bool crosses = p_above != q_above;
      vec3 m = p + (q - p) * (crosses ? heights[k] / (heights[k] - heights[next]) : 0.0);
      float inverse_length_m = inverse_length(m);
      float term = lambert_edge(p_above ? p : m, p_above ? inverse_lengths[k] : inverse_length_m, q_above ? q : m,
                                q_above ? inverse_lengths[next] : inverse_length_m, n);
      sum += (p_above || q_above) ? term : 0.0;
      bool leaves = crosses && p_above, enters = crosses && q_above;
      exit_first = exit_first || (leaves && exit_count == 0 && entry_count == 0);
      exit1 = leaves && exit_count == 1 ? m : exit1;
      exit0 = leaves && exit_count == 0 ? m : exit0;
      entry1 = enters && entry_count == 1 ? m : entry1;
      entry0 = enters && entry_count == 0 ? m : entry0;
      exit_count += leaves ? 1 : 0;
      entry_count += enters ? 1 : 0;
    }
    for (int c = 0; c < exit_count; ++c) {
      vec3 from = c == 0 ? exit0 : exit1;
      vec3 to = (c == 0) == (exit_first || exit_count == 1) ? entry0 : entry1;
      sum += lambert_edge(from, inverse_length(from), to, inverse_length(to), n);
    }
  }
  return min(1.0, abs(sum) * 0.159154943091895335769);
}

// The exact form (atan2, Sutherland-Hodgman's vertex list): the C++ twin's ground truth, kept in
// GLSL for callers that need F to the last bit more than speed, and for bench/glsl_kernels.cpp.
float lambert_edge_exact(vec3 a, vec3 b, vec3 n) {
  vec3 c = cross(a, b);
  float sine = length(c);
  if (!(sine > 0.0)) return 0.0;
  float gamma = atan(sine, dot(a, b));
  return gamma * (dot(n, c) / sine);
}

float polygon_form_factor_exact(vec3 x, vec3 n, vec3 c0, vec3 c1, vec3 c2, vec3 c3) {
  vec3 corners[4] = vec3[4](c0 - x, c1 - x, c2 - x, c3 - x);
  vec3 clipped[8] = vec3[8](vec3(0.0), vec3(0.0), vec3(0.0), vec3(0.0), vec3(0.0), vec3(0.0), vec3(0.0), vec3(0.0));
  int count = 0;
  for (int k = 0; k < 4; ++k) {
    vec3 p = corners[k];
    vec3 q = corners[(k + 1) % 4];
    float hp = dot(n, p), hq = dot(n, q);
    if (hp >= 0.0) clipped[count++] = p;
    if ((hp >= 0.0) != (hq >= 0.0)) clipped[count++] = p + (q - p) * (hp / (hp - hq));
  }
  float sum = 0.0;
  for (int k = 0; k < count; ++k) sum += lambert_edge_exact(clipped[k], clipped[(k + 1) % count], n);
  return min(1.0, abs(sum) * 0.159154943091895335769);
}

float polygon_form_factor_unclipped(vec3 x, vec3 n, vec3 c0, vec3 c1, vec3 c2, vec3 c3) {
  vec3 r[4] = vec3[4](c0 - x, c1 - x, c2 - x, c3 - x);
  float sum = 0.0;
  for (int k = 0; k < 4; ++k) sum += lambert_edge(r[k], inverse_length(r[k]), r[(k + 1) % 4], inverse_length(r[(k + 1) % 4]), n);
  return max(0.0, -sum) * 0.159154943091895335769;
}

#endif
