// The RSM gather of vplkit/rsm_gather.hpp over a block of receivers, for embedding on a CPU (a
// baker, a path tracer's cache, a test): the same per-sample arithmetic as gather_rsm, laid out
// so that the compiler vectorises it across receivers. The result for every receiver is
// gather_rsm<rsm_pattern::radial, Visibility>(receiver, fetch, settings)'s (the pattern alone, no
// coverage): test_rsm_gather_batch.cpp compares every receiver of a batch with it.
//
// Why this shape (measured with bench/bench_kernels.cpp, gather_batch_cost against gather_cost):
// - The receivers of a batch run in lanes of `rsm_gather_batch_lanes`, one lane per receiver, and
//   every step of a sample (hash, offset, texel, fetch, slot, Alg. 6, Eq. 3.2) is a loop over the
//   lanes without a branch: a skipped sample (off the map, on an empty texel, for a receiver the
//   pattern does not run for) is a mask, selected away, as a GPU's lanes do it. Where the scalar
//   gather returns early, a lane's mask is off for the whole batch.
// - The RSM is read from planes (structure of arrays, rsm_planes): a lane's fetch is nine loads
//   from nine arrays, which the compiler turns into gathers or insert sequences, not a 36-byte
//   struct copy through a callable per sample.
// - What the pattern shares between receivers is computed once per batch: the rings' inner radii
//   (the scalar gather's running product, in the same order, so the same floats) and each
//   sample's hash index.
// - Alg. 6's micro linear buffer is one claim count per slot and lane (the scalar kernel packs
//   them into bytes of four words, which a lane loop cannot index); the saturation at 255 is kept,
//   so the verdicts are the same.
// - hash_uint32's data-dependent shift has no SSE instruction (only AVX2 has per-lane shifts): the
//   lanes use hash_uint32_lanes, the same function with the shift split into four constant shifts
//   under a select (test_rsm_gather_batch.cpp checks it equals hash_uint32).
// - The body is compiled twice (batch_isa.hpp): for the build's x86-64-v2 and with AVX2, chosen at
//   run time. AVX2 gives 8 lanes per instruction and per-lane shifts; not its gathers: GCC 12's
//   generic tuning emulates them, and tuning for Skylake (vgatherdps) made the gather 3x slower on
//   the CPU measured (docs/performance.md). Both paths give the same bits (no FMA either way).
// - direction_from_turns is inlined into its lane loop (it is declared inline: GCC would not inline
//   the template otherwise, and the loop calling it stayed scalar, a third of the time).
// Compile with -fno-math-errno and -fno-trapping-math (vplkit_bench does): with errno, std::sqrt
// keeps a call to libm on a branch, and with trapping math GCC does not if-convert selects after
// float compares; the loops holding them then stay scalar (21 against 31 ns per sample, Alg. 6).
// The header is GLM and the standard library only. It runs one range of receivers on the calling
// thread: a caller spreads a large range over cores by splitting it (each range writes only its
// own outputs), as bench_kernels.cpp does with one range per thread.
//
// GLSL twin: none. This is a CPU-only batching of gather_rsm, whose per-sample arithmetic (and so
// shaders/lib/rsm_gather.glsl's) it repeats operation for operation; the parity of that arithmetic
// with the GLSL is proved on gather_rsm.
#pragma once

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include <vplkit/batch_isa.hpp>
#include <vplkit/hash.hpp>
#include <vplkit/polynomial_math.hpp>
#include <vplkit/rsm_gather.hpp>

namespace vplkit {

/// Receivers per lane block. GCC unrolls a lane loop of 8 completely before it vectorises, and
/// the unrolled straight-line code then keeps its branches; at 32 the lane loops stay loops and
/// vectorise (measured, CPU time, one thread, GCC 12, -march=x86-64-v2: 35 ns per sample with
/// Alg. 6 at 32 lanes against 44 at 16; -fopt-info-vec lists which loops vectorise).
inline constexpr int rsm_gather_batch_lanes = 32;

/// A read-only view of an RSM as nine planes of `size.x * size.y` values, row-major (texel (x, y)
/// at y * size.x + x): the position, normal and flux of rsm_texel, component by component.
template <typename T>
struct rsm_planes {
  glm::ivec2 size{0};
  const T* position[3] = {};
  const T* normal[3] = {};
  const T* flux[3] = {};
};

/// Storage for rsm_planes, filled from a fetch (`fetch(glm::ivec2 texel) -> rsm_texel<T>`, as
/// gather_rsm reads it) once per RSM.
template <typename T>
struct rsm_plane_storage {
  glm::ivec2 size{0};
  std::array<std::vector<T>, 9> planes;
  rsm_planes<T> view() const {
    rsm_planes<T> v;
    v.size = size;
    for (int c = 0; c < 3; ++c) {
      v.position[c] = planes[static_cast<std::size_t>(c)].data();
      v.normal[c] = planes[static_cast<std::size_t>(3 + c)].data();
      v.flux[c] = planes[static_cast<std::size_t>(6 + c)].data();
    }
    return v;
  }
};

template <typename T, typename Fetch>
rsm_plane_storage<T> make_rsm_planes(glm::ivec2 size, Fetch&& fetch) {
  rsm_plane_storage<T> storage;
  storage.size = size;
  const std::size_t count = static_cast<std::size_t>(size.x) * static_cast<std::size_t>(size.y);
  for (auto& plane : storage.planes) plane.resize(count);
  for (int y = 0; y < size.y; ++y)
    for (int x = 0; x < size.x; ++x) {
      const rsm_texel<T> texel = fetch(glm::ivec2(x, y));
      const std::size_t i = static_cast<std::size_t>(y) * static_cast<std::size_t>(size.x) + static_cast<std::size_t>(x);
      for (int c = 0; c < 3; ++c) {
        storage.planes[static_cast<std::size_t>(c)][i] = texel.position[c];
        storage.planes[static_cast<std::size_t>(3 + c)][i] = texel.normal[c];
        storage.planes[static_cast<std::size_t>(6 + c)][i] = texel.flux[c];
      }
    }
  return storage;
}

/// hash_uint32 without a per-lane variable shift: state >> (4 + s) for s = state >> 28 in [0, 15]
/// as >> 4 and then >> 1, 2, 4, 8 under the bits of s. Equal to hash_uint32 for every input.
inline std::uint32_t hash_uint32_lanes(std::uint32_t value) {
  const std::uint32_t state = value * 747796405u + 2891336453u;
  const std::uint32_t s = state >> 28u;
  std::uint32_t shifted = state >> 4u;
  shifted = (s & 1u) != 0u ? shifted >> 1u : shifted;
  shifted = (s & 2u) != 0u ? shifted >> 2u : shifted;
  shifted = (s & 4u) != 0u ? shifted >> 4u : shifted;
  shifted = (s & 8u) != 0u ? shifted >> 8u : shifted;
  const std::uint32_t word = (shifted ^ state) * 277803737u;
  return (word >> 22u) ^ word;
}

/// hash_combine through hash_uint32_lanes: equal to hash_combine.
inline std::uint32_t hash_combine_lanes(std::uint32_t seed, std::uint32_t value) {
  return hash_uint32_lanes(seed ^ (value + 0x9e3779b9u + (seed << 6u) + (seed >> 2u)));
}

namespace detail {

/// gather_rsm_batch's work, inlined into one function per instruction set (below): the same
/// source, so the same operations in the same order on every path.
template <rsm_visibility Visibility, typename T>
VPLKIT_BATCH_ALWAYS_INLINE inline void gather_rsm_batch_body(const gather_receiver<T>* receivers, std::size_t count, const rsm_planes<T>& rsm,
                                                            const rsm_gather_settings<T>& settings, glm::vec<3, T>* irradiance) {
  static_assert(Visibility == rsm_visibility::none || Visibility == rsm_visibility::alg6,
                "gather_rsm_batch: visibility none or alg6 (the others keep per-sample state a lane loop cannot hold)");
  constexpr int W = rsm_gather_batch_lanes;
  const radial_pattern_constants<T>& radial = settings.radial;
  const int paths = radial.paths, samples = radial.samples_per_path;
  // Shared by every receiver: the rings' inner radii, as the scalar gather's running product.
  std::vector<T> ring_inner(static_cast<std::size_t>(samples));
  {
    T inner = radial.min_radius;
    for (int s = 0; s < samples; ++s) {
      ring_inner[static_cast<std::size_t>(s)] = inner;
      inner *= radial.ring_ratio;
    }
  }
  const int slot_count = settings.slots.count;
  const int boundaries = slot_count - 1;
  const T* const boundary_tangent = settings.slots.boundary_tangent;
  const int width = rsm.size.x, height = rsm.size.y;
  const T min_distance = T(settings.irradiance.min_distance);
  const T min_distance_squared = min_distance * min_distance;

  for (std::size_t first = 0; first < count; first += W) {
    const std::size_t in_block = count - first < std::size_t(W) ? count - first : std::size_t(W);
    alignas(64) T rx[W], ry[W], rz[W], nx[W], ny[W], nz[W], cu[W], cv[W], rotation[W], scale[W];
    alignas(64) std::uint32_t pixel_hash[W];
    alignas(64) int active[W];
    alignas(64) T sum_r[W], sum_g[W], sum_b[W];
    for (int l = 0; l < W; ++l) {
      // Padding lanes repeat the last receiver, inactive.
      const gather_receiver<T>& r = receivers[first + (std::size_t(l) < in_block ? std::size_t(l) : in_block - 1)];
      rx[l] = r.position.x, ry[l] = r.position.y, rz[l] = r.position.z;
      nx[l] = r.normal.x, ny[l] = r.normal.y, nz[l] = r.normal.z;
      cu[l] = r.rsm_coordinate.x, cv[l] = r.rsm_coordinate.y;
      const radial_pixel<T> pixel = radial_pattern_pixel(r.pixel, radial);
      pixel_hash[l] = pixel.hash, rotation[l] = pixel.rotation, scale[l] = pixel.scale;
      // gather_rsm_with's early outs: behind the light, or the pattern cannot reach the map.
      const glm::vec<2, T> size(settings.rsm_size);
      const glm::vec<2, T> outside = glm::max(glm::max(-r.rsm_coordinate, r.rsm_coordinate - size), glm::vec<2, T>(T(0)));
      const T reach = pixel.scale * radial.max_radius;
      active[l] = std::size_t(l) < in_block && r.position.z < T(0) && glm::dot(outside, outside) <= (reach + T(1)) * (reach + T(1)) ? 1 : 0;
      sum_r[l] = sum_g[l] = sum_b[l] = T(0);
      // An inactive lane still runs every step: its projection (far off the map, or a mirrored one
      // behind the light) must not overflow the float-to-int conversion of the texel, undefined
      // behaviour the scalar gather never reaches. Active lanes lie within reach of the map.
      if (active[l] == 0) cu[l] = cv[l] = T(0);
    }
    int any_active = 0;
    for (int l = 0; l < W; ++l) any_active |= active[l];
    if (any_active != 0) {
      // Each step below is one loop over the lanes (the loop the compiler vectorises); the loops
      // over slots stay outside them. Masks are ints combined with &, not bools with && (whose
      // short circuit is control flow, which stops the vectoriser).
      // Alg. 6's slot values are the integers 1, 0, -1, ... (1 - claims): kept as ints, whose selects
      // vectorise where float compares (which may trap) kept GCC from if-converting the loop.
      alignas(64) int claims[micro_linear_buffer_max_slots][W];
      alignas(64) int previous_index[W];
      alignas(64) int previous_visibility[W];
      alignas(64) int texel_index[W], lit[W], slot[W], slot_claims[W], claim[W];
      alignas(64) T turns[W], sample_radius[W], weight[W], dz[W], horizontal[W], seen[W], px[W], py[W], pz[W];
      for (int path = 0; path < paths; ++path) {
        for (int k = 0; k < slot_count; ++k)
          for (int l = 0; l < W; ++l) claims[k][l] = 0;
        for (int l = 0; l < W; ++l) previous_index[l] = -1, previous_visibility[l] = 1;
        for (int sample = 0; sample < samples; ++sample) {
          const T inner = ring_inner[static_cast<std::size_t>(sample)];
          const T outer = inner * radial.ring_ratio;
          const std::uint32_t sample_number = static_cast<std::uint32_t>(2 + path * samples + sample);
          // radial_pattern_sample and the texel it lands on.
          for (int l = 0; l < W; ++l) {
            const std::uint32_t sample_hash = hash_combine_lanes(pixel_hash[l], sample_number);
            const T angle_offset = radial.angle_jitter * (T(uniform_float_from_bits(sample_hash)) - T(0.5));
            const T radial_position = T(uniform_float_from_bits(hash_uint32_lanes(sample_hash)));
            const T ring_width = scale[l] * (outer - inner);
            const T radius = scale[l] * inner + radial_position * ring_width;
            turns[l] = radial.path_turns * (T(path) + rotation[l] + angle_offset);
            sample_radius[l] = radius;
            weight[l] = radial.path_angle * radius * ring_width;
          }
          for (int l = 0; l < W; ++l) {
            const glm::vec<2, T> direction = direction_from_turns(turns[l]);
            const T radius = sample_radius[l];
            const int tx = static_cast<int>(std::floor(cu[l] + direction.x * radius));
            const int ty = static_cast<int>(std::floor(cv[l] + direction.y * radius));
            const int in_map = int(tx >= 0) & int(ty >= 0) & int(tx < width) & int(ty < height);
            lit[l] = in_map & active[l];
            texel_index[l] = (ty * width + tx) & -in_map;  // 0 off the map
          }
          // The fetch's position, read once (the planes' loads are emulated gathers, the dearest
          // part of a lane step), and its depth: an empty texel is no sample.
          for (int l = 0; l < W; ++l) {
            const std::size_t i = static_cast<std::size_t>(texel_index[l]);
            px[l] = rsm.position[0][i], py[l] = rsm.position[1][i], pz[l] = rsm.position[2][i];
            lit[l] &= int(pz[l] < T(0));
          }
          if constexpr (Visibility == rsm_visibility::alg6) {
            // elevation_bucket, then micro_linear_buffer_alg6 with the slot's count picked by a select per slot.
            for (int l = 0; l < W; ++l) {
              const T dx = px[l] - rx[l], dy = py[l] - ry[l];
              dz[l] = pz[l] - rz[l];
              horizontal[l] = std::sqrt(dx * dx + dy * dy);
              slot[l] = 0;
              slot_claims[l] = 0;
            }
            for (int k = 0; k < boundaries; ++k)
              for (int l = 0; l < W; ++l) slot[l] += dz[l] >= boundary_tangent[k] * horizontal[l] ? 1 : 0;
            for (int k = 0; k < slot_count; ++k)
              for (int l = 0; l < W; ++l) slot_claims[l] = slot[l] == k ? claims[k][l] : slot_claims[l];
            for (int l = 0; l < W; ++l) {
              const bool same_as_previous = slot[l] == previous_index[l];
              const int slot_value = 1 - slot_claims[l];
              const int visibility = same_as_previous ? previous_visibility[l] : slot_value;
              claim[l] = lit[l] & int(!same_as_previous) & int(slot_claims[l] < 255);  // value -= 1, saturating
              previous_index[l] = lit[l] != 0 ? slot[l] : previous_index[l];
              previous_visibility[l] = lit[l] != 0 ? visibility : previous_visibility[l];
              seen[l] = T(glm::clamp(visibility, 0, 1));  // exact: the clamp of the same integer as a float
            }
            for (int k = 0; k < slot_count; ++k)
              for (int l = 0; l < W; ++l) claims[k][l] += slot[l] == k ? claim[l] : 0;
          } else {
            for (int l = 0; l < W; ++l) seen[l] = T(1);
          }
          // pixel_light_irradiance (Eq. 3.2), operation for operation, weighted and summed.
          for (int l = 0; l < W; ++l) {
            const std::size_t i = static_cast<std::size_t>(texel_index[l]);
            const T lx = rx[l] - px[l], ly = ry[l] - py[l], lz = rz[l] - pz[l];
            const T distance_squared = glm::max(lx * lx + ly * ly + lz * lz, min_distance_squared);
            const T emit = glm::max(T(0), rsm.normal[0][i] * lx + rsm.normal[1][i] * ly + rsm.normal[2][i] * lz);
            const T receive = glm::max(T(0), -(nx[l] * lx + ny[l] * ly + nz[l] * lz));
            const T factor = (emit / distance_squared) * (receive / distance_squared);
            const T scaled = seen[l] * weight[l];
            const T er = rsm.flux[0][i] * factor, eg = rsm.flux[1][i] * factor, eb = rsm.flux[2][i] * factor;
            // Times 1 or 0, not a select: the same sums (x * 1 = x, s + 0 = s), and a product where a
            // select of a computed value kept GCC from if-converting the loop.
            const T mask = T(lit[l]);
            sum_r[l] += (scaled * er) * mask;
            sum_g[l] += (scaled * eg) * mask;
            sum_b[l] += (scaled * eb) * mask;
          }
        }
      }
    }
    for (std::size_t l = 0; l < in_block; ++l) {
      const T one_over_pi = T(0.318309886183790671538);
      irradiance[first + l] = glm::vec<3, T>(sum_r[l], sum_g[l], sum_b[l]) * one_over_pi;
    }
  }
}

template <rsm_visibility Visibility, typename T>
void gather_rsm_batch_portable(const gather_receiver<T>* receivers, std::size_t count, const rsm_planes<T>& rsm, const rsm_gather_settings<T>& settings,
                               glm::vec<3, T>* irradiance) {
  gather_rsm_batch_body<Visibility>(receivers, count, rsm, settings, irradiance);
}

#if VPLKIT_BATCH_HAS_AVX2
template <rsm_visibility Visibility, typename T>
VPLKIT_BATCH_TARGET_AVX2 void gather_rsm_batch_avx2(const gather_receiver<T>* receivers, std::size_t count, const rsm_planes<T>& rsm,
                                                    const rsm_gather_settings<T>& settings, glm::vec<3, T>* irradiance) {
  gather_rsm_batch_body<Visibility>(receivers, count, rsm, settings, irradiance);
}
#endif

}  // namespace detail

/// The gather of gather_rsm<rsm_pattern::radial, Visibility>(receivers[i], fetch, settings) for i
/// in [0, count), written to irradiance[i]: the pattern alone (settings.coverage_blocks is not
/// read), Visibility none or alg6. `rsm.size` must be settings.rsm_size. `isa` picks the
/// instantiation (batch_isa.hpp); one the CPU does not run falls back to the portable one.
template <rsm_visibility Visibility, typename T>
void gather_rsm_batch(const gather_receiver<T>* receivers, std::size_t count, const rsm_planes<T>& rsm, const rsm_gather_settings<T>& settings,
                      glm::vec<3, T>* irradiance, batch_isa isa = best_batch_isa()) {
#if VPLKIT_BATCH_HAS_AVX2
  if (isa == batch_isa::avx2 && batch_isa_supported(batch_isa::avx2)) {
    detail::gather_rsm_batch_avx2<Visibility>(receivers, count, rsm, settings, irradiance);
    return;
  }
#else
  (void)isa;
#endif
  detail::gather_rsm_batch_portable<Visibility>(receivers, count, rsm, settings, irradiance);
}

}  // namespace vplkit
