// GLSL twin of include/vplkit/rsm_coarse_visibility.hpp:
// a point light's coarse lights hidden by the light's six depth maps (see the C++ twin for why).
// The including shader defines `float rsm_face_depth(int face, ivec2 texel)`: face's stored
// eye-space z (< 0: a surface; >= 0: none).
#ifndef VPLKIT_RSM_COARSE_VISIBILITY_GLSL
#define VPLKIT_RSM_COARSE_VISIBILITY_GLSL

#include "lib/cube_map.glsl"
#include "lib/rsm_packing.glsl"
#include "lib/transform.glsl"

#define VPLKIT_COARSE_VISIBILITY_SAMPLES 4
#define VPLKIT_COARSE_VISIBILITY_SLAB_NEAR 0.01
#define VPLKIT_COARSE_VISIBILITY_SLAB_FAR 0.25

struct cube_depth_frames {
  mat4 cube_from_light;
};

vec3 cube_face_eye(vec3 d, out int face) {
  face = cube_face_of(d);  // the one face selection (ties included), lib/cube_map.glsl's
  vec3 a = abs(d);
  bool on_x = face < 2;
  bool on_y = face == 2 || face == 3;
  bool on_z = face > 3;
  bool positive = face % 2 == 0;
  float sgn = positive ? 1.0 : -1.0;
  float x = on_x ? -sgn * d.z : (on_z ? sgn * d.x : d.x);
  float y = on_y ? sgn * d.z : -d.y;
  float z = on_x ? -a.x : (on_y ? -a.y : -a.z);
  return vec3(x, y, z);
}

float rsm_face_depth(int face, ivec2 texel);

bool behind_seen_surface(vec3 q, int face, rsm_unprojection unprojection, ivec2 rsm_size) {
  if (!(q.z < 0.0)) return false;
  vec2 ray = vec2(q.x, q.y) / -q.z;
  ivec2 texel = ivec2(floor((ray - unprojection.ray_origin) / unprojection.ray_step + 0.5));
  if (texel.x < 0 || texel.y < 0 || texel.x >= rsm_size.x || texel.y >= rsm_size.y) return false;
  float z = rsm_face_depth(face, texel);
  if (!(z < 0.0)) return false;
  return -q.z > -z * (1.0 + VPLKIT_COARSE_VISIBILITY_SLAB_NEAR) && -q.z < -z * (1.0 + VPLKIT_COARSE_VISIBILITY_SLAB_FAR);
}

float coarse_light_cube_visibility(vec3 x, vec3 x_c, cube_depth_frames frames, rsm_unprojection unprojection, ivec2 rsm_size) {
  vec3 c = transform_direction(frames.cube_from_light, x_c);
  vec3 r = transform_direction(frames.cube_from_light, x);
  for (int i = 0; i < VPLKIT_COARSE_VISIBILITY_SAMPLES; ++i) {
    float t = 0.1 + 0.8 * ((float(i) + 0.5) / float(VPLKIT_COARSE_VISIBILITY_SAMPLES));
    int face = 0;
    vec3 q = cube_face_eye(c + t * (r - c), face);
    if (behind_seen_surface(q, face, unprojection, rsm_size)) return 0.0;
  }
  return 1.0;
}

#endif
