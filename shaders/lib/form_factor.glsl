// GLSL twin of include/vplkit/form_factor.hpp: point-to-point and polygon-to-point form factors
// ([FG]), the polygon clipped at the tangent plane.
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

float lambert_edge(vec3 a, vec3 b, vec3 n) {
  vec3 c = cross(a, b);
  float sine = length(c);
  if (!(sine > 0.0)) return 0.0;
  float gamma = atan(sine, dot(a, b));
  return gamma * (dot(n, c) / sine);
}

float polygon_form_factor(vec3 x, vec3 n, vec3 c0, vec3 c1, vec3 c2, vec3 c3) {
  vec3 corners[4] = vec3[4](c0 - x, c1 - x, c2 - x, c3 - x);
  // Each edge adds at most 2 vertices: 8 when a non-convex or non-planar quad crosses the plane 4
  // times (a convex quad crosses it at most twice: 5).
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
  for (int k = 0; k < count; ++k) sum += lambert_edge(clipped[k], clipped[(k + 1) % count], n);
  return min(1.0, abs(sum) * 0.159154943091895335769);
}

float polygon_form_factor_unclipped(vec3 x, vec3 n, vec3 c0, vec3 c1, vec3 c2, vec3 c3) {
  vec3 r[4] = vec3[4](c0 - x, c1 - x, c2 - x, c3 - x);
  float sum = 0.0;
  for (int k = 0; k < 4; ++k) sum += lambert_edge(r[k], r[(k + 1) % 4], n);
  return max(0.0, -sum) * 0.159154943091895335769;
}

#endif
