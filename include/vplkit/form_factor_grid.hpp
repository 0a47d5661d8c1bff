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
// is clipped by polygon_form_factor itself, the one clipping code. Edge terms are computed only
// within each row's span of corners above the plane (about half of a grid lies below a receiver's
// horizon), and the body is compiled for x86-64-v2 and for AVX2, chosen at run time
// (batch_isa.hpp; the same bits, test_form_factor_grid.cpp).
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

#include <vplkit/batch_isa.hpp>
#include <vplkit/form_factor.hpp>

namespace vplkit {

/// Scratch space of polygon_form_factor_grid, kept by a caller that calls it many times so that
/// it allocates once.
template <typename T>
struct form_factor_grid_scratch {
  std::vector<T> rx, ry, rz, height, inverse_length;  ///< per corner, (cells_u + 1) x (cells_v + 1)
  std::vector<T> along_u, along_v;                   ///< edge terms: corner (i, j) to (i + 1, j), and to (i, j + 1)
  std::vector<int> span_first, span_last;            ///< per row of corners, the first and last above the plane
  std::vector<int> cut;                              ///< a row's cells the plane cuts
};

namespace detail {

/// polygon_form_factor_grid's work, inlined into one function per instruction set (batch_isa.hpp):
/// the same source, so the same operations on every path.
template <typename T>
VPLKIT_BATCH_ALWAYS_INLINE inline void polygon_form_factor_grid_body(const glm::vec<3, T>& x, const glm::vec<3, T>& n, const glm::vec<3, T>& origin,
                                                                    const glm::vec<3, T>& du, const glm::vec<3, T>& dv, int cells_u, int cells_v, T* out,
                                                                    form_factor_grid_scratch<T>& scratch) {
  if (cells_u <= 0 || cells_v <= 0) return;
  const std::size_t row = static_cast<std::size_t>(cells_u) + 1u, rows = static_cast<std::size_t>(cells_v) + 1u;
  const std::size_t corners = row * rows;
  scratch.rx.resize(corners), scratch.ry.resize(corners), scratch.rz.resize(corners);
  scratch.height.resize(corners), scratch.inverse_length.resize(corners);
  scratch.along_u.resize(corners), scratch.along_v.resize(corners);
  scratch.span_first.resize(rows), scratch.span_last.resize(rows), scratch.cut.resize(row);
  T* const rx = scratch.rx.data();
  T* const ry = scratch.ry.data();
  T* const rz = scratch.rz.data();
  T* const height = scratch.height.data();
  T* const inverse_length = scratch.inverse_length.data();
  // Corners: the offset from x as polygon_form_factor forms it (corner - x, the corner being
  // origin + i du + j dv) and its height above the tangent plane.
  for (int j = 0; j <= cells_v; ++j)
    for (int i = 0; i <= cells_u; ++i) {  // int indices: a size_t has no vector conversion to float
      const glm::vec<3, T> r = origin + du * T(i) + dv * T(j) - x;
      const std::size_t c = static_cast<std::size_t>(j) * row + static_cast<std::size_t>(i);
      rx[c] = r.x, ry[c] = r.y, rz[c] = r.z;
      height[c] = glm::dot(n, r);
    }
  // Only a cell wholly above the plane reads edge terms, and only edges between two corners
  // above it: per row, the span from the first to the last corner above (a cell's corners lie in
  // two rows' spans, whatever the rounding of the heights; the plane cuts a row once, so the
  // span holds few corners below, usually none). About half of a grid's cells lie below a
  // receiver's horizon; their edges cost nothing.
  int* const span_first = scratch.span_first.data();
  int* const span_last = scratch.span_last.data();
  for (std::size_t j = 0; j < rows; ++j) {
    // (A min and a max reduction over selects, which vectorise; the running form
    // `above && i < first ? i : first` did not, and cost more than the edge terms.)
    int first = cells_u + 1, last = -1;
    for (int i = 0; i <= cells_u; ++i) {
      const bool above = height[j * row + static_cast<std::size_t>(i)] >= T(0);
      const int as_first = above ? i : cells_u + 1, as_last = above ? i : -1;
      first = as_first < first ? as_first : first;
      last = as_last > last ? as_last : last;
    }
    span_first[j] = first, span_last[j] = last;
  }
  // 1 / |r| of the corners in the spans, then the edge terms: along u within a row's span, along
  // v within the overlap of two rows' spans (loops over a span without branches, which the
  // compiler vectorises; written out, not through a lambda capturing the arrays: GCC did not
  // vectorise that form).
  T* const along_u = scratch.along_u.data();
  T* const along_v = scratch.along_v.data();
  const glm::vec<3, T> normal = n;
  // (An empty span is first = cells_u + 1, last = -1: the loops below do not run.)
  for (std::size_t j = 0; j < rows; ++j) {
    const std::size_t base = j * row;
    for (int i = span_first[j]; i <= span_last[j]; ++i) {
      const std::size_t c = base + static_cast<std::size_t>(i);
      inverse_length[c] = detail::inverse_length(glm::vec<3, T>(rx[c], ry[c], rz[c]));
    }
  }
  for (std::size_t j = 0; j < rows; ++j) {
    const std::size_t base = j * row;
    for (int i = span_first[j]; i < span_last[j]; ++i) {
      const std::size_t c = base + static_cast<std::size_t>(i);
      along_u[c] = detail::lambert_edge(glm::vec<3, T>(rx[c], ry[c], rz[c]), inverse_length[c], glm::vec<3, T>(rx[c + 1], ry[c + 1], rz[c + 1]),
                                        inverse_length[c + 1], normal);
    }
  }
  for (std::size_t j = 0; j + 1 < rows; ++j) {
    const std::size_t base = j * row;
    const int first = glm::max(span_first[j], span_first[j + 1]), last = glm::min(span_last[j], span_last[j + 1]);
    for (int i = first; i <= last; ++i) {
      const std::size_t c = base + static_cast<std::size_t>(i);
      along_v[c] = detail::lambert_edge(glm::vec<3, T>(rx[c], ry[c], rz[c]), inverse_length[c], glm::vec<3, T>(rx[c + row], ry[c + row], rz[c + row]),
                                        inverse_length[c + row], normal);
    }
  }
  // Cells: the four edge terms around (i, j) -> (i + 1, j) -> (i + 1, j + 1) -> (i, j + 1), where
  // the cell is wholly above; 0 elsewhere for now (a select, and terms outside the spans are
  // never read where it is taken). Then the cells the tangent plane cuts, few (along one line of
  // the grid), by the scalar form.
  for (std::size_t j = 0; j + 1 < rows; ++j)
    for (std::size_t i = 0; i + 1 < row; ++i) {
      const std::size_t c00 = j * row + i, c10 = c00 + 1, c01 = c00 + row, c11 = c01 + 1;
      const bool above = (int(height[c00] >= T(0)) & int(height[c10] >= T(0)) & int(height[c11] >= T(0)) & int(height[c01] >= T(0))) != 0;
      const T sum = above ? along_u[c00] + along_v[c10] - along_u[c01] - along_v[c00] : T(0);
      const T f = glm::min(T(1), std::abs(sum) * T(0.159154943091895335769));  // 1 / (2 pi)
      out[j * static_cast<std::size_t>(cells_u) + i] = above ? f : T(0);
    }
  // A cut cell has a corner above, in its rows' spans, so it lies within [first - 1, last] of
  // them; there the cut cells are listed without a branch (a branch per cell, mispredicted at
  // the few cut ones, cost more than the edge terms) and then clipped.
  int* const cut = scratch.cut.data();
  for (std::size_t j = 0; j + 1 < rows; ++j) {
    const int first = glm::max(0, glm::min(span_first[j], span_first[j + 1]) - 1);
    const int last = glm::min(cells_u - 1, glm::max(span_last[j], span_last[j + 1]));
    int cut_count = 0;
    for (int i = first; i <= last; ++i) {
      const std::size_t c00 = j * row + static_cast<std::size_t>(i), c10 = c00 + 1, c01 = c00 + row, c11 = c01 + 1;
      const int above = int(height[c00] >= T(0)) + int(height[c10] >= T(0)) + int(height[c11] >= T(0)) + int(height[c01] >= T(0));
      cut[cut_count] = i;
      cut_count += int(above != 0) & int(above != 4);  // not wholly below (0) nor wholly above (done)
    }
    for (int k = 0; k < cut_count; ++k) {
      const std::size_t c00 = j * row + static_cast<std::size_t>(cut[k]), c10 = c00 + 1, c01 = c00 + row, c11 = c01 + 1;
      const auto corner = [&](std::size_t c) { return glm::vec<3, T>(rx[c], ry[c], rz[c]); };
      out[j * static_cast<std::size_t>(cells_u) + static_cast<std::size_t>(cut[k])] =
          polygon_form_factor(glm::vec<3, T>(T(0)), n, corner(c00), corner(c10), corner(c11), corner(c01));
    }
  }
}

template <typename T>
void polygon_form_factor_grid_portable(const glm::vec<3, T>& x, const glm::vec<3, T>& n, const glm::vec<3, T>& origin, const glm::vec<3, T>& du,
                                       const glm::vec<3, T>& dv, int cells_u, int cells_v, T* out, form_factor_grid_scratch<T>& scratch) {
  polygon_form_factor_grid_body(x, n, origin, du, dv, cells_u, cells_v, out, scratch);
}

#if VPLKIT_BATCH_HAS_AVX2
template <typename T>
VPLKIT_BATCH_TARGET_AVX2 void polygon_form_factor_grid_avx2(const glm::vec<3, T>& x, const glm::vec<3, T>& n, const glm::vec<3, T>& origin,
                                                            const glm::vec<3, T>& du, const glm::vec<3, T>& dv, int cells_u, int cells_v, T* out,
                                                            form_factor_grid_scratch<T>& scratch) {
  polygon_form_factor_grid_body(x, n, origin, du, dv, cells_u, cells_v, out, scratch);
}
#endif

}  // namespace detail

/// F from (x, n) to every cell of the grid; out[j * cells_u + i] is cell (i, j). See the top
/// comment. `isa` picks the instantiation (batch_isa.hpp); one the CPU does not run falls back to
/// the portable one.
template <typename T>
void polygon_form_factor_grid(const glm::vec<3, T>& x, const glm::vec<3, T>& n, const glm::vec<3, T>& origin, const glm::vec<3, T>& du,
                              const glm::vec<3, T>& dv, int cells_u, int cells_v, T* out, form_factor_grid_scratch<T>& scratch,
                              batch_isa isa = best_batch_isa()) {
#if VPLKIT_BATCH_HAS_AVX2
  if (isa == batch_isa::avx2 && batch_isa_supported(batch_isa::avx2)) {
    detail::polygon_form_factor_grid_avx2(x, n, origin, du, dv, cells_u, cells_v, out, scratch);
    return;
  }
#else
  (void)isa;
#endif
  detail::polygon_form_factor_grid_portable(x, n, origin, du, dv, cells_u, cells_v, out, scratch);
}

}  // namespace vplkit
