// The polygon form factor of vplkit/form_factor.hpp from one receiver to every texel of a planar
// grid of quads (a cube-map face of the final gather, a light panel cut into cells), for CPU
// embedding: polygon_form_factor_grid(x, n, origin, du, dv, cells_u, cells_v, out) writes, for
// cell (i, j), the form factor to the quad origin + (i, j) du/dv ... origin + (i + 1, j + 1) du/dv.
//
// Compile with -fno-math-errno and -fno-trapping-math (vplkit_bench does) for the loops to
// vectorise: with errno std::sqrt keeps a libm call on a branch, and with trapping math GCC does not
// if-convert lambert_edge's selects between computed values.
//
// Why it is cheaper than a polygon_form_factor per cell: neighbouring cells share corners and
// edges. Lambert's sum for a cell wholly above the receiver's tangent plane is the sum of its four
// edges' terms (detail::lambert_edge), and an edge shared by two cells enters them with opposite
// directions, whose terms are exact negatives (u . v and |u + v| are symmetric, u x v changes
// sign exactly). So each grid corner's offset and 1/|r| is computed once, each edge's term once
// (in loops over a row without branches, which the compiler vectorises), and a cell adds four
// numbers. A cell wholly below the plane is 0, as in polygon_form_factor; a cell the plane cuts
// is clipped by polygon_form_factor itself, the one clipping code.
//
// Accuracy: the same edge terms as polygon_form_factor, summed in another order: within
// 2.1e-8 + rounding of polygon_form_factor_exact, as polygon_form_factor is
// (test_form_factor_grid.cpp holds both the double and the float form to it, cell by cell).
//
// GLSL twin: none. A CPU-only batching of polygon_form_factor, whose per-edge arithmetic (and so
// shaders/lib/form_factor.glsl's) it reuses; parity of that arithmetic is proved on the scalar form.
#pragma once

#include <cstddef>
#include <vector>

#include <glm/glm.hpp>

#include <vplkit/form_factor.hpp>

namespace vplkit {

/// Scratch space of polygon_form_factor_grid, kept by a caller that calls it many times so that
/// it allocates once.
template <typename T>
struct form_factor_grid_scratch {
  std::vector<T> rx, ry, rz, height, inverse_length;  ///< per corner, (cells_u + 1) x (cells_v + 1)
  std::vector<T> along_u, along_v;                   ///< edge terms: corner (i, j) to (i + 1, j), and to (i, j + 1)
};

/// F from (x, n) to every cell of the grid; out[j * cells_u + i] is cell (i, j). See the top comment.
template <typename T>
void polygon_form_factor_grid(const glm::vec<3, T>& x, const glm::vec<3, T>& n, const glm::vec<3, T>& origin, const glm::vec<3, T>& du,
                              const glm::vec<3, T>& dv, int cells_u, int cells_v, T* out, form_factor_grid_scratch<T>& scratch) {
  if (cells_u <= 0 || cells_v <= 0) return;
  const std::size_t row = static_cast<std::size_t>(cells_u) + 1u, rows = static_cast<std::size_t>(cells_v) + 1u;
  const std::size_t corners = row * rows;
  scratch.rx.resize(corners), scratch.ry.resize(corners), scratch.rz.resize(corners);
  scratch.height.resize(corners), scratch.inverse_length.resize(corners);
  scratch.along_u.resize(corners), scratch.along_v.resize(corners);
  T* const rx = scratch.rx.data();
  T* const ry = scratch.ry.data();
  T* const rz = scratch.rz.data();
  T* const height = scratch.height.data();
  T* const inverse_length = scratch.inverse_length.data();
  // Corners: the offset from x as polygon_form_factor forms it (corner - x, the corner being
  // origin + i du + j dv), its height above the tangent plane and 1 / its length.
  for (int j = 0; j <= cells_v; ++j)
    for (int i = 0; i <= cells_u; ++i) {  // int indices: a size_t has no vector conversion to float
      const glm::vec<3, T> r = origin + du * T(i) + dv * T(j) - x;
      const std::size_t c = static_cast<std::size_t>(j) * row + static_cast<std::size_t>(i);
      rx[c] = r.x, ry[c] = r.y, rz[c] = r.z;
      height[c] = glm::dot(n, r);
      inverse_length[c] = detail::inverse_length(r);
    }
  // Edge terms, one loop per direction over all corners (the last column's or row's term is
  // computed from a wrapped neighbour and never read).
  // (Written out, not through a lambda capturing the arrays: GCC did not vectorise that form.)
  T* const along_u = scratch.along_u.data();
  T* const along_v = scratch.along_v.data();
  const glm::vec<3, T> normal = n;
  for (std::size_t c = 0; c + 1 < corners; ++c)
    along_u[c] = detail::lambert_edge(glm::vec<3, T>(rx[c], ry[c], rz[c]), inverse_length[c], glm::vec<3, T>(rx[c + 1], ry[c + 1], rz[c + 1]),
                                      inverse_length[c + 1], normal);
  for (std::size_t c = 0; c + row < corners; ++c)
    along_v[c] = detail::lambert_edge(glm::vec<3, T>(rx[c], ry[c], rz[c]), inverse_length[c], glm::vec<3, T>(rx[c + row], ry[c + row], rz[c + row]),
                                      inverse_length[c + row], normal);
  // Cells: the four edge terms around (i, j) -> (i + 1, j) -> (i + 1, j + 1) -> (i, j + 1), without
  // a branch (a select where the cell is not wholly above: 0); then the cells the tangent plane
  // cuts, few (along one line of the grid), by the scalar form.
  for (std::size_t j = 0; j + 1 < rows; ++j)
    for (std::size_t i = 0; i + 1 < row; ++i) {
      const std::size_t c00 = j * row + i, c10 = c00 + 1, c01 = c00 + row, c11 = c01 + 1;
      const bool above = (int(height[c00] >= T(0)) & int(height[c10] >= T(0)) & int(height[c11] >= T(0)) & int(height[c01] >= T(0))) != 0;
      const T sum = along_u[c00] + along_v[c10] - along_u[c01] - along_v[c00];
      const T f = glm::min(T(1), std::abs(sum) * T(0.159154943091895335769));  // 1 / (2 pi)
      out[j * static_cast<std::size_t>(cells_u) + i] = above ? f : T(0);
    }
  for (std::size_t j = 0; j + 1 < rows; ++j)
    for (std::size_t i = 0; i + 1 < row; ++i) {
      const std::size_t c00 = j * row + i, c10 = c00 + 1, c01 = c00 + row, c11 = c01 + 1;
      const int above = int(height[c00] >= T(0)) + int(height[c10] >= T(0)) + int(height[c11] >= T(0)) + int(height[c01] >= T(0));
      if (above == 0 || above == 4) continue;  // wholly below (0, as polygon_form_factor) or done above
      const auto corner = [&](std::size_t c) { return glm::vec<3, T>(rx[c], ry[c], rz[c]); };
      out[j * static_cast<std::size_t>(cells_u) + i] = polygon_form_factor(glm::vec<3, T>(T(0)), n, corner(c00), corner(c10), corner(c11), corner(c01));
    }
}

}  // namespace vplkit
