// GLSL twin of include/vplkit/final_gather_downsample.hpp: the small distance cube map of [FG],
// each texel the solid-angle-weighted mean of its block of the full-size map (see there why
// weighted). The including shader provides `vec4 full_cube_fetch(int face, int i, int j)`
// ([radiance | distance] of the full map's texel (i, j) of face `face`).
#ifndef VPLKIT_FINAL_GATHER_DOWNSAMPLE_GLSL
#define VPLKIT_FINAL_GATHER_DOWNSAMPLE_GLSL

#include "lib/direct_light.glsl"

vec4 full_cube_fetch(int face, int i, int j);

float cube_face_texel_solid_angle(int i, int j, int face_size) {
  vec2 ndc = vec2(float(2 * i + 1) / float(face_size) - 1.0, float(2 * j + 1) / float(face_size) - 1.0);
  return perspective_texel_solid_angle(ndc, 1.0, ivec2(face_size));
}

vec4 cube_downsample_texel(int face, int i, int j, int face_size, int resolution) {
  int block = face_size / resolution;
  vec4 sum = vec4(0.0);
  float weight_sum = 0.0;
  for (int y = j * block; y < (j + 1) * block; ++y) {
    for (int x = i * block; x < (i + 1) * block; ++x) {
      float weight = cube_face_texel_solid_angle(x, y, face_size);
      sum += full_cube_fetch(face, x, y) * weight;
      weight_sum += weight;
    }
  }
  return sum / weight_sum;
}

#endif
