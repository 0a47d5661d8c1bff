// The per-receiver RSM gather of [RSMV]: Alg. 1 (with the visibility of Alg. 2 or 3) and
// Alg. 5 (with the branch-free visibility of Alg. 6), or the original RSM gather with the disk
// pattern. Returns the irradiance at the receiver due to the RSM's pixel lights.
//
// The RSM is read through a callable, `fetch(glm::ivec2 texel) -> rsm_texel<T>` (in GLSL the
// including shader defines `rsm_texel rsm_fetch(ivec2 texel)`), so the same gather runs on
// textures, on read-back buffers and on synthetic RSMs in tests.
//
// Irradiance: Eq. 3.2 leaves out the 1/pi of a Lambertian pixel light (as Dachsbacher and
// Stamminger 2005 do); the gather applies it once at the end, so with the RSM's flux being
// the flux reflected by each texel, the result is the physical irradiance and albedo / pi times
// it the reflected radiance. Samples outside the RSM, or on empty texels (eye depth >= 0:
// nothing was rendered there), are skipped and do not touch the micro linear buffer (Alg. 1,
// line 9: visibility is computed only for samples inside the RSM).
//
// A receiver behind the light (light eye z >= 0) has no projection onto the RSM: the perspective
// divide mirrors it, and sampling around the mirrored point lit a blob on the Cornell box's
// ceiling. The pattern skips such a receiver; one outside the light's frustum gets what the
// pattern reaches from its projection off the map. With coverage (settings.coverage_blocks > 0
// and a coarse-light fetch: vplkit/rsm_coverage.hpp, docs/errata.md RSMV-10) both also gather the
// coarse pixel lights of the blocks the pattern does not reach; without it they get only what
// the pattern reaches, as in the thesis.
//
// Space: the gather runs in the light's eye space. The elevation angle of Alg. 1 is defined
// there (section 4.2: the thesis stores the light's eye-space depth in the RSM for it), and
// Eq. 3.2 is unchanged by the light's view, a rigid motion. So a pixel light is its eye-space
// position and normal, which the one-texel RSM of vplkit/rsm_packing.hpp rebuilds from a depth
// and the texel's centre ray without a matrix, and the receiver is moved into that space once
// (make_gather_receiver); dz = z_p - z_x and |dxy| come straight from the two positions.
//
// GLSL twin: shaders/lib/rsm_gather.glsl, with VPLKIT_RSM_PATTERN and VPLKIT_VISIBILITY
// (#defines) for the template parameters.
#pragma once

#include <cmath>

#include <glm/glm.hpp>

#include <type_traits>
#include <utility>

#include <vplkit/irradiance.hpp>
#include <vplkit/micro_linear_buffer.hpp>
#include <vplkit/rsm_coverage.hpp>
#include <vplkit/rsm_pattern.hpp>
#include <vplkit/transform.hpp>

namespace vplkit {

/// One texel of the RSM (Fig. 4.2): a pixel light.
template <typename T>
struct rsm_texel {
  glm::vec<3, T> position;  ///< light eye space; z < 0 in front of the light, z >= 0: empty texel
  glm::vec<3, T> normal;    ///< light eye space, unit
  glm::vec<3, T> flux;      ///< flux reflected by the texel
};

enum class rsm_pattern { radial = 0, disk = 1 };                 ///< GLSL: VPLKIT_RSM_PATTERN 0 / 1
/// The visibility of the samples: none, the thesis's Alg. 2, 3 and 6 as printed, or alg6_ray:
/// Alg. 6 with the elevation measured about the receiver's own light ray (elevation_bucket_about,
/// `up` towards the light), without the samples that lie in or behind the receiver's tangent plane
/// (they light nothing and hide nothing), and with Alg. 3's same-slot rule only between samples
/// that cannot hide one another (micro_linear_buffer_alg6_ray; docs/errata.md, RSMV-12). GLSL:
/// VPLKIT_VISIBILITY. voxel: the scene's occupancy grid beyond the RSM (vplkit/voxel_visibility.hpp,
/// voxel_rsm_visibility; gather_rsm_with takes it: gather_rsm has no grid).
enum class rsm_visibility { none = 0, alg2 = 2, alg3 = 3, alg6 = 6, alg6_ray = 7, voxel = 8 };

/// "none", "alg2", "alg3", "alg6", "alg6-ray".
inline const char* visibility_name(rsm_visibility visibility) {
  switch (visibility) {
    case rsm_visibility::none: return "none";
    case rsm_visibility::alg2: return "alg2";
    case rsm_visibility::alg3: return "alg3";
    case rsm_visibility::alg6: return "alg6";
    case rsm_visibility::alg6_ray: return "alg6-ray";
    case rsm_visibility::voxel: return "voxel";
  }
  return "unknown";
}



/// Everything the gather needs besides the receiver and the RSM. GLSL twin: the uniforms of
/// shaders/gather.frag, filled by set_uniforms.
template <typename T>
struct rsm_gather_settings {
  irradiance_settings<T> irradiance;
  radial_pattern_constants<T> radial = make_radial_pattern_constants(radial_pattern_settings<T>{});
  disk_pattern_settings<T> disk;
  elevation_slots<T> slots = make_elevation_slots<T>(5);  ///< the thesis's 5 slots
  glm::ivec2 rsm_size = glm::ivec2(512);
  /// C, the coarse lights' blocks per side of the RSM (vplkit/rsm_coverage.hpp); 0: no coverage, as
  /// in the thesis. Read only by the gathers given a coarse-light fetch.
  int coverage_blocks = 0;
  /// s, the side of the pixel tile over which the coverage's blocks are interleaved
  /// (coverage_interleave_phase): each receiver gathers every s-th block per axis, weighted s^2.
  /// 1: every receiver gathers every block.
  int coverage_interleave = 1;
  /// 1: the RSM is a perspective (spot) light's, the light at the eye-space origin; 0: an
  /// orthographic (directional) one, shining along -z. alg6_ray's `up` is the direction to the
  /// light: -position / |position|, or +z.
  int perspective = 1;
};

/// The coverage the defaults use: 16 x 16 coarse lights (docs/rsm-study.md, "Any frame").
inline constexpr int default_coverage_blocks = 16;
/// The interleave the defaults use (docs/rsm-study.md, "The coverage's cost").
inline constexpr int default_coverage_interleave = 3;

template <typename T>
struct settings_description<rsm_gather_settings<T>> {
  using S = rsm_gather_settings<T>;
  static constexpr const char* name = "rsm_gather_settings";
  static constexpr bool glsl_twin = true;
  static constexpr auto fields() {
    return std::make_tuple(schema::field(&S::irradiance, "irradiance", schema::any_finite(), "", "Eq. 3.2's distance clamp"),
                           schema::field(&S::radial, "radial", schema::any_finite(), "", "the radial pattern (Alg. 1 and 5)"),
                           schema::field(&S::disk, "disk", schema::any_finite(), "", "the original RSM's disk pattern"),
                           schema::field(&S::slots, "slots", schema::any_finite(), "", "the micro linear buffer's elevation slots"),
                           schema::field(&S::rsm_size, "rsm_size", schema::at_least(1), "texels", "the RSM's width and height"),
                           schema::field(&S::coverage_blocks, "coverage_blocks", schema::closed_range(0, rsm_coverage_max_blocks), "per RSM side",
                                 "coarse pixel lights that light the receivers the pattern cannot reach; 0: none"),
                           schema::field(&S::coverage_interleave, "coverage_interleave", schema::closed_range(1, rsm_coverage_max_interleave), "pixels",
                                 "side of the pixel tile the coverage's blocks are interleaved over (each receiver gathers 1 / side^2 of them); 1: none"),
                           schema::field(&S::perspective, "perspective", schema::closed_range(0, 1), "", "1: a spot light (perspective RSM), 0: a directional one"));
  }
  static setting_problem rules(const S& settings) {
    if (!coverage_lattice_holds_a_block(settings.coverage_blocks, settings.coverage_interleave))
      return setting_problem("rsm_gather_settings::coverage_interleave must not exceed coverage_blocks: a receiver's lattice would hold no block");
    return {};
  }
};

/// The few numbers that shape the gather, with the radius relative to the RSM so that it scales
/// with the RSM's size.
template <typename T>
struct rsm_gather_preset {
  T radius_fraction;     ///< r_max of the radial and disk patterns as a fraction of the RSM's larger side
  int paths;             ///< P
  int samples_per_path;  ///< S
  int slots;             ///< B, micro linear buffer slots
};

template <typename T>
struct settings_description<rsm_gather_preset<T>> {
  using S = rsm_gather_preset<T>;
  static constexpr const char* name = "rsm_gather_preset";
  static constexpr bool glsl_twin = false;  // make_rsm_gather_settings turns it into rsm_gather_settings
  static constexpr auto fields() {
    return std::make_tuple(schema::field(&S::radius_fraction, "radius_fraction", schema::open_closed_range(0, 2), "of the RSM side",
                                 "r_max of the radial and disk patterns as a fraction of the RSM's larger side"),
                           schema::field(&S::paths, describe_field(&radial_pattern_settings<T>::paths)),
                           schema::field(&S::samples_per_path, describe_field(&radial_pattern_settings<T>::samples_per_path)),
                           schema::field(&S::slots, describe_field(&elevation_slots<T>::count)));
  }
  static setting_problem rules(const S& settings) { return schema::no_rules(settings); }
};

/// The defaults, chosen by the study of bench/rsm-study.sweep (docs/rsm-study.md) against the
/// brute-force gather on five occlusion scenes: 3/4 of the RSM side is the smallest radius of
/// the study whose gather misses at most ~1 % of the light the whole RSM delivers (1/8 missed
/// 64-75 %, 1/2 up to 7 %), and 20 paths x 15 samples with 8 slots is the cheapest point of the
/// study at which Alg. 6 lowers the error against exact visibility and at least halves the leak
/// on every scene (5 slots over-occlude at 20 x 15: their error rose above no visibility's).
template <typename T>
constexpr rsm_gather_preset<T> default_rsm_gather_preset() {
  return {T(0.75), 20, 15, 8};
}

/// The thesis's configuration: 15 paths x 10 samples, 5 slots; the thesis gives no radius, and
/// 1/8 of the RSM (64 texels of 512) is what this project used before the study.
template <typename T>
constexpr rsm_gather_preset<T> thesis_rsm_gather_preset() {
  return {T(0.125), 15, 10, 5};
}

/// The receiver: a G-buffer sample, in the light's eye space like the pixel lights.
template <typename T>
struct gather_receiver {
  glm::vec<3, T> position;        ///< light eye space
  glm::vec<3, T> normal;          ///< light eye space, unit
  glm::vec<2, T> rsm_coordinate;  ///< its projection onto the RSM, in texels (continuous)
  glm::uvec2 pixel;               ///< its pixel in the indirect buffer (seeds the pattern)
};

/// A G-buffer sample (world space) as the gather's receiver: moved into the light's eye space by
/// `light_view` (rigid, so the normal turns with its upper 3x3, transform_direction) and projected onto the RSM.
template <typename T>
gather_receiver<T> make_gather_receiver(const glm::vec<3, T>& world_position, const glm::vec<3, T>& world_normal,
                                        const glm::mat<4, 4, T>& light_view, const glm::mat<4, 4, T>& light_view_projection,
                                        glm::ivec2 rsm_size, glm::uvec2 pixel) {
  return {transform_point(light_view, world_position), transform_direction(light_view, world_normal),
          map_coordinate(light_view_projection, world_position, rsm_size), pixel};
}

/// The sampling radius in texels for one given as a fraction of the RSM's larger side.
template <typename T>
T rsm_radius_in_texels(T radius_fraction, glm::ivec2 rsm_size) {
  return radius_fraction * T(glm::max(rsm_size.x, rsm_size.y));
}

/// Gather settings for an RSM of `rsm_size` texels, derived in one place: the radial and disk
/// patterns with their radius (rsm_radius_in_texels of `radius_fraction`; their own max_radius is
/// replaced), the pattern constants and the slot tangents. irradiance keeps its default.
template <typename T>
rsm_gather_settings<T> make_rsm_gather_settings(radial_pattern_settings<T> radial, disk_pattern_settings<T> disk, T radius_fraction, int slots,
                                                glm::ivec2 rsm_size) {
  radial.max_radius = disk.max_radius = rsm_radius_in_texels(radius_fraction, rsm_size);
  rsm_gather_settings<T> settings;
  settings.radial = make_radial_pattern_constants(radial);
  settings.disk = disk;
  settings.slots = make_elevation_slots<T>(slots);
  settings.rsm_size = rsm_size;
  return settings;
}

/// Gather settings for an RSM of `rsm_size` texels from a preset, the other pattern settings at
/// their defaults.
template <typename T>
rsm_gather_settings<T> rsm_gather_settings_from(const rsm_gather_preset<T>& preset, glm::ivec2 rsm_size) {
  radial_pattern_settings<T> radial;
  radial.paths = preset.paths;
  radial.samples_per_path = preset.samples_per_path;
  return make_rsm_gather_settings(radial, disk_pattern_settings<T>{}, preset.radius_fraction, preset.slots, rsm_size);
}

/// The gather settings of `vplkit render` for an RSM of `rsm_size` texels: the default preset with
/// coverage, every receiver gathering every coarse light. `vplkit render` also interleaves them
/// (coverage_interleave = default_coverage_interleave), which needs the post filter after the
/// gather to average each tile: set it only where such a filter follows.
template <typename T>
rsm_gather_settings<T> default_rsm_gather_settings(glm::ivec2 rsm_size) {
  rsm_gather_settings<T> settings = rsm_gather_settings_from(default_rsm_gather_preset<T>(), rsm_size);
  settings.coverage_blocks = default_coverage_blocks;
  return settings;
}

/// The coarse-light fetch of a gather without coverage.
struct no_coarse_lights {};

/// Consecutive samples of a path that share one visibility call (rsm-voxel's
/// voxel_march_settings::group): the sum of their weighted irradiances, and the pixel light of the
/// largest, the one the group is judged by. So a group whose members are all visible or all hidden
/// gets the per-sample answer exactly, and a group wholly behind a wall stays dark. GLSL twin:
/// struct rsm_sample_group in lib/rsm_gather.glsl.
template <typename T>
struct rsm_sample_group {
  glm::vec<3, T> sum{T(0)};
  T best = T(0);          ///< the largest member's weighted irradiance, summed over the channels; 0: none lights the receiver
  rsm_texel<T> light{};   ///< that member
  void add(const glm::vec<3, T>& weighted, const rsm_texel<T>& member) {
    sum += weighted;
    const T size = weighted.x + weighted.y + weighted.z;
    if (size > best) {
      best = size;
      light = member;
    }
  }
};

namespace detail {

/// alg6_ray's `up` for a receiver: the unit direction from it towards the light (see
/// rsm_gather_settings::perspective).
template <typename T>
glm::vec<3, T> towards_light(const gather_receiver<T>& receiver, const rsm_gather_settings<T>& settings) {
  if (settings.perspective == 0) return glm::vec<3, T>(T(0), T(0), T(1));
  return -receiver.position / std::sqrt(receiver.position.x * receiver.position.x + receiver.position.y * receiver.position.y +
                                        receiver.position.z * receiver.position.z);
}

/// The per-path visibility of Alg. 2, 3 and 6 (or none, or alg6_ray): a micro linear buffer,
/// reset for every path, fed with the elevation slot of each sample (both points in the light's
/// eye space).
template <rsm_visibility Visibility, typename T>
struct micro_linear_buffer_visibility {
  const elevation_slots<T>& slots;
  glm::vec<3, T> up{T(0), T(0), T(1)};  ///< alg6_ray: towards the light
  T min_distance = T(0);                ///< alg6_ray: the tangent-plane tolerance's distance
  micro_linear_buffer<T> linear_buffer{};
  void begin_path() { micro_linear_buffer_reset(linear_buffer, slots.count); }
  T operator()(const gather_receiver<T>& receiver, const rsm_texel<T>& light) {
    if constexpr (Visibility == rsm_visibility::none) {
      (void)receiver, (void)light;
      return T(1);
    } else if constexpr (Visibility == rsm_visibility::alg6_ray) {
      if (!alg6_ray_in_front(receiver.position, receiver.normal, light.position, min_distance)) return T(1);  // no claim
      const int index = elevation_bucket_about(receiver.position, light.position, up, slots);
      return glm::clamp(micro_linear_buffer_alg6_ray(linear_buffer, index, receiver.position, light.position, light.normal), T(0), T(1));
    } else {
      const int index = elevation_bucket(receiver.position, light.position, slots);
      if constexpr (Visibility == rsm_visibility::alg2) return micro_linear_buffer_alg2(linear_buffer, index);
      else if constexpr (Visibility == rsm_visibility::alg3) return micro_linear_buffer_alg3(linear_buffer, index);
      else return glm::clamp(micro_linear_buffer_alg6(linear_buffer, index), T(0), T(1));
    }
  }
};

/// Whether a gather_rsm_with Visibility also judges the coverage's coarse lights: a member
/// `T coarse(const gather_receiver<T>&, const coarse_light<T>&)` (voxel_rsm_visibility's).
template <typename Visibility, typename T, typename = void>
struct judges_coarse_lights : std::false_type {};
template <typename Visibility, typename T>
struct judges_coarse_lights<Visibility, T,
                            std::void_t<decltype(std::declval<Visibility&>().coarse(std::declval<const gather_receiver<T>&>(), std::declval<const coarse_light<T>&>()))>>
    : std::true_type {};

/// Whether a gather_rsm_with Visibility judges groups of consecutive samples of a path by one call
/// (rsm_sample_group): a member `int samples_per_march() const` (voxel_rsm_visibility's).
template <typename Visibility, typename = void>
struct groups_samples : std::false_type {};
template <typename Visibility>
struct groups_samples<Visibility, std::void_t<decltype(std::declval<const Visibility&>().samples_per_march())>> : std::true_type {};

/// The micro linear buffer's visibility with the coverage's coarse lights judged by
/// `segment_visible(x, x_c) -> T` (both in the light's eye space): a point light's
/// coarse_light_cube_visibility over its six depth maps (vplkit/rsm_coarse_visibility.hpp).
template <rsm_visibility Visibility, typename T, typename CoarseVisibility>
struct micro_linear_buffer_with_coarse : micro_linear_buffer_visibility<Visibility, T> {
  CoarseVisibility segment_visible;
  T coarse(const gather_receiver<T>& receiver, const coarse_light<T>& light) { return segment_visible(receiver.position, light.position); }
};

}  // namespace detail

/// The coarse-light visibility of a gather that leaves the coverage's coarse lights unoccluded,
/// as the thesis's coverage does (a spot's, a sun's, or a point light's without its six faces).
struct unoccluded_coarse_lights {
  template <typename T>
  T operator()(const glm::vec<3, T>&, const glm::vec<3, T>&) const {
    return T(1);
  }
};

/// Whether gather_rsm with `visibility` judges the coarse lights by a coarse visibility: every
/// visibility but the voxel grid's, which judges them by its own march (GLSL: VPLKIT_VISIBILITY
/// other than 8, with coverage). The coarse lights are vplkit's coverage, not the thesis's pattern
/// (errata RSMV-10, RSMV-14), so their visibility does not depend on which of the thesis's
/// visibilities the pattern's samples get: without it the lit side of a partition lit the floor
/// behind it for rsm-original and rsm-radial too (docs/scenes.md, workshop corner +17.8 %).
constexpr bool judges_coarse_lights_by_segment(rsm_visibility visibility) { return visibility != rsm_visibility::voxel; }

/// The gather with the visibility of each sample supplied by `visibility`, an object with
/// `begin_path()` (called before every path of the radial pattern, once for the disk pattern)
/// and `T operator()(const gather_receiver<T>&, const rsm_texel<T>& light)`,
/// called for every sample that lands on a lit texel, near to far along each path. This is the
/// one sampling loop: gather_rsm below passes the micro linear buffer, the ground truth
/// (gather_with_ray_cast_visibility in frontend/reference/reference.hpp) passes a ray cast to measure the
/// same samples with exact visibility. `coarse_fetch(glm::ivec2 block) -> coarse_light<T>` reads the
/// coarse lights (rsm_coverage.hpp) when settings.coverage_blocks > 0; no_coarse_lights{}: none.
/// A visibility with a member `coarse(receiver, coarse_light)` judges the coarse lights too
/// (voxel_rsm_visibility; gather_rsm's micro_linear_buffer_with_coarse, for every visibility and
/// both patterns, given a coarse visibility); the others (e.g. the ground truth's ray cast) leave
/// them unoccluded, as the thesis's coverage does. A visibility with a member
/// `samples_per_march()` (voxel_rsm_visibility) is called once per group of that many consecutive
/// samples of a path (the last group of a path may be shorter), for the group's largest member
/// (rsm_sample_group), and its answer weighs the whole group: the march is what rsm-voxel's frame
/// pays for (docs/rsm-study.md, "Where the time goes").
/// C++ only: the GLSL twin selects its visibility by define.
template <rsm_pattern Pattern, typename T, typename Fetch, typename CoarseFetch, typename Visibility>
glm::vec<3, T> gather_rsm_with(const gather_receiver<T>& receiver, Fetch&& fetch, CoarseFetch&& coarse_fetch, const rsm_gather_settings<T>& settings,
                               Visibility&& visibility) {
  constexpr bool with_coverage = !std::is_same_v<std::decay_t<CoarseFetch>, no_coarse_lights>;
  constexpr bool grouped = detail::groups_samples<std::decay_t<Visibility>>::value;
  static_assert(!grouped || Pattern == rsm_pattern::radial, "a grouping visibility groups the samples of a path: it needs rsm_pattern::radial");
  glm::vec<3, T> irradiance(0);
  const bool in_front = receiver.position.z < T(0);
  // The pattern's outer radius for this receiver, in texels.
  T reach = settings.disk.max_radius;
  if (in_front) {
    // One sample: fetch, visibility, Eq. 3.2, accumulate (Alg. 1 lines 9-16, Alg. 5 lines 9-15).
    // A grouping visibility: the sample joins its group instead, judged when the group is complete.
    rsm_sample_group<T> group;
    auto accumulate = [&](const pattern_sample<T>& s) {
      const glm::ivec2 texel = glm::ivec2(glm::floor(receiver.rsm_coordinate + s.offset));
      if (texel.x < 0 || texel.y < 0 || texel.x >= settings.rsm_size.x || texel.y >= settings.rsm_size.y) return;
      const rsm_texel<T> light = fetch(texel);
      if (!(light.position.z < T(0))) return;
      if constexpr (grouped) {
        group.add(s.weight * pixel_light_irradiance(receiver.position, receiver.normal, light.position, light.normal, light.flux, settings.irradiance),
                  light);
      } else {
        const T seen = visibility(receiver, light);
        const glm::vec<3, T> e = pixel_light_irradiance(receiver.position, receiver.normal, light.position, light.normal,
                                                        light.flux, settings.irradiance);
        irradiance += (seen * s.weight) * e;
      }
    };
    // How far the projection lies outside the RSM: the pattern runs only when it can land on it.
    const glm::vec<2, T> size(settings.rsm_size);
    const glm::vec<2, T> outside = glm::max(glm::max(-receiver.rsm_coordinate, receiver.rsm_coordinate - size), glm::vec<2, T>(T(0)));
    const T outside_squared = glm::dot(outside, outside);
    if constexpr (Pattern == rsm_pattern::radial) {
      const radial_pixel<T> pixel = radial_pattern_pixel(receiver.pixel, settings.radial);
      reach = pixel.scale * settings.radial.max_radius;
      if (outside_squared <= (reach + T(1)) * (reach + T(1))) {
        int group_size = 1;
        if constexpr (grouped) group_size = glm::max(visibility.samples_per_march(), 1);
        for (int path = 0; path < settings.radial.paths; ++path) {
          visibility.begin_path();
          T ring_inner_radius = settings.radial.min_radius;
          for (int sample_index = 0; sample_index < settings.radial.samples_per_path; ++sample_index) {
            accumulate(radial_pattern_sample(path, sample_index, ring_inner_radius, pixel, settings.radial));
            ring_inner_radius *= settings.radial.ring_ratio;
            if constexpr (grouped) {
              // The group's one call, for its largest member; a group that lights nothing is not judged.
              if ((sample_index + 1) % group_size == 0 || sample_index + 1 == settings.radial.samples_per_path) {
                if (group.best > T(0)) irradiance += visibility(receiver, group.light) * group.sum;
                group = rsm_sample_group<T>{};
              }
            }
          }
        }
      }
    } else {
      if (outside_squared <= (reach + T(1)) * (reach + T(1))) {
        visibility.begin_path();
        const glm::vec<2, T> shift = rsm_disk_pixel_shift(receiver.pixel, settings.disk);
        for (int sample_index = 0; sample_index < settings.disk.samples; ++sample_index) accumulate(rsm_disk_sample(sample_index, shift, settings.disk));
      }
    }
    if (!(outside_squared > T(0))) return irradiance * T(0.318309886183790671538);  // on the map: the pattern alone
  }
  if constexpr (with_coverage) {
    // Behind the light every block; off the map the blocks beyond the pattern's reach; of those,
    // the receiver's lattice of the interleave, weighted by its size.
    const int blocks = settings.coverage_blocks;
    const glm::ivec2 side = coverage_block_side(settings.rsm_size, glm::max(blocks, 1));
    const int stride = glm::max(settings.coverage_interleave, 1);
    const glm::ivec2 phase = coverage_interleave_phase(receiver.pixel, stride);
    glm::vec<3, T> coverage(0);
    for (int y = phase.y; y < blocks; y += stride)
      for (int x = phase.x; x < blocks; x += stride) {
        // Behind the light every block counts: the reach test only for receivers in front, where
        // skipping it for the others saved about 2 % of loft 3's frame (docs/rsm-study.md).
        if (in_front) {
          const glm::vec<2, T> offset = coverage_block_centre<T>(glm::ivec2(x, y), side) - receiver.rsm_coordinate;
          if (!(glm::dot(offset, offset) > reach * reach)) continue;
        }
        const coarse_light<T> light = coarse_fetch(glm::ivec2(x, y));
        if constexpr (detail::judges_coarse_lights<std::decay_t<Visibility>, T>::value) {
          // A coarse light that lights nothing here is not judged: the cube's segment test and the
          // voxel march cost more than Eq. 3.2.
          const glm::vec<3, T> e = coarse_light_irradiance(receiver.position, receiver.normal, light, settings.irradiance);
          if (e.x + e.y + e.z > T(0)) coverage += visibility.coarse(receiver, light) * e;
        } else {
          coverage += coarse_light_irradiance(receiver.position, receiver.normal, light, settings.irradiance);
        }
      }
    irradiance += coverage * T(stride * stride);
  } else {
    (void)coarse_fetch;
  }
  return irradiance * T(0.318309886183790671538);  // 1 / pi
}

/// The same without coverage: the pattern alone.
template <rsm_pattern Pattern, typename T, typename Fetch, typename Visibility>
glm::vec<3, T> gather_rsm_with(const gather_receiver<T>& receiver, Fetch&& fetch, const rsm_gather_settings<T>& settings, Visibility&& visibility) {
  return gather_rsm_with<Pattern>(receiver, fetch, no_coarse_lights{}, settings, visibility);
}

/// The gather: irradiance at the receiver, with coverage when settings.coverage_blocks > 0
/// (`coarse_fetch(glm::ivec2 block) -> coarse_light<T>`, e.g. reduce_rsm_block's results).
/// Visibility needs the radial pattern (its samples lie on paths); the disk pattern has none.
/// The coarse lights are weighted by `coarse_visibility(x, x_c) -> T` (receiver and coarse light in
/// the light's eye space; GLSL: gather.frag's rsm_depth_coarse_visibility), whatever the pattern
/// and the visibility (judges_coarse_lights_by_segment): a point light's
/// coarse_light_cube_visibility, or unoccluded_coarse_lights{}.
template <rsm_pattern Pattern, rsm_visibility Visibility, typename T, typename Fetch, typename CoarseFetch, typename CoarseVisibility>
glm::vec<3, T> gather_rsm(const gather_receiver<T>& receiver, Fetch&& fetch, CoarseFetch&& coarse_fetch, CoarseVisibility&& coarse_visibility,
                          const rsm_gather_settings<T>& settings) {
  static_assert(Pattern == rsm_pattern::radial || Visibility == rsm_visibility::none,
                "the disk pattern has no paths: visibility needs rsm_pattern::radial");
  static_assert(Visibility != rsm_visibility::voxel, "the voxel visibility needs its grid: gather_rsm_with with voxel_rsm_visibility (voxel_visibility.hpp)");
  detail::micro_linear_buffer_visibility<Visibility, T> visibility{settings.slots};
  if constexpr (Visibility == rsm_visibility::alg6_ray) {
    // Behind the light there is no path (the coverage alone): no `up` to compute.
    if (receiver.position.z < T(0)) visibility.up = detail::towards_light(receiver, settings);
    visibility.min_distance = T(settings.irradiance.min_distance);
  }
  static_assert(judges_coarse_lights_by_segment(Visibility));
  detail::micro_linear_buffer_with_coarse<Visibility, T, std::decay_t<CoarseVisibility>> judged{visibility, coarse_visibility};
  return gather_rsm_with<Pattern>(receiver, fetch, coarse_fetch, settings, judged);
}

/// The gather with the coverage's coarse lights unoccluded (unoccluded_coarse_lights).
template <rsm_pattern Pattern, rsm_visibility Visibility, typename T, typename Fetch, typename CoarseFetch>
glm::vec<3, T> gather_rsm(const gather_receiver<T>& receiver, Fetch&& fetch, CoarseFetch&& coarse_fetch, const rsm_gather_settings<T>& settings) {
  return gather_rsm<Pattern, Visibility>(receiver, fetch, coarse_fetch, unoccluded_coarse_lights{}, settings);
}

/// The gather of the pattern alone (no coverage, whatever settings.coverage_blocks says).
template <rsm_pattern Pattern, rsm_visibility Visibility, typename T, typename Fetch>
glm::vec<3, T> gather_rsm(const gather_receiver<T>& receiver, Fetch&& fetch, const rsm_gather_settings<T>& settings) {
  return gather_rsm<Pattern, Visibility>(receiver, fetch, no_coarse_lights{}, settings);
}

}  // namespace vplkit
