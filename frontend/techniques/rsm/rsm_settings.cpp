#include "frontend/techniques/rsm/rsm_settings.hpp"

#include <utility>

#include "frontend/core/error.hpp"
#include "frontend/core/named_table.hpp"

namespace vplkit {

const std::vector<rsm_technique>& rsm_techniques() {
  static const std::vector<rsm_technique> techniques = {
      {"direct", false, rsm_pattern::radial, rsm_visibility::none, "direct light only (shadow density, Alg. 4)"},
      {"rsm-original", true, rsm_pattern::disk, rsm_visibility::none, "original RSM: disk pattern, 400 samples, no visibility"},
      {"rsm-radial", true, rsm_pattern::radial, rsm_visibility::none, "radial pattern, no visibility"},
      {"rsm-alg2", true, rsm_pattern::radial, rsm_visibility::alg2, "radial pattern, micro linear buffer Alg. 2"},
      {"rsm-alg3", true, rsm_pattern::radial, rsm_visibility::alg3, "radial pattern, micro linear buffer Alg. 3"},
      {"rsm-alg6", true, rsm_pattern::radial, rsm_visibility::alg6, "radial pattern, micro linear buffer Alg. 6 (the thesis)"},
      {"rsm-alg6-ray", true, rsm_pattern::radial, rsm_visibility::alg6_ray,
       "radial pattern, Alg. 6 with the elevation about the receiver's light ray and without the samples in its tangent plane (docs/errata.md RSMV-12)"},
      {"rsm-voxel", true, rsm_pattern::radial, rsm_visibility::voxel,
       "radial pattern, each sample's visibility by a 3D DDA through a conservative voxel grid of the scene's triangles (vplkit/voxel_visibility.hpp; "
       "docs/rsm-study.md, \"Beyond one RSM\")"},
  };
  return techniques;
}

const rsm_technique& find_rsm_technique(const std::string& name) { return find_by_name(rsm_techniques(), name, "technique"); }

// The table in groups, each a function, in the table's order (the order of the options, the
// controls and the JSON): the targets, the gather's preset and pattern sizes, the patterns'
// details, the coverage, voxels and history, and the filters. An entry is its field's member
// path: the default is the struct's initialiser, and get and set come from the path.
namespace {

using entry = setting<rsm_pipeline_settings, rsm_technique>;
using S = rsm_pipeline_settings;
// The kernel structs the frame uploads, as it derives them (rsm_pipeline's make_frame_constants):
// the member paths of .feeds() read them.
using G = rsm_gather_settings<float>;
using R = radial_pattern_constants<float>;
using D = disk_pattern_settings<float>;
using E = elevation_slots<float>;
using I = irradiance_settings<float>;
using B = bilateral_settings<float>;
using V = voxel_march_settings<float>;
using RP = radial_pattern_settings<float>;

// Who reads what, by the technique's description.
bool gathers(const rsm_technique& t) { return t.indirect; }
bool radial(const rsm_technique& t) { return t.indirect && t.pattern == rsm_pattern::radial; }
bool disk(const rsm_technique& t) { return t.indirect && t.pattern == rsm_pattern::disk; }
bool with_visibility(const rsm_technique& t) { return t.indirect && t.visibility != rsm_visibility::none && t.visibility != rsm_visibility::voxel; }
bool voxel(const rsm_technique& t) { return t.indirect && t.visibility == rsm_visibility::voxel; }
const char* const gathering = "the techniques that gather indirect light";

G gather(const S& s) { return derive(s).gather; }
I irradiance(const S& s) { return derive(s).gather.irradiance; }
B bilateral(const S& s) { return s.bilateral; }
shadow_density_settings<float> shadow(const S& s) { return s.shadow; }
temporal_settings<float> temporal(const S& s) { return s.temporal; }
V voxel_march(const S& s) { return s.voxel_march; }

std::vector<entry> target_settings() {
  return {
      entry::extent("size", path_of(&S::width), path_of(&S::height), schema::closed_range(1, max_image_side), "pixels", "final image size, N or WxH")
          .builds("the targets")
          .not_live(),
      entry::choice("format", path_of(&S::format), {{"rgba16f", texel_format::rgba16f}, {"rgba32f", texel_format::rgba32f}},
                    "float format of the render targets (the RSM is packed: RGBA32UI)")
          .builds("the targets"),
      entry::number("min-distance", path_of(&S::irradiance, &I::min_distance))
          .feeds("post.frag", "irradiance", irradiance, &I::min_distance)
          .feeds("gather.frag", "settings", gather, &G::irradiance, &I::min_distance),
      entry::number("rsm-size", path_of(&S::rsm_size), schema::closed_range(1, max_image_side), "texels", "square RSM resolution")
          .feeds("rsm.frag: rsm_size; gbuffer.frag: rsm_size")
          .feeds("gather.frag", "settings", gather, &G::rsm_size)
          .builds("the RSM's target"),
      entry::number("indirect-divisor", path_of(&S::indirect_divisor), schema::closed_range(1, 8), "", "indirect buffer = image / this per axis (2: half, 1: full)")
          .allowing({1, 2, 4, 8})
          .read_by(gathers, gathering)
          .feeds("gather.frag: indirect_divisor; blur_x.frag: indirect_divisor; blur_y.frag: indirect_divisor; post.frag: indirect_divisor")
          .defines("post.frag: VPLKIT_QUAD_BLUR")  // divisor 2 with the separable filter: blur_y.frag's quads
          .builds("the indirect buffers"),
  };
}

// The settings a gather preset sets, as their entries' text: the preset is these values.
std::vector<std::pair<std::string, std::string>> preset_values(const rsm_gather_preset<float>& p) {
  return {{"radius", format_real(p.radius_fraction)},
          {"paths", std::to_string(p.paths)},
          {"samples-per-path", std::to_string(p.samples_per_path)},
          {"slots", std::to_string(p.slots)}};
}

const rsm_gather_preset<float>* find_preset(const std::string& name) {
  static const rsm_gather_preset<float> defaults = default_rsm_gather_preset<float>(), thesis = thesis_rsm_gather_preset<float>();
  return name == "thesis" ? &thesis : name == "default" ? &defaults : nullptr;
}

entry preset_setting() {
  const auto describe = [](const rsm_gather_preset<float>& p) {
    return "radius " + format_real(p.radius_fraction) + ", " + std::to_string(p.paths) + " x " + std::to_string(p.samples_per_path) + ", " +
           std::to_string(p.slots) + " slots";
  };
  entry preset = entry::custom(
      "preset", setting_type::choice, "",
      "the gather's radius, paths, samples and slots: default (" + describe(*find_preset("default")) + "; docs/rsm-study.md) or thesis (" +
          describe(*find_preset("thesis")) + "); --radius, --paths, --samples-per-path and --slots override it",
      [](const S& s) {
        // A preset is in effect when each of its settings has its value.
        const auto is = [&s](const char* name) {
          for (const auto& [setting, value] : preset_values(*find_preset(name)))
            if (find_by_name(rsm_settings_table(), setting, "setting").get(s) != value) return false;
          return true;
        };
        return std::string(is("thesis") ? "thesis" : is("default") ? "default" : "custom");
      },
      [](S& s, const std::string& text) {
        for (const auto& [setting, value] : preset_values(*find_preset(text))) find_by_name(rsm_settings_table(), setting, "setting").set(s, value);
      });
  preset.choices = {"default", "thesis"};
  preset.applies_first = true;
  preset.in_effect = false;  // radius, paths, samples and slots are
  preset.live = false;
  preset.read_by(gathers, gathering);
  return preset;
}

std::vector<entry> gather_settings() {
  entry texels = entry::custom(
      "max-radius", setting_type::real, "RSM texels", "the sampling radius in RSM texels (instead of --radius)",
      [](const S& s) { return format_real(rsm_radius_in_texels(s.radius, glm::ivec2(s.rsm_size))); },
      [](S& s, const std::string& text) { s.radius = static_cast<float>(*parse_real(text)) / static_cast<float>(s.rsm_size); });
  texels.range = schema::above(0.0);
  texels.in_effect = false;  // radius is
  texels.excludes = "radius";
  texels.read_by(gathers, gathering);
  return {
      preset_setting(),
      entry::number("radius", path_of(&S::radius), describe_field(&rsm_gather_preset<float>::radius_fraction))
          .read_by(gathers, gathering)
          .feeds("gather.frag", "settings", gather, &G::radial, &R::ring_ratio)
          .feeds("gather.frag", "settings", gather, &G::disk, &D::max_radius),
      texels,
      entry::number("paths", path_of(&S::radial, &RP::paths)).read_by(radial, "the radial pattern").feeds("gather.frag", "settings", gather, &G::radial, &R::paths),
      entry::number("samples-per-path", path_of(&S::radial, &RP::samples_per_path))
          .read_by(radial, "the radial pattern")
          .feeds("gather.frag", "settings", gather, &G::radial, &R::samples_per_path),
      entry::number("slots", path_of(&S::slots), describe_field(&E::count))
          .read_by(with_visibility, "the micro linear buffer")
          .feeds("gather.frag", "settings", gather, &G::slots, &E::count)
          .defines("gather.frag: VPLKIT_SLOT_COUNT"),
  };
}

std::vector<entry> pattern_settings() {
  return {
      entry::number("min-radius", path_of(&S::radial, &RP::min_radius))
          .read_by(radial, "the radial pattern")
          .feeds("gather.frag", "settings", gather, &G::radial, &R::min_radius),
      entry::number("rotation-jitter", path_of(&S::radial, &RP::rotation_jitter))
          .read_by(radial, "the radial pattern")
          .feeds("gather.frag", "settings", gather, &G::radial, &R::rotation_jitter),
      entry::number("angle-jitter", path_of(&S::radial, &RP::angle_jitter))
          .read_by(radial, "the radial pattern")
          .feeds("gather.frag", "settings", gather, &G::radial, &R::angle_jitter),
      entry::number("scale-jitter", path_of(&S::radial, &RP::scale_jitter))
          .read_by(radial, "the radial pattern")
          .feeds("gather.frag", "settings", gather, &G::radial, &R::scale_jitter),
      entry::number("disk-samples", path_of(&S::disk, &D::samples)).read_by(disk, "the original RSM's disk").feeds("gather.frag", "settings", gather, &G::disk, &D::samples),
      entry::choice("disk-weights", path_of(&S::disk, &D::printed_weights), {{"unbiased", false}, {"printed", true}},
                    "original RSM: unbiased (xi, the inverse of the samples' density) or printed (the original's xi^2, biased low; "
                    "docs/errata.md RSMV-9)")
          .read_by(disk, "the original RSM's disk")
          .feeds("gather.frag", "settings", gather, &G::disk, &D::printed_weights),
      entry::choice("disk-pattern", path_of(&S::disk, &D::per_pixel_shift), {{"per-pixel", true}, {"fixed", false}},
                    "original RSM: per-pixel (each pixel shifts the samples, so the receivers' errors are independent and average out) "
                    "or fixed (the original's: the same samples for every pixel of a frame, one error across the image; docs/errata.md RSMV-9)")
          .read_by(disk, "the original RSM's disk")
          .feeds("gather.frag", "settings", gather, &G::disk, &D::per_pixel_shift),
  };
}

std::vector<entry> coverage_voxel_history_settings() {
  return {
      entry::number("coverage-blocks", path_of(&S::coverage_blocks), describe_field(&G::coverage_blocks))
          .read_by(gathers, gathering)
          .feeds("gather.frag", "settings", gather, &G::coverage_blocks)
          .feeds("rsm_coarse.frag: coverage_blocks")
          .defines("gather.frag: VPLKIT_RSM_COVERAGE")
          .builds("the coarse lights' targets"),
      entry::number("coverage-interleave", path_of(&S::coverage_interleave), describe_field(&G::coverage_interleave))
          .read_by(gathers, gathering)
          .feeds("gather.frag", "settings", gather, &G::coverage_interleave),
      entry::number("voxel-resolution", path_of(&S::voxel_grid, &voxel_grid_settings<float>::resolution))
          .read_by(voxel, "rsm-voxel")
          .not_live()
          .feeds("gather.frag: voxel_shape; gather.frag: voxel_packed")
          .builds("the voxel grid"),
      entry::number("voxel-memory", path_of(&S::voxel_grid, &voxel_grid_settings<float>::max_megabytes))
          .read_by(voxel, "rsm-voxel")
          .not_live()
          .feeds("gather.frag: voxel_shape; gather.frag: voxel_packed")
          .builds("the voxel grid"),
      entry::number("voxel-start-offset", path_of(&S::voxel_march, &V::start_offset))
          .read_by(voxel, "rsm-voxel")
          .feeds("gather.frag", "voxel_march", voxel_march, &V::start_offset),
      entry::number("voxel-end-offset", path_of(&S::voxel_march, &V::end_offset))
          .read_by(voxel, "rsm-voxel")
          .feeds("gather.frag", "voxel_march", voxel_march, &V::end_offset),
      entry::number("voxel-group", path_of(&S::voxel_march, &V::group))
          .read_by(voxel, "rsm-voxel")
          .feeds("gather.frag", "voxel_march", voxel_march, &V::group),
      // Below 1 the frames blend with a history: the temporal program and the history targets.
      entry::number("temporal-blend", path_of(&S::temporal, &temporal_settings<float>::blend))
          .read_by(gathers, gathering)
          .not_live()
          .feeds("temporal.frag", "temporal", temporal, &temporal_settings<float>::blend)
          .builds("the temporal pass and its history", [](const S& s) { return std::string(s.temporal.blend < 1.0f ? "history" : "none"); }),
      entry::number("seed", path_of(&S::radial, &RP::seed), describe_field(&RP::seed).range, "", "seed of the sampling patterns")
          .sets_also(path_of(&S::disk, &D::seed))
          .read_by(gathers, gathering)
          .feeds("gather.frag", "settings", gather, &G::radial, &R::seed)
          .feeds("gather.frag", "settings", gather, &G::disk, &D::seed),
  };
}

std::vector<entry> filter_settings() {
  using K = shadow_density_settings<float>;
  return {
      entry::choice("post-filter", path_of(&S::filter), {{"separable", post_filter::separable}, {"full", post_filter::full}},
                    "bilateral post filter of the indirect light: separable (2 x 17 taps) or the full 2D kernel")
          .read_by(gathers, gathering)
          .defines("post.frag: VPLKIT_SEPARABLE")
          .defines("post.frag: VPLKIT_QUAD_BLUR"),
      entry::number("filter-kernel-size", path_of(&S::bilateral, &B::kernel_size))
          .read_by(gathers, gathering)
          .feeds("blur_x.frag", "bilateral", bilateral, &B::kernel_size)
          .feeds("blur_y.frag", "bilateral", bilateral, &B::kernel_size)
          .feeds("post.frag", "bilateral", bilateral, &B::kernel_size),
      entry::number("filter-spatial-sigma", path_of(&S::bilateral, &B::spatial_sigma))
          .read_by(gathers, gathering)
          .feeds("blur_x.frag", "bilateral", bilateral, &B::spatial_sigma)
          .feeds("blur_y.frag", "bilateral", bilateral, &B::spatial_sigma)
          .feeds("post.frag", "bilateral", bilateral, &B::spatial_sigma),
      entry::number("filter-depth-sigma", path_of(&S::bilateral, &B::depth_sigma))
          .read_by(gathers, gathering)
          .feeds("blur_x.frag", "bilateral", bilateral, &B::depth_sigma)
          .feeds("blur_y.frag", "bilateral", bilateral, &B::depth_sigma)
          .feeds("post.frag", "bilateral", bilateral, &B::depth_sigma),
      entry::number("filter-normal-power", path_of(&S::bilateral, &B::normal_power))
          .read_by(gathers, gathering)
          .feeds("blur_x.frag", "bilateral", bilateral, &B::normal_power)
          .feeds("blur_y.frag", "bilateral", bilateral, &B::normal_power)
          .feeds("post.frag", "bilateral", bilateral, &B::normal_power),
      entry::number("shadow-kernel-size", path_of(&S::shadow, &K::kernel_size)).feeds("gbuffer.frag", "shadow", shadow, &K::kernel_size),
      entry::number("shadow-depth-bias", path_of(&S::shadow, &K::depth_bias)).feeds("gbuffer.frag", "shadow", shadow, &K::depth_bias),
  };
}

}  // namespace

const std::vector<setting<rsm_pipeline_settings, rsm_technique>>& rsm_settings_table() {
  static const std::vector<entry> table = [] {
    std::vector<entry> all;
    for (std::vector<entry> group : {target_settings(), gather_settings(), pattern_settings(), coverage_voxel_history_settings(), filter_settings()})
      for (entry& one : group) all.push_back(std::move(one));
    return all;
  }();
  return table;
}

rsm_derived_settings derive(const rsm_pipeline_settings& settings) {
  rsm_derived_settings derived;
  derived.gather = make_rsm_gather_settings(settings.radial, settings.disk, settings.radius, settings.slots, glm::ivec2(settings.rsm_size));
  derived.gather.irradiance = settings.irradiance;
  derived.gather.coverage_blocks = settings.coverage_blocks;
  derived.gather.coverage_interleave = settings.coverage_interleave;
  // The radial pattern's settings with the radius the gather has (its constants replace them).
  derived.radial = settings.radial;
  derived.radial.max_radius = derived.gather.disk.max_radius;
  return derived;
}

std::string validate(const rsm_pipeline_settings& settings) {
  try {
    find_rsm_technique(settings.technique);
  } catch (const error& failure) {
    return failure.what();
  }
  if (const std::string problem = check_settings(rsm_settings_table(), settings); !problem.empty()) return problem;
  const rsm_derived_settings derived = derive(settings);
  for (const setting_problem& problem : {validate(derived.radial), validate(derived.gather.disk), validate(settings.irradiance), validate(settings.shadow), validate(settings.bilateral),
                                         validate(settings.temporal), validate(settings.voxel_grid), validate(settings.voxel_march)})
    if (problem) return problem.message();
  if (const char* problem = validate_coverage_blocks(settings.coverage_blocks)) return problem;
  if (const char* problem = validate_coverage_interleave(settings.coverage_interleave)) return problem;
  // The interleave's lattices are averaged back by the post filter: it must span a tile (2s + 1
  // taps), and a lattice must hold a block.
  const int side = settings.coverage_interleave;
  if (!coverage_lattice_holds_a_block(settings.coverage_blocks, side))
    return "coverage-interleave " + std::to_string(side) + " exceeds coverage-blocks " + std::to_string(settings.coverage_blocks) +
           ": a receiver's lattice would hold no block";
  if (side > 1 && settings.coverage_blocks > 0 && settings.bilateral.kernel_size < 2 * side + 1)
    return "coverage-interleave " + std::to_string(side) + " needs a post filter of at least " + std::to_string(2 * side + 1) +
           " taps to average its tiles (filter-kernel-size is " + std::to_string(settings.bilateral.kernel_size) + "; or coverage-interleave 1)";
  return {};
}

}  // namespace vplkit
