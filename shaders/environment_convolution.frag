#version 330 core
// Final gathering, the classic baseline: an irradiance environment map, E(o, n) for the normal n
// of each texel's centre direction, K x K per face, gathered at the reference point itself (a
// perfectly convolved map: right at o only).
#define VPLKIT_FORM_FACTOR 0
#include "lib/final_gather.glsl"

uniform sampler2D small_cube;
uniform int resolution;
uniform int environment_resolution;
uniform vec3 reference_point;
layout(location = 0) out vec4 environment;

vec4 small_cube_fetch(int face, int i, int j) { return texelFetch(small_cube, ivec2(face * resolution + i, j), 0); }

void main() {
  ivec2 texel = ivec2(gl_FragCoord.xy);
  int face = texel.x / environment_resolution;
  vec3 n = normalize(cube_texel_direction(face, texel.x - face * environment_resolution, texel.y, environment_resolution));
  environment = vec4(final_gather_irradiance(reference_point, n, reference_point, resolution), 1.0);
}
