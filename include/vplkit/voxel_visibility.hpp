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
// by voxel_grid_settings::max_megabytes (64 MiB by default: the cells grow until the packed grid
// fits) and by 2048 texels per side of the packed texture (GLSL ES 3.00's least
// GL_MAX_TEXTURE_SIZE).
//
// Packing (the CPU grid holds the GPU texture's words): three copies of the grid, one per axis,
// side by side in one RGBA32UI texture (an atlas; one usampler2D, so that choosing a copy is an
// offset, not a divergent choice of sampler). In the copy along axis a, one texel holds 128
// consecutive cells along a, cell a = 32 c + b in component c, bit b; with (b, c) the next two
// axes in cyclic order (x: y, z; y: z, x; z: x, y), the texel of a cell is (offset_a + cell.b,
// cell.c + (cell.a / 128) * cells.c). The copies lie at x offsets 0 (along z, the single copy of
// earlier rounds), cells.x (along x) and cells.x + cells.y (along y), so the texture is
// cells.x + cells.y + cells.z wide and as high as the highest copy: 16 bytes per 128 cells per
// copy, and zero texels below the lower copies (on a flat scene the copies' heights differ: the
// study's sun frames, 130 x 15-34 x 130 cells, take 1.1-1.2 MiB where the copies themselves
// fill 61-138 KiB along z, as much along x and 264 KiB along y, whose 15-34 cells still take a
// whole 128-cell texel per column). max_megabytes and the 2048 texels per side bound the whole texture. GL 3.3
// and ES 3.0 read it with texelFetch on a usampler2D.
//
// The march (voxel_march_words): from the receiver x moved start_offset cell sides along its
// normal to the sample x_p moved end_offset cell sides along its normal, every cell the segment
// passes through (6-connected; voxel_march_cells, the cell-by-cell 3D DDA, is the definition)
// is tested; one occupied cell hides the sample. It marches the copy whose words lie along the
// segment's major axis, in words of 32 cells (a texel component): a 3D DDA over super-cells of
// 1 x 1 x 32 cells in that copy (the two minor axes step a cell, the major one a word), and at each
// step the run of cells the segment crosses in that column of the word, floor(a(t_start)) to
// floor(a(t_end)) clamped to the word (the major coordinate is monotonic along the segment),
// tested at once with a mask. The same cells as the cell-by-cell march (up to a tie where two
// axes' boundaries meet within a rounding), one fetch per step, and the two minor extents plus
// major / 32 steps instead of dx + dy + dz: about 2/3 of the cells on a diagonal, far fewer near
// an axis (the study's frames: 2.2-2.6x fewer fetches per march).
// A point farther than sqrt(3) cell sides from a plane lies in a cell the plane cannot touch, so
// with offsets of 2 (the defaults; sqrt(3) plus the growth and a margin) neither the receiver's
// nor the sample's own (locally flat) surface occludes them. Larger offsets step over walls
// thinner than the offset near the receiver; smaller ones darken every receiver by its own
// surface. Two earlier ways to shorten the march lost on llvmpipe, whose SIMD lanes run every
// branch of the loop's body and each loop as long as the group's longest: a coarse level (one bit
// per 4 x 4 x 4 cells) and a distance per cell both fetched fewer cells with a dearer step and
// made the frame slower; a word along z only (the single copy, words of 32 or 128 cells) saved
// only the z steps and measured no cheaper (docs/rsm-study.md, "Where the time goes").
//
// One march per group (voxel_march_settings::group): llvmpipe's frame pays for every march that any
// lane of a SIMD group runs, as long as the group's longest, not for the cells fetched. So the
// samples of a path share one march per run of `group` (rsm_sample_group in rsm_gather.hpp), to
// the run's member that lights the receiver most; a run all visible or all hidden gets the
// per-sample answer (docs/rsm-study.md, "Where the time goes": the frame against the run's length).
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

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include <vplkit/rsm_gather.hpp>
#include <vplkit/settings.hpp>
#include <vplkit/transform.hpp>

namespace vplkit {

/// Largest voxel_grid_settings::resolution; make_voxel_grid_shape grows the cells further where
/// the packed texture would exceed 2048 texels a side (a cube keeps at most 512 cells a side).
inline constexpr int voxel_grid_max_resolution = 512;
/// The most samples of a path that share one march (voxel_march_settings::group): a path holds at
/// most 256 (radial_pattern_settings::samples_per_path).
inline constexpr int voxel_max_group = 256;
/// The packed texture's largest side (GLSL ES 3.00's least GL_MAX_TEXTURE_SIZE).
inline constexpr int voxel_grid_max_texture_side = 2048;
/// Cells per packed texel (RGBA32UI: 4 x 32 bits along its copy's axis).
inline constexpr int voxel_cells_per_texel = 128;

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

/// The march's offsets, and how many consecutive samples of a path share one march. GLSL twin:
/// struct voxel_march_settings.
template <typename T>
struct voxel_march_settings {
  T start_offset = T(2);  ///< cell sides along the receiver's normal
  T end_offset = T(2);    ///< cell sides along the sample's normal
  int group = 2;          ///< samples of a path per march (rsm_sample_group; docs/rsm-study.md, "Where the time goes"); 1: every sample its own
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
                                 "the voxel march ends this far along the sample's normal (> 1.74: its own surface does not occlude it)"),
                           schema::field(&S::group, "group", schema::closed_range(1, voxel_max_group), "samples",
                                 "consecutive samples of a path that share one voxel march, to their largest member; 1: a march per sample"));
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

/// A vector with its axes in the order of the copy along `axis` (voxel_texel_along): the next two
/// axes in cyclic order, then `axis` (x: y, z, x; y: z, x, y; z: x, y, z). GLSL twin: voxel_axes_along.
template <typename V>
V voxel_axes_along(int axis, const V& v) {
  return axis == 0 ? V(v.y, v.z, v.x) : (axis == 1 ? V(v.z, v.x, v.y) : v);
}

/// The x offset of the copy along `axis` in the packed texture: z at 0, x at cells.x, y at
/// cells.x + cells.y. GLSL twin: voxel_copy_offset.
inline int voxel_copy_offset(int axis, glm::ivec3 cells) { return axis == 2 ? 0 : (axis == 0 ? cells.x : cells.x + cells.y); }

/// The packed texture's size in texels for `cells`: the three copies side by side, as high as the
/// highest.
inline glm::ivec2 voxel_texture_size(glm::ivec3 cells) {
  int height = 0;
  for (int axis = 0; axis < 3; ++axis) {
    const glm::ivec3 along = voxel_axes_along(axis, cells);
    height = glm::max(height, along.y * ((along.z + voxel_cells_per_texel - 1) / voxel_cells_per_texel));
  }
  return glm::ivec2(cells.x + cells.y + cells.z, height);
}

/// The texel holding cell `cell` of a copy at x offset `offset` (voxel_copy_offset), `cell` and
/// `cells` in that copy's order (voxel_axes_along): its bit is cell.z's (voxel_bit). GLSL twin:
/// voxel_texel_along.
inline glm::ivec2 voxel_texel_along(int offset, glm::ivec3 cell, glm::ivec3 cells) { return glm::ivec2(offset + cell.x, cell.y + (cell.z >> 7) * cells.y); }

/// The packed texel holding cell `cell` in the copy along z (the cell-by-cell march's and the
/// grid's `occupied`; C++ only: the GLSL march reads words, voxel_texel_along).
inline glm::ivec2 voxel_texel(glm::ivec3 cell, glm::ivec3 cells) { return voxel_texel_along(0, cell, cells); }

/// Whether cell z's bit is set in its packed texel (C++ only: the GLSL march tests a word's run
/// of bits with one mask).
inline bool voxel_bit(const glm::uvec4& texel, int z) { return ((texel[(z >> 5) & 3] >> static_cast<unsigned>(z & 31)) & 1u) != 0u; }

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

/// The CPU grid: its shape and the packed texture's texels (row by row, voxel_texture_size): every
/// cell's bit in each of the three copies.
struct voxel_grid {
  voxel_grid_shape<float> shape;
  std::vector<glm::uvec4> texels;
  int width = 0;  ///< the packed texture's width (voxel_texture_size)
  std::size_t occupied_cells = 0;

  const glm::uvec4& texel(glm::ivec2 t) const {
    return texels[static_cast<std::size_t>(t.y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(t.x)];
  }
  /// Read from the copy along z (mark keeps the three copies the same).
  bool occupied(glm::ivec3 cell) const { return voxel_bit(texel(voxel_texel(cell, shape.cells)), cell.z); }
  void mark(glm::ivec3 cell) {
    occupied_cells += occupied(cell) ? 0u : 1u;
    for (int axis = 0; axis < 3; ++axis) {
      const glm::ivec3 along = voxel_axes_along(axis, cell);
      const glm::ivec2 t = voxel_texel_along(voxel_copy_offset(axis, shape.cells), along, voxel_axes_along(axis, shape.cells));
      texels[static_cast<std::size_t>(t.y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(t.x)][(along.z >> 5) & 3] |=
          1u << static_cast<unsigned>(along.z & 31);
    }
  }
  std::size_t bytes() const { return texels.size() * sizeof(glm::uvec4); }
};

/// An empty grid of `shape`.
inline voxel_grid make_voxel_grid(const voxel_grid_shape<float>& shape) {
  voxel_grid grid;
  grid.shape = shape;
  const glm::ivec2 size = voxel_texture_size(shape.cells);
  grid.width = size.x;
  grid.texels.assign(static_cast<std::size_t>(size.x) * static_cast<std::size_t>(size.y), glm::uvec4(0u));
  return grid;
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
/// `fetch(glm::ivec2 texel) -> glm::uvec4` reads the packed grid (the copy along z). The definition
/// that the gather's march, voxel_march_words, is tested against; C++ only (the shaders march words).
/// The steps are written in the order the twin computes them, without a division by a zero
/// direction (infinite steps are a large number instead).
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
  glm::ivec3 step(0);
  glm::vec<3, T> t_max(far), t_delta(far);
  for (int i = 0; i < 3; ++i) {
    if (std::abs(d[i]) > T(1e-12)) {
      step[i] = d[i] > T(0) ? 1 : -1;
      const T boundary = T(cell[i] + (d[i] > T(0) ? 1 : 0));
      t_max[i] = (boundary - u0[i]) * inverse_d[i];
      t_delta[i] = std::abs(inverse_d[i]);
    }
  }
  const int steps = cells.x + cells.y + cells.z;
  for (int n = 0; n <= steps; ++n) {
    if (voxel_bit(fetch(voxel_texel(cell, cells)), cell.z)) return T(0);
    // The axis whose boundary comes first; ties to the lower axis.
    int axis = 0;
    if (t_max.y < t_max[axis]) axis = 1;
    if (t_max.z < t_max[axis]) axis = 2;
    if (t_max[axis] > t_exit) break;
    cell[axis] += step[axis];
    if (cell[axis] < 0 || cell[axis] >= cells[axis]) break;
    t_max[axis] += t_delta[axis];
  }
  return T(1);
}

/// Cells per word of the march (a texel component): voxel_march_words steps the major axis a word at a time.
inline constexpr int voxel_cells_per_word = 32;

/// Whether nothing occupied lies on the segment from `from` to `to` (in the grid's cells): the
/// cells voxel_march_cells visits (up to ties), read from the copy along the segment's major axis a
/// word of 32 cells at a time. In that copy's order (voxel_axes_along) the major axis is z: a 3D
/// DDA over super-cells of 1 x 1 x 32 cells (t_delta.z = 32 |1/d.z|), each step's interval of t
/// ending at the first boundary of the three (or at the clip), and the cells of the step's column
/// of the word from floor(z) where the interval begins to floor(z) where it ends (z is monotonic
/// along the segment) tested at once: a mask of bits low..high of the word's component, both
/// clamped to [0, 31], so that no shift reaches 32. The column sequence is the cell march's (the
/// same x and y boundaries) except at ties: they go to the lower axis in the copy's order, which
/// is not the grid's for every pair (along y the minor axes are z then x; a minor axis goes before
/// the major one); and the runs follow floor(z(t)) where the cell march compares accumulated
/// boundaries. So the two differ where two axes' boundaries meet exactly or within a rounding (a
/// segment through a cell's edge: 2-3 % of the segments between integer points of a cluttered
/// grid, either way; none of 24 000 random ones in the kernel test). 1 visible, 0 hidden.
/// GLSL twin: voxel_march_words.
template <typename T, typename Fetch>
T voxel_march_words(Fetch&& fetch, glm::ivec3 grid_cells, const glm::vec<3, T>& from, const glm::vec<3, T>& to) {
  // The major axis (ties to z, then x): its copy's words lie along the segment.
  const glm::vec<3, T> extent = glm::abs(to - from);
  int major = 2;
  if (extent.x > extent[major]) major = 0;
  if (extent.y > extent[major]) major = 1;
  const int offset = voxel_copy_offset(major, grid_cells);
  const glm::ivec3 cells = voxel_axes_along(major, grid_cells);
  const glm::vec<3, T> u0 = voxel_axes_along(major, from);
  const glm::vec<3, T> d = voxel_axes_along(major, to) - u0;
  const glm::vec<3, T> size(cells);
  constexpr T far = T(1e30);
  // Clip t to the grid's box (slabs), as voxel_march_cells but without a branch per axis (the
  // march's setup is most of its cost: docs/rsm-study.md, "Where the time goes"): an axis the
  // segment does not move along bounds nothing, unless the segment lies outside its slab.
  const glm::vec<3, bool> moving = glm::greaterThan(glm::abs(d), glm::vec<3, T>(T(1e-12)));
  const glm::vec<3, T> inverse_d = glm::mix(glm::vec<3, T>(far), glm::vec<3, T>(T(1)) / glm::mix(glm::vec<3, T>(T(1)), d, moving), moving);
  const glm::vec<3, T> ta = (glm::vec<3, T>(T(0)) - u0) * inverse_d;
  const glm::vec<3, T> tb = (size - u0) * inverse_d;
  const glm::vec<3, T> t_low = glm::mix(glm::vec<3, T>(-far), glm::min(ta, tb), moving);
  const glm::vec<3, T> t_high = glm::mix(glm::vec<3, T>(far), glm::max(ta, tb), moving);
  const glm::vec<3, T> parallel = glm::vec<3, T>(T(1)) - glm::vec<3, T>(moving);
  const T blocked = glm::dot(parallel, glm::vec<3, T>(glm::lessThan(u0, glm::vec<3, T>(T(0)))) + glm::vec<3, T>(glm::greaterThan(u0, size)));
  const T t_enter = glm::max(T(0), glm::max(t_low.x, glm::max(t_low.y, t_low.z)));
  const T t_exit = glm::min(T(1), glm::min(t_high.x, glm::min(t_high.y, t_high.z)));
  if (t_enter > t_exit || blocked > T(0)) return T(1);
  glm::ivec3 cell = glm::clamp(glm::ivec3(glm::floor(u0 + d * t_enter)), glm::ivec3(0), cells - 1);
  // From here cell.z counts words; z_from is the first cell of the current column's run.
  int z_from = cell.z;
  cell.z = cell.z >> 5;
  const glm::vec<3, T> side(T(1), T(1), T(voxel_cells_per_word));  // a super-cell's sides, in cells
  const glm::ivec3 step = glm::ivec3(glm::sign(d)) * glm::ivec3(moving);
  const glm::vec<3, T> boundary = glm::vec<3, T>(cell + glm::ivec3(glm::greaterThan(d, glm::vec<3, T>(T(0))))) * side;
  glm::vec<3, T> t_max = glm::mix(glm::vec<3, T>(far), (boundary - u0) * inverse_d, moving);
  const glm::vec<3, T> t_delta = glm::mix(glm::vec<3, T>(far), glm::abs(inverse_d) * side, moving);
  const glm::ivec3 limit(cells.x, cells.y, (cells.z + voxel_cells_per_word - 1) >> 5);
  const int steps = limit.x + limit.y + limit.z;
  for (int n = 0; n <= steps; ++n) {
    // The axis whose boundary comes first; ties to the lower axis.
    int axis = 0;
    if (t_max.y < t_max[axis]) axis = 1;
    if (t_max.z < t_max[axis]) axis = 2;
    const int z_to = static_cast<int>(std::floor(u0.z + d.z * glm::min(t_max[axis], t_exit)));
    const int base = cell.z << 5;
    const int low = glm::clamp(glm::min(z_from, z_to) - base, 0, 31);
    const int high = glm::clamp(glm::max(z_from, z_to) - base, 0, 31);
    const std::uint32_t mask = (~0u << static_cast<unsigned>(low)) & (~0u >> static_cast<unsigned>(31 - high));
    if ((fetch(voxel_texel_along(offset, glm::ivec3(cell.x, cell.y, base), cells))[cell.z & 3] & mask) != 0u) return T(0);
    if (t_max[axis] > t_exit) break;
    cell[axis] += step[axis];
    if (cell[axis] < 0 || cell[axis] >= limit[axis]) break;
    t_max[axis] += t_delta[axis];
    z_from = z_to;
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

/// voxel_march_words between two world points.
template <typename T, typename Fetch>
T voxel_segment_visible(Fetch&& fetch, const voxel_grid_shape<T>& shape, const glm::vec<3, T>& from, const glm::vec<3, T>& to) {
  const T inverse_cell = T(1) / shape.cell_size;
  return voxel_march_words(fetch, shape.cells, (from - shape.origin) * inverse_cell, (to - shape.origin) * inverse_cell);
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
  return voxel_march_words(fetch, shape.cells, transform_point(to_cells, x + n * (settings.start_offset * shape.cell_size)),
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
  glm::uvec4 operator()(glm::ivec2 texel) const { return grid->texel(texel); }
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
  /// gather_rsm_with calls the march once per this many samples of a path (rsm_sample_group).
  int samples_per_march() const { return settings.group; }
  T operator()(const gather_receiver<T>& receiver, const rsm_texel<T>& light) {
    return voxel_light_visible(fetch, shape, settings, light_to_cells, receiver.position, receiver.normal, light.position, light.normal);
  }
  T coarse(const gather_receiver<T>& receiver, const coarse_light<T>& light) {
    return voxel_coarse_light_visible(fetch, shape, settings, light_to_cells, receiver.position, receiver.normal, light.position, light.normal);
  }
};

}  // namespace vplkit
