// Visibility beyond one RSM: a conservative voxel occupancy grid of the scene, marched from the
// receiver to each RSM sample with a 3D DDA (Amanatides and Woo 1987). One RSM cannot tell a solid
// wall from a thin screen (docs/rsm-study.md, "Any frame"): the sun-lit ground outside a closed
// room leaks through its walls under every micro-linear-buffer variant. A grid of the scene's own
// triangles knows the wall is there.
//
// The grid (built on the CPU, voxel_grid_add_triangle): cubic cells over the scene's bounds, one
// cell of margin on every side; a cell is occupied when a triangle overlaps it, by the exact
// separating-axis test of Akenine-Moller (2001) on the cell grown by a ten-thousandth of its side
// so that rounding cannot drop a triangle that touches it. So a zero-thickness quad occupies every
// cell it passes through and is an occluder, and every segment that crosses a triangle visits a
// cell holding the crossing point: a sample behind a closed wall is never visible. Its resolution
// follows the scene's size (voxel_grid_settings::resolution cells along the longest side), bounded
// by voxel_grid_settings::max_megabytes (64 MiB by default: the cells grow until the packed grid,
// half a byte per cell, fits; the build adds two lines of cells) and by 2048 texels per side of the
// packed texture (GLSL ES 3.00's least GL_MAX_TEXTURE_SIZE).
//
// The distance per cell (voxel_grid_build_distances, after the triangles): the Chebyshev distance
// in cells to the nearest occupied cell, capped at 15 (voxel_distance_cap); 0 is an occupied cell,
// so the one field is both the occupancy and the distance. Built by a separable 3-pass transform
// (along x, then y, then z), linear in the cells (at most 2 x 15 reads per cell per pass), with
// one line of scratch. Until it runs (and again after a later triangle) every free cell holds 1:
// the march is then the cell-by-cell DDA, never wrong, only slower.
//
// Packing (the CPU grid holds the GPU texture's words): one RGBA32UI texel holds 32 cells along z,
// a nibble each, z = 8 c + k in component c, bits 4k to 4k + 3; the texel of cell (x, y, z) is
// (x, y + (z / 32) * cells.y), so the texture is cells.x wide and cells.y * ceil(cells.z / 32)
// high: 16 bytes per 32 cells, half a byte per cell. GL 3.3 and ES 3.0 read it with texelFetch
// on a usampler2D.
//
// The march (voxel_march_cells): from the receiver x moved start_offset cell sides along its
// normal to the sample x_p moved end_offset cell sides along its normal, every cell the segment
// passes through is judged (6-connected); one occupied cell hides the sample. A point farther
// than sqrt(3) cell sides from a plane lies in a cell the plane cannot touch, so with offsets of
// 2 (the defaults; sqrt(3) plus the growth and a margin) neither the receiver's nor the sample's
// own (locally flat) surface occludes them. Larger offsets step over walls thinner than the
// offset near the receiver; smaller ones darken every receiver by its own surface.
// In a free cell of distance r no occupied cell lies within r - 1 cells, so the march jumps to
// where the segment leaves that (2r - 1)-cell cube and goes on from the cell the cell-by-cell
// march would be in there: one loop, the cell-by-cell step being the jump of r = 1. The answers
// are the cell-by-cell march's exactly (tests/kernels/test_voxel_visibility.cpp).
// A coarse level (one bit per 4 x 4 x 4 cells, stepped brick by brick through empty space) cut
// the fetches per march by a quarter on beyond.txt but made llvmpipe's frame slower: its SIMD
// lanes run every branch of the loop's body, so each step cost both levels' work
// (docs/rsm-study.md, "Beyond one RSM": "Where the time goes").
//
// In the gather (voxel_rsm_visibility, the Visibility of gather_rsm_with): the receiver, the pixel
// lights and the coverage's coarse lights are in the light's eye space; one affine matrix
// (voxel_cells_from) takes them to the grid's cells, so a sample costs two point transforms. A
// sample the receiver's or its own tangent plane faces away from lights nothing (Eq. 3.2's
// positive parts) and is not marched. A coarse light (rsm_coverage.hpp) is marched like a pixel
// light from its mean position along its mean normal, normalised (voxel_coarse_light_visible): the
// coverage's receivers, off the map or behind the light, shone through walls without it.
//
// GLSL twin: shaders/lib/voxel_visibility.glsl.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include <vplkit/rsm_gather.hpp>
#include <vplkit/settings.hpp>
#include <vplkit/transform.hpp>

namespace vplkit {

/// Largest voxel_grid_settings::resolution. The packed texture's 2048 texels per side hold about
/// 250 cells along every axis of a cube (258 x 9 rows of 32 cells exceeds them); flatter scenes
/// get more along their long sides. Beyond what fits, the cells grow (make_voxel_grid_shape).
inline constexpr int voxel_grid_max_resolution = 512;
/// The packed texture's largest side (GLSL ES 3.00's least GL_MAX_TEXTURE_SIZE).
inline constexpr int voxel_grid_max_texture_side = 2048;
/// Cells per packed texel (RGBA32UI: 4 x 32 bits along z, a nibble per cell).
inline constexpr int voxel_cells_per_texel = 32;
/// The largest distance a cell holds (a nibble): the march jumps at most 15 cells at a time.
inline constexpr int voxel_distance_cap = 15;

/// How the grid is built (CPU only).
template <typename T>
struct voxel_grid_settings {
  int resolution = 128;       ///< cells along the scene's longest side
  T max_megabytes = T(64);    ///< bound on the packed grid (MiB)
};

template <typename T>
struct settings_description<voxel_grid_settings<T>> {
  using S = voxel_grid_settings<T>;
  static constexpr const char* name = "voxel_grid_settings";
  static constexpr bool glsl_twin = false;  // the build runs on the CPU; the shader reads voxel_grid_shape
  static constexpr auto fields() {
    return std::make_tuple(schema::field(&S::resolution, "resolution", schema::closed_range(1, voxel_grid_max_resolution), "cells",
                                 "voxel grid cells along the scene's longest side (fewer when the memory bound needs it)"),
                           schema::field(&S::max_megabytes, "max_megabytes", schema::closed_range(0.001, 1024), "MiB",
                                 "memory bound of the voxel grid: its cells grow until the packed grid fits"));
  }
  static setting_problem rules(const S& settings) { return schema::no_rules(settings); }
};

/// The march's offsets. GLSL twin: struct voxel_march_settings.
template <typename T>
struct voxel_march_settings {
  T start_offset = T(2);  ///< cell sides along the receiver's normal
  T end_offset = T(2);    ///< cell sides along the sample's normal
};

template <typename T>
struct settings_description<voxel_march_settings<T>> {
  using S = voxel_march_settings<T>;
  static constexpr const char* name = "voxel_march_settings";
  static constexpr bool glsl_twin = true;
  static constexpr auto fields() {
    return std::make_tuple(schema::field(&S::start_offset, "start_offset", schema::closed_range(0, 16), "cells",
                                 "the voxel march starts this far along the receiver's normal (> 1.74: its own surface does not occlude it)"),
                           schema::field(&S::end_offset, "end_offset", schema::closed_range(0, 16), "cells",
                                 "the voxel march ends this far along the sample's normal (> 1.74: its own surface does not occlude it)"));
  }
  static setting_problem rules(const S& settings) { return schema::no_rules(settings); }
};

/// Where the grid lies: cells of side cell_size from origin (world space). GLSL twin: struct
/// voxel_grid_shape.
template <typename T>
struct voxel_grid_shape {
  glm::vec<3, T> origin{T(0)};
  T cell_size = T(1);
  glm::ivec3 cells{1};
};

template <typename T>
struct settings_description<voxel_grid_shape<T>> {
  using S = voxel_grid_shape<T>;
  static constexpr const char* name = "voxel_grid_shape";
  static constexpr bool glsl_twin = true;
  static constexpr auto fields() {
    return std::make_tuple(schema::field(&S::origin, "origin", schema::any_finite(), "scene units", "the voxel grid's lowest corner"),
                           schema::field(&S::cell_size, "cell_size", schema::above(0.0), "scene units", "side of one voxel"),
                           schema::field(&S::cells, "cells", schema::closed_range(1, voxel_grid_max_texture_side), "", "voxels per axis"));
  }
  static setting_problem rules(const S& settings) { return schema::no_rules(settings); }
};

/// The packed texture's size in texels for `cells`.
inline glm::ivec2 voxel_texture_size(glm::ivec3 cells) {
  return glm::ivec2(cells.x, cells.y * ((cells.z + voxel_cells_per_texel - 1) / voxel_cells_per_texel));
}

/// The packed texel holding cell `cell`. GLSL twin: voxel_texel.
inline glm::ivec2 voxel_texel(glm::ivec3 cell, glm::ivec3 cells) { return glm::ivec2(cell.x, cell.y + (cell.z >> 5) * cells.y); }

/// Cell z's distance in its packed texel (0: occupied). GLSL twin: voxel_distance.
inline int voxel_distance(const glm::uvec4& texel, int z) { return static_cast<int>((texel[(z >> 3) & 3] >> static_cast<unsigned>((z & 7) * 4)) & 15u); }

/// A packed word with every nonzero distance set to 1 (the cell-by-cell march's grid).
inline std::uint32_t voxel_unit_distances(std::uint32_t word) { return (word | (word >> 1) | (word >> 2) | (word >> 3)) & 0x11111111u; }

/// The packed grid's size in bytes.
inline std::size_t voxel_grid_bytes(glm::ivec3 cells) {
  const glm::ivec2 size = voxel_texture_size(cells);
  return static_cast<std::size_t>(size.x) * static_cast<std::size_t>(size.y) * sizeof(glm::uvec4);
}

/// The shape for a scene whose triangles lie in [low, high]: resolution cells along the longest
/// side plus one of margin on every side, the cells grown by 1 % steps until the packed grid fits
/// max_megabytes and 2048 texels per side. A flat or empty extent gets one cell's thickness.
template <typename T>
voxel_grid_shape<T> make_voxel_grid_shape(const glm::vec<3, T>& low, const glm::vec<3, T>& high, const voxel_grid_settings<T>& settings) {
  const glm::vec<3, T> extent = glm::max(high - low, glm::vec<3, T>(T(0)));
  const T longest = glm::max(extent.x, glm::max(extent.y, extent.z));
  const int resolution = glm::clamp(settings.resolution, 1, voxel_grid_max_resolution);
  T cell = longest > T(0) ? longest / T(resolution) : T(1);
  const double bound = static_cast<double>(settings.max_megabytes) * 1024.0 * 1024.0;
  voxel_grid_shape<T> shape;
  for (;;) {
    // +2: the margin, so that a surface on the bounds lies inside and the offsets' points beside it.
    shape.cells = glm::ivec3(glm::ceil(extent / cell)) + 2;
    shape.cells = glm::max(shape.cells, glm::ivec3(3));
    const glm::ivec2 texture = voxel_texture_size(shape.cells);
    const bool fits = static_cast<double>(voxel_grid_bytes(shape.cells)) <= bound && texture.x <= voxel_grid_max_texture_side &&
                      texture.y <= voxel_grid_max_texture_side;
    if (fits || (shape.cells.x <= 3 && shape.cells.y <= 3 && shape.cells.z <= 3)) break;
    cell *= T(1.01);
  }
  shape.cell_size = cell;
  // Centred: the margin is at least one cell on every side.
  shape.origin = (low + high) * T(0.5) - glm::vec<3, T>(shape.cells) * (cell * T(0.5));
  return shape;
}

/// Whether the triangle (a, b, c) overlaps the axis-aligned box centre +- half: the separating
/// axis test of Akenine-Moller ("Fast 3D triangle-box overlap testing", 2001): the box's three
/// axes, the triangle's normal and the nine cross products of the box's axes with its edges.
/// Exact up to rounding; degenerate triangles (segments, points) are tested as what they are.
template <typename T>
bool triangle_box_overlap(const glm::vec<3, T>& centre, const glm::vec<3, T>& half, const glm::vec<3, T>& a, const glm::vec<3, T>& b,
                          const glm::vec<3, T>& c) {
  const glm::vec<3, T> v[3] = {a - centre, b - centre, c - centre};
  const glm::vec<3, T> edges[3] = {v[1] - v[0], v[2] - v[1], v[0] - v[2]};
  const auto separated = [&](const glm::vec<3, T>& axis) {
    const T p0 = glm::dot(v[0], axis), p1 = glm::dot(v[1], axis), p2 = glm::dot(v[2], axis);
    const T r = half.x * std::abs(axis.x) + half.y * std::abs(axis.y) + half.z * std::abs(axis.z);
    return glm::min(p0, glm::min(p1, p2)) > r || glm::max(p0, glm::max(p1, p2)) < -r;
  };
  for (int i = 0; i < 3; ++i) {
    glm::vec<3, T> axis(T(0));
    axis[i] = T(1);
    if (separated(axis)) return false;
    for (const glm::vec<3, T>& edge : edges)
      if (separated(glm::cross(axis, edge))) return false;
  }
  return !separated(glm::cross(edges[0], edges[1]));
}

/// The CPU grid: its shape and the packed texture's texels (row by row, voxel_texture_size), a
/// distance per cell (0: occupied).
struct voxel_grid {
  voxel_grid_shape<float> shape;
  std::vector<glm::uvec4> texels;
  std::size_t occupied_cells = 0;
  bool distances_built = false;  ///< the distances are the transform's (else every free cell holds 1)

  std::size_t index(glm::ivec3 cell) const {
    const glm::ivec2 t = voxel_texel(cell, shape.cells);
    return static_cast<std::size_t>(t.y) * static_cast<std::size_t>(shape.cells.x) + static_cast<std::size_t>(t.x);
  }
  int distance(glm::ivec3 cell) const { return voxel_distance(texels[index(cell)], cell.z); }
  bool occupied(glm::ivec3 cell) const { return distance(cell) == 0; }
  void set_distance(glm::ivec3 cell, int value) {
    std::uint32_t& word = texels[index(cell)][(cell.z >> 3) & 3];
    const unsigned shift = static_cast<unsigned>((cell.z & 7) * 4);
    word = (word & ~(15u << shift)) | (static_cast<std::uint32_t>(value) << shift);
  }
  void mark(glm::ivec3 cell) {
    // A new occupied cell makes its neighbours' distances too large: back to the unit distances,
    // always conservative, until the transform runs again.
    if (distances_built) {
      for (glm::uvec4& texel : texels)
        for (int c = 0; c < 4; ++c) texel[c] = voxel_unit_distances(texel[c]);
      distances_built = false;
    }
    occupied_cells += occupied(cell) ? 0u : 1u;
    set_distance(cell, 0);
  }
  std::size_t bytes() const { return texels.size() * sizeof(glm::uvec4); }
};

/// An empty grid of `shape` (every cell free, distance 1).
inline voxel_grid make_voxel_grid(const voxel_grid_shape<float>& shape) {
  voxel_grid grid;
  grid.shape = shape;
  const glm::ivec2 size = voxel_texture_size(shape.cells);
  grid.texels.assign(static_cast<std::size_t>(size.x) * static_cast<std::size_t>(size.y), glm::uvec4(0x11111111u));
  return grid;
}

/// One pass of the distance transform along `axis`, in place, line by line: a cell's new value is
/// min over the line's cells c' of max(|c - c'|, value(c')), capped at voxel_distance_cap (cells
/// beyond the grid are free). The first pass reads the occupancy (0 or not), so its values are the
/// distances along the axis; the next two make them the Chebyshev distances in the plane, then in
/// the grid (L-infinity is separable this way: the nearest cell within r on every axis).
inline void voxel_distance_pass(voxel_grid& grid, int axis) {
  const glm::ivec3 cells = grid.shape.cells;
  const int length = cells[axis], u = (axis + 1) % 3, v = (axis + 2) % 3;
  std::vector<int> line(static_cast<std::size_t>(length)), out(static_cast<std::size_t>(length));
  for (int b = 0; b < cells[v]; ++b)
    for (int a = 0; a < cells[u]; ++a) {
      glm::ivec3 cell(0);
      cell[u] = a;
      cell[v] = b;
      for (int i = 0; i < length; ++i) {
        cell[axis] = i;
        const int value = grid.distance(cell);
        line[static_cast<std::size_t>(i)] = axis == 0 ? (value == 0 ? 0 : voxel_distance_cap) : value;
      }
      for (int i = 0; i < length; ++i) {
        // max(|delta|, value) >= |delta|: no cell farther than the best so far can improve on it.
        int best = line[static_cast<std::size_t>(i)];
        for (int delta = 1; delta < best; ++delta) {
          if (i - delta >= 0) best = std::min(best, std::max(delta, line[static_cast<std::size_t>(i - delta)]));
          if (i + delta < length) best = std::min(best, std::max(delta, line[static_cast<std::size_t>(i + delta)]));
        }
        out[static_cast<std::size_t>(i)] = best;
      }
      for (int i = 0; i < length; ++i) {
        cell[axis] = i;
        grid.set_distance(cell, out[static_cast<std::size_t>(i)]);
      }
    }
}

/// Each cell's Chebyshev distance in cells to the nearest occupied cell, capped at
/// voxel_distance_cap: the separable transform's three passes, after the last triangle.
inline void voxel_grid_build_distances(voxel_grid& grid) {
  for (int axis = 0; axis < 3; ++axis) voxel_distance_pass(grid, axis);
  grid.distances_built = true;
}

/// Marks every cell the triangle overlaps (the test in double; each cell grown by 1e-4 of its side).
/// Non-finite corners are skipped: they bound no cell.
inline void voxel_grid_add_triangle(voxel_grid& grid, const glm::vec3& a, const glm::vec3& b, const glm::vec3& c) {
  const glm::dvec3 o(grid.shape.origin);
  const double h = grid.shape.cell_size;
  const glm::dvec3 p[3] = {(glm::dvec3(a) - o) / h, (glm::dvec3(b) - o) / h, (glm::dvec3(c) - o) / h};  // in cells
  for (const glm::dvec3& corner : p)
    if (!std::isfinite(corner.x) || !std::isfinite(corner.y) || !std::isfinite(corner.z)) return;
  constexpr double grow = 1e-4;
  const glm::dvec3 low = glm::min(p[0], glm::min(p[1], p[2])) - grow, high = glm::max(p[0], glm::max(p[1], p[2])) + grow;
  const glm::ivec3 last = grid.shape.cells - 1;
  const glm::ivec3 first_cell = glm::clamp(glm::ivec3(glm::floor(low)), glm::ivec3(0), last);
  const glm::ivec3 last_cell = glm::clamp(glm::ivec3(glm::floor(high)), glm::ivec3(0), last);
  if (high.x < 0.0 || high.y < 0.0 || high.z < 0.0 || low.x > last.x + 1.0 || low.y > last.y + 1.0 || low.z > last.z + 1.0) return;
  const glm::dvec3 half(0.5 + grow);
  for (int z = first_cell.z; z <= last_cell.z; ++z)
    for (int y = first_cell.y; y <= last_cell.y; ++y)
      for (int x = first_cell.x; x <= last_cell.x; ++x)
        if (triangle_box_overlap(glm::dvec3(x, y, z) + 0.5, half, p[0], p[1], p[2])) grid.mark(glm::ivec3(x, y, z));
}

/// Whether nothing occupied lies on the segment from `u0` to `u1`, both in the grid's cells (cell
/// (i, j, k) spans [i, i + 1) x [j, j + 1) x [k, k + 1)): a 3D DDA over every cell the segment
/// passes through, clipped to the grid (outside it is empty). 1 visible, 0 hidden.
/// `fetch(glm::ivec2 texel) -> glm::uvec4` reads the packed grid. GLSL twin: voxel_march_cells.
/// The cell-by-cell march is the merge of the three axes' boundary crossings, each at
/// t = (boundary - u0) / d computed afresh (no running sums), in order of t, ties to the lower
/// axis. In a free cell of distance r the cube of cells within r - 1 holds nothing: the march
/// takes the first of the cube's three faces ahead that the segment crosses, and there moves
/// the cell r cells on that axis and, on the others, across every boundary the merge crosses
/// first (those before t, or at t on a lower axis): the cell the cell-by-cell march reaches
/// there, having judged only free cells of the cube on the way. floor(u0 + d t) finds that count
/// up to a rounding, which one comparison each way with the boundaries' own t settles. With r = 1
/// the jump is one DDA step. The steps are written in the order the twin computes them, without a
/// division by a zero direction (infinite steps are a large number instead).
template <typename T, typename Fetch>
T voxel_march_cells(Fetch&& fetch, glm::ivec3 cells, const glm::vec<3, T>& u0, const glm::vec<3, T>& u1) {
  const glm::vec<3, T> d = u1 - u0;  // cells per unit of t, t in [0, 1]
  const glm::vec<3, T> size(cells);
  constexpr T far = T(1e30);
  // Clip t to the grid's box (slabs).
  T t_enter = T(0), t_exit = T(1);
  glm::vec<3, T> inverse_d(far);
  for (int i = 0; i < 3; ++i) {
    if (std::abs(d[i]) > T(1e-12)) {
      inverse_d[i] = T(1) / d[i];
      const T ta = (T(0) - u0[i]) * inverse_d[i], tb = (size[i] - u0[i]) * inverse_d[i];
      t_enter = glm::max(t_enter, glm::min(ta, tb));
      t_exit = glm::min(t_exit, glm::max(ta, tb));
    } else if (u0[i] < T(0) || u0[i] > size[i]) {
      return T(1);  // parallel to this slab and outside it
    }
  }
  if (t_enter > t_exit) return T(1);
  glm::ivec3 cell = glm::clamp(glm::ivec3(glm::floor(u0 + d * t_enter)), glm::ivec3(0), cells - 1);
  glm::ivec3 step(0), ahead(0);  // ahead: 1 where a cell's boundary ahead is its upper one
  for (int i = 0; i < 3; ++i) {
    if (std::abs(d[i]) > T(1e-12)) {
      step[i] = d[i] > T(0) ? 1 : -1;
      ahead[i] = d[i] > T(0) ? 1 : 0;
    }
  }
  const int steps = cells.x + cells.y + cells.z;
  for (int n = 0; n <= steps; ++n) {
    const int r = voxel_distance(fetch(voxel_texel(cell, cells)), cell.z);
    if (r == 0) return T(0);
    // The free cube's faces ahead, and when the segment crosses each.
    const glm::ivec3 face = cell + step * (r - 1) + ahead;
    glm::vec<3, T> t_face(far);
    for (int i = 0; i < 3; ++i)
      if (step[i] != 0) t_face[i] = (T(face[i]) - u0[i]) * inverse_d[i];
    // The face crossed first; ties to the lower axis.
    int axis = 0;
    if (t_face.y < t_face[axis]) axis = 1;
    if (t_face.z < t_face[axis]) axis = 2;
    const T t = t_face[axis];
    if (t > t_exit) break;
    glm::ivec3 moved(0);
    for (int i = 0; i < 3; ++i) {
      if (step[i] == 0) continue;
      if (i == axis) {
        moved[i] = r;
        continue;
      }
      // Boundaries crossed on this axis before the face: at most r - 1 (its own face comes later).
      const T p = u0[i] + d[i] * t;
      int k = glm::clamp(step[i] * (static_cast<int>(std::floor(p)) - cell[i]), 0, r - 1);
      const int next = cell[i] + step[i] * k + ahead[i];
      const T t_next = (T(next) - u0[i]) * inverse_d[i];
      const T t_last = (T(next - step[i]) - u0[i]) * inverse_d[i];
      if (k < r - 1 && (t_next < t || (t_next == t && i < axis))) k += 1;
      else if (k > 0 && !(t_last < t || (t_last == t && i < axis))) k -= 1;
      moved[i] = k;
    }
    cell += step * moved;
    if (glm::any(glm::lessThan(cell, glm::ivec3(0))) || glm::any(glm::greaterThanEqual(cell, cells))) break;
  }
  return T(1);
}

/// The affine map from a space (e.g. the light's eye space) to the grid's cells, given the map
/// from that space to the world (rigid or the identity): p -> (to_world p - origin) / cell_size.
/// The gather's single matrix. GLSL: gather.frag's uniform voxel_from_light.
template <typename T>
glm::mat<4, 4, T> voxel_cells_from(const voxel_grid_shape<T>& shape, const glm::mat<4, 4, T>& to_world) {
  glm::mat<4, 4, T> to_cells(T(1) / shape.cell_size);
  to_cells[3] = glm::vec<4, T>(-shape.origin / shape.cell_size, T(1));
  return to_cells * to_world;
}

/// voxel_march_cells between two world points.
template <typename T, typename Fetch>
T voxel_segment_visible(Fetch&& fetch, const voxel_grid_shape<T>& shape, const glm::vec<3, T>& from, const glm::vec<3, T>& to) {
  const T inverse_cell = T(1) / shape.cell_size;
  return voxel_march_cells(fetch, shape.cells, (from - shape.origin) * inverse_cell, (to - shape.origin) * inverse_cell);
}

/// The visibility of a pixel light (position x_p, unit normal n_p) from a receiver (x, n), all in
/// a space that `to_cells` (voxel_cells_from) takes to the grid's cells: the segment between the
/// points moved along their normals by the settings' offsets (cell sides). 1 (no claim) when
/// either tangent plane faces away: such a light lights nothing. GLSL twin: voxel_light_visible.
template <typename T, typename Fetch>
T voxel_light_visible(Fetch&& fetch, const voxel_grid_shape<T>& shape, const voxel_march_settings<T>& settings, const glm::mat<4, 4, T>& to_cells,
                      const glm::vec<3, T>& x, const glm::vec<3, T>& n, const glm::vec<3, T>& xp, const glm::vec<3, T>& np) {
  const glm::vec<3, T> to_light = xp - x;
  if (!(glm::dot(n, to_light) > T(0)) || !(glm::dot(np, to_light) < T(0))) return T(1);
  return voxel_march_cells(fetch, shape.cells, transform_point(to_cells, x + n * (settings.start_offset * shape.cell_size)),
                           transform_point(to_cells, xp + np * (settings.end_offset * shape.cell_size)));
}

/// The same with every point in the world.
template <typename T, typename Fetch>
T voxel_light_visible(Fetch&& fetch, const voxel_grid_shape<T>& shape, const voxel_march_settings<T>& settings, const glm::vec<3, T>& x,
                      const glm::vec<3, T>& n, const glm::vec<3, T>& xp, const glm::vec<3, T>& np) {
  return voxel_light_visible(fetch, shape, settings, voxel_cells_from(shape, glm::mat<4, 4, T>(T(1))), x, n, xp, np);
}

/// The visibility of a coverage's coarse light (mean position x_c, mean normal n_c of length <= 1)
/// from a receiver: voxel_light_visible with the normal made unit, so that the end offset is the
/// settings' in any block; 1 where the normal is 0 (such a light emits nothing). GLSL twin:
/// voxel_coarse_light_visible.
template <typename T, typename Fetch>
T voxel_coarse_light_visible(Fetch&& fetch, const voxel_grid_shape<T>& shape, const voxel_march_settings<T>& settings, const glm::mat<4, 4, T>& to_cells,
                             const glm::vec<3, T>& x, const glm::vec<3, T>& n, const glm::vec<3, T>& xc, const glm::vec<3, T>& nc) {
  const T length = std::sqrt(glm::dot(nc, nc));
  if (!(length > T(0))) return T(1);
  return voxel_light_visible(fetch, shape, settings, to_cells, x, n, xc, nc / length);
}

/// The packed grid's fetch for the C++ gather.
struct voxel_grid_fetch {
  const voxel_grid* grid;
  glm::uvec4 operator()(glm::ivec2 texel) const {
    return grid->texels[static_cast<std::size_t>(texel.y) * static_cast<std::size_t>(grid->shape.cells.x) + static_cast<std::size_t>(texel.x)];
  }
};

/// The Visibility of gather_rsm_with (rsm_gather.hpp) by the grid: the receiver, the pixel lights
/// and the coarse lights moved from the light's eye space to the grid's cells by `light_to_cells`
/// (voxel_cells_from(shape, inverse light view)). GLSL: VPLKIT_VISIBILITY 8 in lib/rsm_gather.glsl,
/// which calls the including shader's rsm_voxel_visibility and rsm_voxel_coarse_visibility.
template <typename T, typename Fetch>
struct voxel_rsm_visibility {
  Fetch fetch;
  voxel_grid_shape<T> shape;
  voxel_march_settings<T> settings;
  glm::mat<4, 4, T> light_to_cells;
  void begin_path() {}
  T operator()(const gather_receiver<T>& receiver, const rsm_texel<T>& light) {
    return voxel_light_visible(fetch, shape, settings, light_to_cells, receiver.position, receiver.normal, light.position, light.normal);
  }
  T coarse(const gather_receiver<T>& receiver, const coarse_light<T>& light) {
    return voxel_coarse_light_visible(fetch, shape, settings, light_to_cells, receiver.position, receiver.normal, light.position, light.normal);
  }
};

}  // namespace vplkit
