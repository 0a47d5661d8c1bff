// GLSL twin of include/vplkit/cube_map.hpp: the face of a point light's cube of RSMs and shadow
// maps that a direction falls in, and each face's axis and up vector (OpenGL's cube map order).
#ifndef VPLKIT_CUBE_MAP_GLSL
#define VPLKIT_CUBE_MAP_GLSL

int cube_face_of(vec3 d) {
  vec3 a = abs(d);
  if (a.x >= a.y && a.x >= a.z) return d.x >= 0.0 ? 0 : 1;
  if (a.y >= a.z) return d.y >= 0.0 ? 2 : 3;
  return d.z >= 0.0 ? 4 : 5;
}

vec3 cube_face_axis(int face) {
  int f = clamp(face, 0, 5);
  vec3 axis = vec3(0.0);
  axis[f / 2] = (f % 2 == 0) ? 1.0 : -1.0;
  return axis;
}

vec3 cube_face_up(int face) {
  int f = clamp(face, 0, 5);
  if (f == 2) return vec3(0.0, 0.0, 1.0);
  if (f == 3) return vec3(0.0, 0.0, -1.0);
  return vec3(0.0, -1.0, 0.0);
}

#endif
