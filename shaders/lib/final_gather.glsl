// GLSL twin of include/vplkit/final_gather.hpp: cube-map geometry and the final-gathering sum of
// [FG]. Define VPLKIT_FORM_FACTOR (0 polygon, 1 point) and provide
// `vec4 small_cube_fetch(int face, int i, int j)` ([radiance | distance]).
#ifndef VPLKIT_FINAL_GATHER_GLSL
#define VPLKIT_FINAL_GATHER_GLSL

// Required (no default): an undefined name in `#if` is an error in GLSL ES, so a forgotten define
// must stop here with a message that names it, not at the `#if` below.
#ifndef VPLKIT_FORM_FACTOR
#error "define VPLKIT_FORM_FACTOR (0 polygon, 1 point) before including lib/final_gather.glsl"
#endif

#include "lib/form_factor.glsl"

vec4 small_cube_fetch(int face, int i, int j);

void cube_face_axes(int face, out vec3 major, out vec3 s_axis, out vec3 t_axis) {
  if (face == 0) { major = vec3(1.0, 0.0, 0.0); s_axis = vec3(0.0, 0.0, -1.0); t_axis = vec3(0.0, -1.0, 0.0); }
  else if (face == 1) { major = vec3(-1.0, 0.0, 0.0); s_axis = vec3(0.0, 0.0, 1.0); t_axis = vec3(0.0, -1.0, 0.0); }
  else if (face == 2) { major = vec3(0.0, 1.0, 0.0); s_axis = vec3(1.0, 0.0, 0.0); t_axis = vec3(0.0, 0.0, 1.0); }
  else if (face == 3) { major = vec3(0.0, -1.0, 0.0); s_axis = vec3(1.0, 0.0, 0.0); t_axis = vec3(0.0, 0.0, -1.0); }
  else if (face == 4) { major = vec3(0.0, 0.0, 1.0); s_axis = vec3(1.0, 0.0, 0.0); t_axis = vec3(0.0, -1.0, 0.0); }
  else { major = vec3(0.0, 0.0, -1.0); s_axis = vec3(-1.0, 0.0, 0.0); t_axis = vec3(0.0, -1.0, 0.0); }
}

vec3 cube_face_direction(int face, vec2 uv) {
  vec3 major, s_axis, t_axis;
  cube_face_axes(face, major, s_axis, t_axis);
  return major + s_axis * uv.x + t_axis * uv.y;
}

vec3 cube_corner_direction(int face, int ci, int cj, int resolution) {
  return cube_face_direction(face, vec2(float(2 * ci) / float(resolution) - 1.0, float(2 * cj) / float(resolution) - 1.0));
}

vec3 cube_texel_direction(int face, int i, int j, int resolution) {
  return cube_face_direction(face, vec2(float(2 * i + 1) / float(resolution) - 1.0, float(2 * j + 1) / float(resolution) - 1.0));
}

ivec3 cube_texel_of(vec3 direction, int resolution) {
  vec3 a = abs(direction);
  int face;
  if (a.x >= a.y && a.x >= a.z) face = direction.x >= 0.0 ? 0 : 1;
  else if (a.y >= a.z) face = direction.y >= 0.0 ? 2 : 3;
  else face = direction.z >= 0.0 ? 4 : 5;
  vec3 major, s_axis, t_axis;
  cube_face_axes(face, major, s_axis, t_axis);
  float depth = dot(direction, major);
  vec2 uv = depth > 0.0 ? vec2(dot(direction, s_axis) / depth, dot(direction, t_axis) / depth) : vec2(0.0);
  ivec2 texel = clamp(ivec2(floor((uv + 1.0) * 0.5 * float(resolution))), ivec2(0), ivec2(resolution - 1));
  return ivec3(face, texel.x, texel.y);
}

float cube_corner_distance(int face, int ci, int cj, int resolution) {
  vec3 major, s_axis, t_axis;
  cube_face_axes(face, major, s_axis, t_axis);
  float sum = 0.0;
  for (int k = 0; k < 4; ++k) {
    // Whole numbers, exact: no division, which GLSL need not round correctly (see the C++ twin).
    int du = (k & 1) != 0 ? 1 : -1, dv = (k & 2) != 0 ? 1 : -1;
    vec3 direction = major * float(resolution) + s_axis * float(2 * ci - resolution + du) + t_axis * float(2 * cj - resolution + dv);
    ivec3 texel = cube_texel_of(direction, resolution);
    sum += small_cube_fetch(texel.x, texel.y, texel.z).w;
  }
  return sum * 0.25;
}

vec3 final_gather_irradiance(vec3 x, vec3 n, vec3 o, int resolution) {
  vec3 irradiance = vec3(0.0);
  for (int face = 0; face < 6; ++face) {
    for (int j = 0; j < resolution; ++j) {
      for (int i = 0; i < resolution; ++i) {
        vec4 texel = small_cube_fetch(face, i, j);
        vec3 corner[4];
        for (int k = 0; k < 4; ++k) {
          int ci = i + ((k == 1 || k == 2) ? 1 : 0), cj = j + (k >= 2 ? 1 : 0);
          corner[k] = o + normalize(cube_corner_direction(face, ci, cj, resolution)) * cube_corner_distance(face, ci, cj, resolution);
        }
        vec3 radiance = texel.xyz;
#if VPLKIT_FORM_FACTOR == 0
        irradiance += radiance * (3.14159265358979323846 * polygon_form_factor(x, n, corner[0], corner[1], corner[2], corner[3]));
#else
        vec3 y = o + normalize(cube_texel_direction(face, i, j, resolution)) * texel.w;
        vec3 diagonals = cross(corner[2] - corner[0], corner[3] - corner[1]);
        float twice_area = length(diagonals);
        if (!(twice_area > 0.0)) continue;
        vec3 normal = diagonals / twice_area;
        if (dot(normal, o - y) < 0.0) normal = -normal;
        irradiance += radiance * (3.14159265358979323846 * point_form_factor(x, n, y, normal) * (0.5 * twice_area));
#endif
      }
    }
  }
  return irradiance;
}

#endif
