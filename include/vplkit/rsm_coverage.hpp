// Indirect light for the receivers the RSM gather's pattern cannot reach. [RSMV]'s gather starts
// at the receiver's projection onto the RSM: a receiver behind a spot light (light eye z >= 0)
// has none, and one outside the light's frustum projects off the map, where the pattern reaches
// only the part of the RSM within its radius. The pixel lights light them all the same: the
// ceiling and the upper walls of a room lit by a spot under its ceiling (45 % of the Cornell box's
// indirect light).
//
// Coverage (docs/errata.md, RSMV-10): the RSM is cut into C x C blocks, and each block becomes one
// coarse pixel light (reduce_rsm_block): its flux is the sum of its texels' flux; its position and
// normal are their means weighted by each texel's flux (r + g + b), the normal left unnormalised
// (for a block across a corner, <mean normal, d> is the mean of the faces' cosines, exact where
// both are positive); its extent is the weighted mean squared distance of its texels from that
// position. The gather (rsm_gather.hpp) adds, for a receiver the pattern cannot reach, every coarse
// light whose block the pattern does not reach: behind the light every block; off the map the
// blocks whose centre lies beyond the pattern's outer radius from the projection (the pattern
// gathers the others, with its visibility); with an interleave of side s, only those on the
// receiver's lattice of stride s, weighted s^2 (coverage_interleave_phase). No visibility for the
// coarse lights: the micro linear buffer needs a path from a projection.
//
// A coarse light's irradiance (coarse_light_irradiance) is Eq. 3.2 with twice the extent added to
// the squared distance of its second factor:
//   E = flux * (<n_c, x - x_c>+ / max(d^2, m^2)) * (<n, x_c - x>+ / (max(d^2, m^2) + 2 extent)),
// which is exact on the axis of a uniform Lambertian disk (radius R, mean squared radius R^2 / 2:
// E = F / (pi (d^2 + R^2)) with the gather's 1/pi) and within a few percent on a square's: near
// its block the light is that of a surface of its size, not a point's, which grows like 1 / d^2
// and over-estimates by a third at a distance of one block side.
//
// GLSL twin: shaders/lib/rsm_coverage.glsl.
#pragma once

#include <cmath>

#include <glm/glm.hpp>

#include <vplkit/irradiance.hpp>

namespace vplkit {

/// Largest C (blocks per side). GLSL: VPLKIT_MAX_COVERAGE_BLOCKS.
inline constexpr int rsm_coverage_max_blocks = 64;

/// Returns nullptr when `blocks` (C) is usable, 0 (coverage off) included, else why not.
constexpr const char* validate_coverage_blocks(int blocks) {
  if (blocks < 0 || blocks > rsm_coverage_max_blocks) return "coverage blocks per side must be in [0, 64] (0: no coverage)";
  return nullptr;
}

/// Largest interleave side s (rsm_gather_settings::coverage_interleave).
inline constexpr int rsm_coverage_max_interleave = 8;

/// Returns nullptr when the interleave side s is usable (1: every receiver gathers every block).
constexpr const char* validate_coverage_interleave(int side) {
  if (side < 1 || side > rsm_coverage_max_interleave) return "coverage interleave must be in [1, 8] (1: every receiver gathers every block)";
  return nullptr;
}

/// Whether every receiver's lattice of the interleave holds a block: s <= C (or no coverage, or no
/// interleave). Past it a receiver whose pixel modulo s is >= C gathers no coarse light at all.
constexpr bool coverage_lattice_holds_a_block(int blocks, int side) { return blocks <= 0 || side <= 1 || side <= blocks; }

/// Interleaved coverage (Keller and Heidrich's interleaved sampling): with side s the receiver at
/// pixel p gathers only the blocks b with b % s == p % s (per axis), each weighted s^2, so that
/// the s x s receivers of a pixel tile together gather every block once and the post filter,
/// which averages many more texels than s^2, restores the whole sum. The gather costs up to s^2
/// times less: the receivers shaded together pay for the largest lattice, ceil(C / s)^2 blocks
/// (C = 16, s = 3: 36 of 256, 7x). The first block of pixel p's lattice. GLSL twin:
/// coverage_interleave_phase.
inline glm::ivec2 coverage_interleave_phase(glm::uvec2 pixel, int side) {
  const auto s = static_cast<unsigned>(side > 0 ? side : 1);
  return glm::ivec2(static_cast<int>(pixel.x % s), static_cast<int>(pixel.y % s));
}

/// One coarse pixel light, in the light's eye space like the RSM's. GLSL twin: struct coarse_light.
template <typename T>
struct coarse_light {
  glm::vec<3, T> position{T(0)};  ///< flux-weighted mean of its texels' positions
  glm::vec<3, T> normal{T(0)};    ///< flux-weighted mean of their unit normals (length <= 1)
  glm::vec<3, T> flux{T(0)};      ///< the sum of their flux
  T extent = T(0);                ///< flux-weighted mean squared distance of its texels from `position`
};

/// The running sums of reduce_rsm_block. Positions are summed relative to the first pixel light
/// added (`origin`), so that the extent, a mean square less a squared mean, is a difference of
/// numbers of the block's size rather than of its distance from the light.
template <typename T>
struct coarse_light_sum {
  glm::vec<3, T> origin{T(0)};
  glm::vec<3, T> position{T(0)};  ///< sum of weight * (position - origin)
  glm::vec<3, T> normal{T(0)};
  glm::vec<3, T> flux{T(0)};
  T square = T(0);                ///< sum of weight * |position - origin|^2
  T weight = T(0);
  int count = 0;
};

/// Adds one pixel light (position, unit normal, flux) to the sums.
template <typename T>
void coarse_light_add(coarse_light_sum<T>& sum, const glm::vec<3, T>& position, const glm::vec<3, T>& normal, const glm::vec<3, T>& flux) {
  if (sum.count == 0) sum.origin = position;
  const T weight = flux.x + flux.y + flux.z;
  const glm::vec<3, T> offset = position - sum.origin;
  sum.position += weight * offset;
  sum.normal += weight * normal;
  sum.flux += flux;
  sum.square += weight * glm::dot(offset, offset);
  sum.weight += weight;
  sum.count += 1;
}

/// The coarse light of the sums; a block without flux is all zeros (it lights nothing).
template <typename T>
coarse_light<T> coarse_light_from(const coarse_light_sum<T>& sum) {
  coarse_light<T> light;
  if (!(sum.weight > T(0))) return light;
  const T inverse = T(1) / sum.weight;
  const glm::vec<3, T> mean_offset = sum.position * inverse;
  light.position = sum.origin + mean_offset;
  light.normal = sum.normal * inverse;
  light.flux = sum.flux;
  light.extent = glm::max(T(0), sum.square * inverse - glm::dot(mean_offset, mean_offset));
  return light;
}

/// The side of a block in texels for an RSM of `rsm_size` cut into `blocks` per side (the last
/// block of a row may be shorter).
inline glm::ivec2 coverage_block_side(glm::ivec2 rsm_size, int blocks) { return (rsm_size + blocks - 1) / blocks; }

/// The coarse light of block `block` (0 <= block < blocks per axis): every texel of the block read
/// through `fetch(glm::ivec2) -> rsm_texel` (rsm_gather.hpp), row by row; empty texels (eye
/// depth >= 0) are skipped.
template <typename T, typename Fetch>
coarse_light<T> reduce_rsm_block(glm::ivec2 block, int blocks, glm::ivec2 rsm_size, Fetch&& fetch) {
  const glm::ivec2 side = coverage_block_side(rsm_size, blocks);
  const glm::ivec2 first = block * side, last = glm::min(first + side, rsm_size);
  coarse_light_sum<T> sum;
  for (int y = first.y; y < last.y; ++y)
    for (int x = first.x; x < last.x; ++x) {
      const auto texel = fetch(glm::ivec2(x, y));
      if (texel.position.z < T(0)) coarse_light_add(sum, texel.position, texel.normal, texel.flux);
    }
  return coarse_light_from(sum);
}

/// The irradiance at (x, n) due to one coarse light: Eq. 3.2 with twice the light's extent added
/// to the second squared distance (see the top). Without the gather's 1/pi, like
/// pixel_light_irradiance.
template <typename T, typename S = T>
glm::vec<3, T> coarse_light_irradiance(const glm::vec<3, T>& x, const glm::vec<3, T>& n, const coarse_light<T>& light,
                                       const irradiance_settings<S>& settings = {}) {
  const glm::vec<3, T> light_to_receiver = x - light.position;
  const T min_distance = T(settings.min_distance);
  const T distance_squared = glm::max(glm::dot(light_to_receiver, light_to_receiver), min_distance * min_distance);
  const T spread_squared = distance_squared + T(2) * light.extent;
  const T emit = glm::max(T(0), glm::dot(light.normal, light_to_receiver));
  const T receive = glm::max(T(0), -glm::dot(n, light_to_receiver));
  // One division for both factors: the gather evaluates this for every coarse light of every
  // uncovered receiver, where a second division measured about 5 % of loft 3's frame (docs/rsm-study.md).
  return light.flux * ((emit * receive) / (distance_squared * spread_squared));
}

/// The centre of block `block` in RSM texels (continuous coordinates, like a receiver's projection).
template <typename T>
glm::vec<2, T> coverage_block_centre(glm::ivec2 block, glm::ivec2 side) {
  return (glm::vec<2, T>(block) + T(0.5)) * glm::vec<2, T>(side);
}

}  // namespace vplkit
