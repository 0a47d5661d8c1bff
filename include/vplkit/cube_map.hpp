// The six faces of a point light's omnidirectional RSM and shadow map: each face is a 90-degree
// perspective view (tan_half_fov = 1) along one axis, in OpenGL's cube map order and orientation
// (GL_TEXTURE_CUBE_MAP_POSITIVE_X + face: 0 +x, 1 -x, 2 +y, 3 -y, 4 +z, 5 -z). A direction from
// the light belongs to the face of its major axis, so the six frusta tile the sphere and every
// receiver reads exactly one face's shadow map (the original RSM paper's cube map for point lights).
//
// GLSL twin: shaders/lib/cube_map.glsl.
#pragma once

#include <cmath>

#include <glm/glm.hpp>

namespace vplkit {

/// The face whose frustum contains direction `d` (from the light; need not be unit length): the
/// axis of d's largest absolute component, its sign choosing between the two faces on that axis.
/// Ties go to x before y before z, so a direction on a face's border has exactly one face; a zero
/// vector is face 0 (+x).
template <typename T, glm::qualifier Q>
int cube_face_of(const glm::vec<3, T, Q>& d) {
  const glm::vec<3, T, Q> a = glm::abs(d);
  if (a.x >= a.y && a.x >= a.z) return d.x >= T(0) ? 0 : 1;
  if (a.y >= a.z) return d.y >= T(0) ? 2 : 3;
  return d.z >= T(0) ? 4 : 5;
}

/// The unit direction face `face` looks along (its frustum's axis); face outside 0..5 is clamped.
template <typename T>
glm::vec<3, T> cube_face_axis(int face) {
  const int f = glm::clamp(face, 0, 5);
  glm::vec<3, T> axis(0);
  axis[f / 2] = (f % 2 == 0) ? T(1) : T(-1);
  return axis;
}

/// The up vector of face `face` (a lookAt up, orthogonal to its axis), OpenGL's cube map
/// orientation: -y for the four side faces, +z for +y and -z for -y.
template <typename T>
glm::vec<3, T> cube_face_up(int face) {
  const int f = glm::clamp(face, 0, 5);
  if (f == 2) return glm::vec<3, T>(0, 0, 1);
  if (f == 3) return glm::vec<3, T>(0, 0, -1);
  return glm::vec<3, T>(0, -1, 0);
}

}  // namespace vplkit
