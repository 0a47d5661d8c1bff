#version 330 core
// Final gathering, pass 2: each face averaged down from face_size^2 to M^2 texels, radiance and
// distance alike ([FG], section 4). Faces lie side by side: texel (face * size + i, j).
uniform sampler2D faces;
uniform int face_size;
uniform int resolution;
layout(location = 0) out vec4 averaged;

void main() {
  ivec2 texel = ivec2(gl_FragCoord.xy);
  int face = texel.x / resolution;
  int block = face_size / resolution;
  ivec2 first = ivec2(face * face_size + (texel.x - face * resolution) * block, texel.y * block);
  vec4 sum = vec4(0.0);
  for (int y = 0; y < block; ++y)
    for (int x = 0; x < block; ++x) sum += texelFetch(faces, first + ivec2(x, y), 0);
  averaged = sum / float(block * block);
}
