// A point light's coarse lights (rsm_coverage.hpp) hidden by the light's own depth maps, the six
// faces of its cube of RSMs.
//
// The coverage adds its coarse lights without visibility, and a point light's indirect light
// rides mostly on them (78 % in docs/scenes.md's workshop corner), so the lit side of a partition
// lit the floor behind it. The RSM technique already holds what the light sees: each face's
// eye-space depth. A coarse light at x_c is hidden from the receiver x when one of K points of the
// segment, p = x_c + t (x - x_c) for t = 0.1 + 0.8 (i + 0.5) / K, lies just behind the surface the
// light sees in p's direction: 1 % to 25 % of that surface's depth behind it (a slab). A test of
// "behind by more than a thickness" alone hides every segment that ends in the light's shadow,
// the receivers the coarse lights are meant for (measured: workshop corner 0.952 instead of the
// reference's 1, every frame lower); the slab lets those through and still catches a wall a
// segment crosses when a sample falls within the slab behind it. The ends stay out (t in
// [0.1, 0.9]): the coarse light is a flux-weighted mean of its block, off the surfaces at a corner.
//
// Each point is looked up in the face its direction falls in (cube_face_of), every face being
// symmetric with a 90-degree field of view (the gathering face's unprojection serves them all);
// `face_depth(face, texel)` returns that face's stored eye-space z (< 0: a surface; >= 0: none).
// The point's eye coordinates in that face are a sign-and-swap of its light-centred direction
// (cube_face_eye), not a product with the face's view matrix: picking that matrix per point (a
// dynamically indexed uniform array, a per-lane gather on llvmpipe) was most of the test's cost
// (docs/scenes.md).
// A spot's or a sun's single map does not see the segment's part outside its frustum (measured no
// better, docs/scenes.md): the gather uses this for point lights only.
//
// Used by gather_rsm's coarse visibility for every visibility but the voxel grid's (rsm_gather.hpp;
// the CPU mirror fills it from the six faces' RSMs) and by gather.frag's
// rsm_depth_coarse_visibility; errata RSMV-14.
// GLSL twin: shaders/lib/rsm_coarse_visibility.glsl.
#pragma once

#include <glm/glm.hpp>

#include <vplkit/cube_map.hpp>
#include <vplkit/rsm_packing.hpp>
#include <vplkit/transform.hpp>

namespace vplkit {

/// Points of the segment tested (K) and the slab behind the stored depth, as shares of it.
inline constexpr int coarse_visibility_samples = 4;
inline constexpr float coarse_visibility_slab_near = 0.01f;
inline constexpr float coarse_visibility_slab_far = 0.25f;

/// The gathering face's eye space to the cube's axes (the world's, rotated; the light at the
/// origin). Every face's eye space follows from the cube's axes by cube_face_eye.
template <typename T>
struct cube_depth_frames {
  glm::mat<4, 4, T> cube_from_light{T(1)};
};

/// Direction `d` from the light (the cube's axes) in the eye space of the face it falls in, and
/// that face (`face`, cube_face_of's, ties included). Face g is glm::lookAt(0, cube_face_axis(g),
/// cube_face_up(g)) (rsm_pipeline's make_light_frustum): eye x along cross(axis, up), y along up,
/// z along -axis, so z = -|major component| and x, y are the other two components, signed per
/// face (OpenGL's cube map table: +x (-dz, -dy), -x (dz, -dy), +y (dx, dz), -y (dx, -dz),
/// +z (dx, -dy), -z (-dx, -dy)). Selects and negations only, no matrix.
template <typename T>
glm::vec<3, T> cube_face_eye(const glm::vec<3, T>& d, int& face) {
  face = cube_face_of(d);  // the one face selection (ties included), cube_map.hpp's
  const glm::vec<3, T> a = glm::abs(d);
  const bool on_x = face < 2;
  const bool on_y = face == 2 || face == 3;
  const bool on_z = face > 3;
  const bool positive = face % 2 == 0;
  const T sgn = positive ? T(1) : T(-1);
  const T x = on_x ? -sgn * d.z : (on_z ? sgn * d.x : d.x);
  const T y = on_y ? sgn * d.z : -d.y;
  const T z = on_x ? -a.x : (on_y ? -a.y : -a.z);
  return glm::vec<3, T>(x, y, z);
}

/// Whether eye-space point q of face `face` lies in the slab behind the surface that face sees
/// along q's ray.
template <typename T, typename FaceDepth>
bool behind_seen_surface(const glm::vec<3, T>& q, int face, const rsm_unprojection<T>& unprojection, glm::ivec2 rsm_size, FaceDepth&& face_depth) {
  if (!(q.z < T(0))) return false;
  const glm::vec<2, T> ray = glm::vec<2, T>(q.x, q.y) / -q.z;
  const glm::ivec2 texel = glm::ivec2(glm::floor((ray - unprojection.ray_origin) / unprojection.ray_step + T(0.5)));
  if (texel.x < 0 || texel.y < 0 || texel.x >= rsm_size.x || texel.y >= rsm_size.y) return false;
  const T z = face_depth(face, texel);
  if (!(z < T(0))) return false;
  return -q.z > -z * T(1.0 + coarse_visibility_slab_near) && -q.z < -z * T(1.0 + coarse_visibility_slab_far);
}

/// 0 when a point of the segment from coarse light x_c to receiver x (the gathering face's eye
/// space) lies in the slab behind what the light sees, else 1.
template <typename T, typename FaceDepth>
T coarse_light_cube_visibility(const glm::vec<3, T>& x, const glm::vec<3, T>& x_c, const cube_depth_frames<T>& frames,
                               const rsm_unprojection<T>& unprojection, glm::ivec2 rsm_size, FaceDepth&& face_depth) {
  // The segment's ends on the cube's axes once: the rotation is linear, so its points follow.
  const glm::vec<3, T> c = transform_direction(frames.cube_from_light, x_c);
  const glm::vec<3, T> r = transform_direction(frames.cube_from_light, x);
  for (int i = 0; i < coarse_visibility_samples; ++i) {
    const T t = T(0.1) + T(0.8) * ((T(i) + T(0.5)) / T(coarse_visibility_samples));
    int face = 0;
    const glm::vec<3, T> q = cube_face_eye(c + t * (r - c), face);
    if (behind_seen_surface(q, face, unprojection, rsm_size, face_depth)) return T(0);
  }
  return T(1);
}

}  // namespace vplkit
