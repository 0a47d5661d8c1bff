// Diffuse final gathering from a distance cube map ([FG]): the environment of a dynamic
// object, seen from its reference point o, is stored as 6 faces of M x M texels holding the
// average radiance and the average distance from o of what each texel sees. Each texel stands
// for a quad area light whose corners lie along the texel's corner directions at the distances
// found there; a shaded point x gathers from all 6 M^2 quads.
//
// Cube-map geometry follows OpenGL's cube-map convention: face 0..5 = +x, -x, +y, -y, +z, -z,
// and texel (i, j) of face f covers (u, v) in [2i/M - 1, 2(i+1)/M - 1] x [2j/M - 1, ...] with
// the direction ma + u s + v t (the (s, t) axes of the GL specification's table). A face
// rendered with the view whose rows are (s, t, -ma) and a 90-degree projection puts texel
// (i, j) at pixel (i, j) of the render target, rows bottom-up.
//
// Corner distances: a corner is shared by up to four texels (three at a cube corner); its
// distance is the mean of the four texels found half a texel diagonally around it, across face
// edges where it lies on one (the paper takes them from the cube map's bilinear filtering).
//
// Irradiance at (x, n):
//   polygon:  E = sum pi L_i F(x, n, quad_i)                              (polygon_form_factor)
//   point:    E = sum pi L_i point_form_factor(x, n, y_i, n_i) A_i        (a virtual light per
//             texel at its centre direction and distance, with the quad's normal n_i derived from
//             its corners, turned towards o, and the quad's area A_i: no normal is stored)
// and the reflected radiance kd / pi * E. The classic baseline is the polygon gather evaluated at
// the reference point itself, E(o, n): a perfectly convolved environment map, exact at o only.
//
// The including shader provides `vec4 small_cube_fetch(int face, int i, int j)` ([radiance |
// distance]); C++ takes the same as a callable. GLSL twin: shaders/lib/final_gather.glsl.
#pragma once

#include <cmath>

#include <glm/glm.hpp>

#include <vplkit/form_factor.hpp>

namespace vplkit {

/// The face's major axis, s axis and t axis (OpenGL's cube-map table).
template <typename T>
void cube_face_axes(int face, glm::vec<3, T>& major, glm::vec<3, T>& s_axis, glm::vec<3, T>& t_axis) {
  if (face == 0) { major = {1, 0, 0}; s_axis = {0, 0, -1}; t_axis = {0, -1, 0}; }
  else if (face == 1) { major = {-1, 0, 0}; s_axis = {0, 0, 1}; t_axis = {0, -1, 0}; }
  else if (face == 2) { major = {0, 1, 0}; s_axis = {1, 0, 0}; t_axis = {0, 0, 1}; }
  else if (face == 3) { major = {0, -1, 0}; s_axis = {1, 0, 0}; t_axis = {0, 0, -1}; }
  else if (face == 4) { major = {0, 0, 1}; s_axis = {1, 0, 0}; t_axis = {0, -1, 0}; }
  else { major = {0, 0, -1}; s_axis = {-1, 0, 0}; t_axis = {0, -1, 0}; }
}

/// The (unnormalised) direction of face coordinate (u, v) in [-1, 1]^2.
template <typename T>
glm::vec<3, T> cube_face_direction(int face, const glm::vec<2, T>& uv) {
  glm::vec<3, T> major, s_axis, t_axis;
  cube_face_axes(face, major, s_axis, t_axis);
  return major + s_axis * uv.x + t_axis * uv.y;
}

/// Direction of corner (ci, cj), ci, cj in 0..M, of face `face` at resolution M.
template <typename T>
glm::vec<3, T> cube_corner_direction(int face, int ci, int cj, int resolution) {
  return cube_face_direction(face, glm::vec<2, T>(T(2 * ci) / T(resolution) - T(1), T(2 * cj) / T(resolution) - T(1)));
}

/// Direction of the centre of texel (i, j).
template <typename T>
glm::vec<3, T> cube_texel_direction(int face, int i, int j, int resolution) {
  return cube_face_direction(face, glm::vec<2, T>(T(2 * i + 1) / T(resolution) - T(1), T(2 * j + 1) / T(resolution) - T(1)));
}

/// The face and texel a direction falls in: (face, i, j). Ties between axes go to x, then y.
template <typename T>
glm::ivec3 cube_texel_of(const glm::vec<3, T>& direction, int resolution) {
  const glm::vec<3, T> a = glm::abs(direction);
  int face;
  if (a.x >= a.y && a.x >= a.z) face = direction.x >= T(0) ? 0 : 1;
  else if (a.y >= a.z) face = direction.y >= T(0) ? 2 : 3;
  else face = direction.z >= T(0) ? 4 : 5;
  glm::vec<3, T> major, s_axis, t_axis;
  cube_face_axes(face, major, s_axis, t_axis);
  const T depth = glm::dot(direction, major);
  // depth is the largest |component|: 0 only for the zero vector, whose 0/0 would reach the int
  // conversion below as NaN (undefined behaviour); it takes the face's centre instead.
  const glm::vec<2, T> uv = depth > T(0) ? glm::vec<2, T>(glm::dot(direction, s_axis) / depth, glm::dot(direction, t_axis) / depth) : glm::vec<2, T>(T(0));
  const glm::ivec2 texel = glm::clamp(glm::ivec2(glm::floor((uv + T(1)) * T(0.5) * T(resolution))), glm::ivec2(0), glm::ivec2(resolution - 1));
  return {face, texel.x, texel.y};
}

/// Distance from o of corner (ci, cj) of face `face`: the mean of the four texels around it.
template <typename T, typename Fetch>
T cube_corner_distance(int face, int ci, int cj, int resolution, Fetch&& fetch) {
  glm::vec<3, T> major, s_axis, t_axis;
  cube_face_axes(face, major, s_axis, t_axis);
  T sum = T(0);
  for (int k = 0; k < 4; ++k) {
    // The point half a texel diagonally off the corner, as a direction scaled by M (which
    // cube_texel_of ignores): whole numbers, exact on both twins. (u, v) = (2 ci +- 1) / M - 1
    // instead computed with a division, which GLSL need not round correctly (llvmpipe's 12.0 / 6.0
    // is not 2.0), moved the points at a cube's corners off the diagonal where two faces tie, and
    // the GPU read another of the three texels there than the CPU (test_parity_final_gather.cpp).
    const int du = (k & 1) ? 1 : -1, dv = (k & 2) ? 1 : -1;
    const glm::vec<3, T> direction = major * T(resolution) + s_axis * T(2 * ci - resolution + du) + t_axis * T(2 * cj - resolution + dv);
    const glm::ivec3 texel = cube_texel_of(direction, resolution);
    sum += fetch(texel.x, texel.y, texel.z).w;
  }
  return sum * T(0.25);
}

enum class gather_form_factor { polygon = 0, point = 1 };  ///< GLSL: VPLKIT_FORM_FACTOR 0 / 1

/// Irradiance at (x, n) from the M x M distance cube map around o. See the top comment.
template <gather_form_factor Kind, typename T, typename Fetch>
glm::vec<3, T> final_gather_irradiance(const glm::vec<3, T>& x, const glm::vec<3, T>& n, const glm::vec<3, T>& o, int resolution,
                                       Fetch&& fetch) {
  glm::vec<3, T> irradiance(0);
  for (int face = 0; face < 6; ++face) {
    for (int j = 0; j < resolution; ++j) {
      for (int i = 0; i < resolution; ++i) {
        const glm::vec<4, T> texel = fetch(face, i, j);
        glm::vec<3, T> corner[4];
        for (int k = 0; k < 4; ++k) {
          const int ci = i + ((k == 1 || k == 2) ? 1 : 0), cj = j + (k >= 2 ? 1 : 0);
          corner[k] = o + glm::normalize(cube_corner_direction<T>(face, ci, cj, resolution)) *
                              cube_corner_distance<T>(face, ci, cj, resolution, fetch);
        }
        const glm::vec<3, T> radiance(texel);
        if constexpr (Kind == gather_form_factor::polygon) {
          irradiance += radiance * (T(3.14159265358979323846) * polygon_form_factor(x, n, corner[0], corner[1], corner[2], corner[3]));
        } else {
          const glm::vec<3, T> y = o + glm::normalize(cube_texel_direction<T>(face, i, j, resolution)) * texel.w;
          const glm::vec<3, T> diagonals = glm::cross(corner[2] - corner[0], corner[3] - corner[1]);
          const T twice_area = glm::length(diagonals);
          if (!(twice_area > T(0))) continue;
          glm::vec<3, T> normal = diagonals / twice_area;
          if (glm::dot(normal, o - y) < T(0)) normal = -normal;  // the surface faces the reference point
          irradiance += radiance * (T(3.14159265358979323846) * point_form_factor(x, n, y, normal) * (T(0.5) * twice_area));
        }
      }
    }
  }
  return irradiance;
}

}  // namespace vplkit
