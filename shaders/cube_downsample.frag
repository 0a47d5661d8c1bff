#version 330 core
// Final gathering, pass 2: each face averaged down from face_size^2 to M^2 texels, radiance and
// distance alike ([FG], section 4), each texel weighted by its solid angle
// (lib/final_gather_downsample.glsl). Faces lie side by side: texel (face * size + i, j).
#include "lib/final_gather_downsample.glsl"

uniform sampler2D faces;
uniform int face_size;
uniform int resolution;
layout(location = 0) out vec4 averaged;

vec4 full_cube_fetch(int face, int i, int j) { return texelFetch(faces, ivec2(face * face_size + i, j), 0); }

void main() {
  ivec2 texel = ivec2(gl_FragCoord.xy);
  int face = texel.x / resolution;
  averaged = cube_downsample_texel(face, texel.x - face * resolution, texel.y, face_size, resolution);
}
