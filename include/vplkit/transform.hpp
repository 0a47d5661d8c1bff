// Point transforms shared by the passes and their CPU mirrors, written as explicit sums in a
// fixed order so that GLSL and C++ round the same way: a point or a direction into a matrix's space, and its
// projection onto a map (RSM, shadow map) in texels.
//
// GLSL twin: shaders/lib/transform.glsl.
#pragma once

#include <glm/glm.hpp>

namespace vplkit {

/// p transformed by an affine matrix (the w row is ignored).
template <typename T>
glm::vec<3, T> transform_point(const glm::mat<4, 4, T>& m, const glm::vec<3, T>& p) {
  return glm::vec<3, T>(m[0]) * p.x + glm::vec<3, T>(m[1]) * p.y + glm::vec<3, T>(m[2]) * p.z + glm::vec<3, T>(m[3]);
}

/// v turned by an affine matrix's upper 3x3 (a direction: no translation).
template <typename T>
glm::vec<3, T> transform_direction(const glm::mat<4, 4, T>& m, const glm::vec<3, T>& v) {
  return glm::vec<3, T>(m[0]) * v.x + glm::vec<3, T>(m[1]) * v.y + glm::vec<3, T>(m[2]) * v.z;
}

/// The projection of a world point onto a size.x x size.y map rendered with view_projection,
/// in texels: ((ndc.xy + 1) / 2) * size.
template <typename T>
glm::vec<2, T> map_coordinate(const glm::mat<4, 4, T>& view_projection, const glm::vec<3, T>& p, const glm::ivec2& size) {
  const glm::vec<4, T> clip = view_projection[0] * p.x + view_projection[1] * p.y + view_projection[2] * p.z + view_projection[3];
  const glm::vec<2, T> ndc = glm::vec<2, T>(clip) / clip.w;
  return (ndc * T(0.5) + T(0.5)) * glm::vec<2, T>(size);
}

}  // namespace vplkit
