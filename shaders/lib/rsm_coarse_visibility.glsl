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
  mat4 face_from_light[6];
};

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
  for (int i = 0; i < VPLKIT_COARSE_VISIBILITY_SAMPLES; ++i) {
    float t = 0.1 + 0.8 * ((float(i) + 0.5) / float(VPLKIT_COARSE_VISIBILITY_SAMPLES));
    vec3 p = x_c + t * (x - x_c);
    int face = cube_face_of(transform_direction(frames.cube_from_light, p));
    if (behind_seen_surface(transform_point(frames.face_from_light[face], p), face, unprojection, rsm_size)) return 0.0;
  }
  return 1.0;
}

#endif
