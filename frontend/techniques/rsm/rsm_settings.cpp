#include "frontend/techniques/rsm/rsm_settings.hpp"

#include <tuple>

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

const std::vector<setting<rsm_pipeline_settings, rsm_technique>>& rsm_settings_table() {
  using entry = setting<rsm_pipeline_settings, rsm_technique>;
  const auto gathers = [](const rsm_technique& t) { return t.indirect; };
  const auto radial = [](const rsm_technique& t) { return t.indirect && t.pattern == rsm_pattern::radial; };
  const auto disk = [](const rsm_technique& t) { return t.indirect && t.pattern == rsm_pattern::disk; };
  const auto with_visibility = [](const rsm_technique& t) {
    return t.indirect && t.visibility != rsm_visibility::none && t.visibility != rsm_visibility::voxel;
  };
  const auto voxel = [](const rsm_technique& t) { return t.indirect && t.visibility == rsm_visibility::voxel; };
  const std::string gathering = "the techniques that gather indirect light";
  const rsm_gather_preset<float> defaults = default_rsm_gather_preset<float>(), thesis = thesis_rsm_gather_preset<float>();
  const auto preset_text = [](const rsm_gather_preset<float>& p) {
    return "radius " + format_real(p.radius_fraction) + ", " + std::to_string(p.paths) + " x " + std::to_string(p.samples_per_path) + ", " +
           std::to_string(p.slots) + " slots";
  };
  // The kernel structs the frame uploads, as it derives them (rsm_pipeline's make_frame_constants):
  // the member paths of .feeds() read them.
  using G = rsm_gather_settings<float>;
  using R = radial_pattern_constants<float>;
  using D = disk_pattern_settings<float>;
  using E = elevation_slots<float>;
  using I = irradiance_settings<float>;
  using B = bilateral_settings<float>;
  const auto gather = [](const rsm_pipeline_settings& s) { return derive(s).gather; };
  const auto irradiance = [](const rsm_pipeline_settings& s) { return derive(s).gather.irradiance; };
  const auto bilateral = [](const rsm_pipeline_settings& s) { return s.bilateral; };
  const auto shadow = [](const rsm_pipeline_settings& s) { return s.shadow; };
  const auto temporal = [](const rsm_pipeline_settings& s) { return s.temporal; };
  const auto voxel_march = [](const rsm_pipeline_settings& s) { return s.voxel_march; };
  using V = voxel_march_settings<float>;
  static const std::vector<entry> table = {
      entry::custom("size", setting_type::size, "pixels", "final image size, N or WxH",
                    [](const rsm_pipeline_settings& s) { return s.width == s.height ? std::to_string(s.width) : std::to_string(s.width) + "x" + std::to_string(s.height); },
                    [](rsm_pipeline_settings& s, const std::string& text) { std::tie(s.width, s.height) = *parse_extent(text); })
          .within(schema::closed_range(1, max_image_side))
          .not_live(),
      entry::choice("format", [](auto& s) -> auto& { return s.format; }, {{"rgba16f", texel_format::rgba16f}, {"rgba32f", texel_format::rgba32f}},
                    "float format of the render targets (the RSM is packed: RGBA32UI)"),
      entry::number("min-distance", [](auto& s) -> auto& { return s.irradiance.min_distance; }, describe_field(&irradiance_settings<float>::min_distance))
          .feeds("post.frag", "irradiance", irradiance, &I::min_distance)
          .feeds("gather.frag", "settings", gather, &G::irradiance, &I::min_distance),
      entry::number("rsm-size", [](auto& s) -> auto& { return s.rsm_size; }, schema::closed_range(1, max_image_side), "texels", "square RSM resolution")
          .feeds("rsm.frag: rsm_size; gbuffer.frag: rsm_size")
          .feeds("gather.frag", "settings", gather, &G::rsm_size),
      entry::number("indirect-divisor", [](auto& s) -> auto& { return s.indirect_divisor; }, schema::closed_range(1, 8), "",
                    "indirect buffer = image / this per axis (2: half, 1: full)")
          .allowing({1, 2, 4, 8})
          .read_by(gathers, gathering)
          .feeds("gather.frag: indirect_divisor; blur_x.frag: indirect_divisor; post.frag: indirect_divisor"),
      [&] {
        entry preset = entry::custom(
            "preset", setting_type::choice, "",
            "the gather's radius, paths, samples and slots: default (" + preset_text(defaults) + "; docs/rsm-study.md) or thesis (" + preset_text(thesis) +
                "); --radius, --paths, --samples-per-path and --slots override it",
            [](const rsm_pipeline_settings& s) {
              // A preset is in effect when applying it changes no setting in effect: apply() is
              // the one place that says which fields a preset sets.
              const auto is = [&s](const rsm_gather_preset<float>& p) {
                rsm_pipeline_settings applied = s;
                applied.apply(p);
                for (const setting<rsm_pipeline_settings, rsm_technique>& other : rsm_settings_table())
                  if (other.in_effect && other.get(applied) != other.get(s)) return false;
                return true;
              };
              return std::string(is(thesis_rsm_gather_preset<float>()) ? "thesis" : is(default_rsm_gather_preset<float>()) ? "default" : "custom");
            },
            [](rsm_pipeline_settings& s, const std::string& text) {
              s.apply(text == "thesis" ? thesis_rsm_gather_preset<float>() : default_rsm_gather_preset<float>());
            });
        preset.choices = {"default", "thesis"};
        preset.applies_first = true;
        preset.in_effect = false;  // radius, paths, samples and slots are
        preset.live = false;
        preset.read_by(gathers, gathering);
        return preset;
      }(),
      entry::number("radius", [](auto& s) -> auto& { return s.radius; }, describe_field(&rsm_gather_preset<float>::radius_fraction))
          .read_by(gathers, gathering)
          .feeds("gather.frag", "settings", gather, &G::radial, &R::ring_ratio)
          .feeds("gather.frag", "settings", gather, &G::disk, &D::max_radius),
      [&] {
        entry texels = entry::custom(
            "max-radius", setting_type::real, "RSM texels", "the sampling radius in RSM texels (instead of --radius)",
            [](const rsm_pipeline_settings& s) { return format_real(rsm_radius_in_texels(s.radius, glm::ivec2(s.rsm_size))); },
            [](rsm_pipeline_settings& s, const std::string& text) { s.radius = static_cast<float>(*parse_real(text)) / static_cast<float>(s.rsm_size); });
        texels.range = schema::above(0.0);
        texels.in_effect = false;  // radius is
        texels.excludes = "radius";
        texels.read_by(gathers, gathering);
        return texels;
      }(),
      entry::number("paths", [](auto& s) -> auto& { return s.radial.paths; }, describe_field(&radial_pattern_settings<float>::paths))
          .read_by(radial, "the radial pattern")
          .feeds("gather.frag", "settings", gather, &G::radial, &R::paths),
      entry::number("samples-per-path", [](auto& s) -> auto& { return s.radial.samples_per_path; },
                    describe_field(&radial_pattern_settings<float>::samples_per_path))
          .read_by(radial, "the radial pattern")
          .feeds("gather.frag", "settings", gather, &G::radial, &R::samples_per_path),
      entry::number("slots", [](auto& s) -> auto& { return s.slots; }, describe_field(&elevation_slots<float>::count))
          .read_by(with_visibility, "the micro linear buffer")
          .feeds("gather.frag", "settings", gather, &G::slots, &E::count)
          .feeds("gather.frag: VPLKIT_SLOT_COUNT"),
      entry::number("min-radius", [](auto& s) -> auto& { return s.radial.min_radius; }, describe_field(&radial_pattern_settings<float>::min_radius))
          .read_by(radial, "the radial pattern")
          .feeds("gather.frag", "settings", gather, &G::radial, &R::min_radius),
      entry::number("rotation-jitter", [](auto& s) -> auto& { return s.radial.rotation_jitter; },
                    describe_field(&radial_pattern_settings<float>::rotation_jitter))
          .read_by(radial, "the radial pattern")
          .feeds("gather.frag", "settings", gather, &G::radial, &R::rotation_jitter),
      entry::number("angle-jitter", [](auto& s) -> auto& { return s.radial.angle_jitter; }, describe_field(&radial_pattern_settings<float>::angle_jitter))
          .read_by(radial, "the radial pattern")
          .feeds("gather.frag", "settings", gather, &G::radial, &R::angle_jitter),
      entry::number("scale-jitter", [](auto& s) -> auto& { return s.radial.scale_jitter; }, describe_field(&radial_pattern_settings<float>::scale_jitter))
          .read_by(radial, "the radial pattern")
          .feeds("gather.frag", "settings", gather, &G::radial, &R::scale_jitter),
      entry::number("disk-samples", [](auto& s) -> auto& { return s.disk.samples; }, describe_field(&disk_pattern_settings<float>::samples))
          .read_by(disk, "the original RSM's disk")
          .feeds("gather.frag", "settings", gather, &G::disk, &D::samples),
      entry::choice("disk-weights", [](auto& s) -> auto& { return s.disk.printed_weights; }, {{"unbiased", false}, {"printed", true}},
                    "original RSM: unbiased (xi, the inverse of the samples' density) or printed (the original's xi^2, biased low; "
                    "docs/errata.md RSMV-9)")
          .read_by(disk, "the original RSM's disk")
          .feeds("gather.frag", "settings", gather, &G::disk, &D::printed_weights),
      entry::choice("disk-pattern", [](auto& s) -> auto& { return s.disk.per_pixel_shift; }, {{"per-pixel", true}, {"fixed", false}},
                    "original RSM: per-pixel (each pixel shifts the samples, so the receivers' errors are independent and average out) "
                    "or fixed (the original's: the same samples for every pixel of a frame, one error across the image; docs/errata.md RSMV-9)")
          .read_by(disk, "the original RSM's disk")
          .feeds("gather.frag", "settings", gather, &G::disk, &D::per_pixel_shift),
      entry::number("coverage-blocks", [](auto& s) -> auto& { return s.coverage_blocks; },
                    describe_field(&rsm_gather_settings<float>::coverage_blocks))
          .read_by(gathers, gathering)
          .feeds("gather.frag", "settings", gather, &G::coverage_blocks)
          .feeds("rsm_coarse.frag: coverage_blocks"),
      entry::number("coverage-interleave", [](auto& s) -> auto& { return s.coverage_interleave; },
                    describe_field(&rsm_gather_settings<float>::coverage_interleave))
          .read_by(gathers, gathering)
          .feeds("gather.frag", "settings", gather, &G::coverage_interleave),
      entry::number("voxel-resolution", [](auto& s) -> auto& { return s.voxel_grid.resolution; }, describe_field(&voxel_grid_settings<float>::resolution))
          .read_by(voxel, "rsm-voxel")
          .not_live()
          .feeds("gather.frag: voxel_shape; gather.frag: voxel_packed"),
      entry::number("voxel-memory", [](auto& s) -> auto& { return s.voxel_grid.max_megabytes; }, describe_field(&voxel_grid_settings<float>::max_megabytes))
          .read_by(voxel, "rsm-voxel")
          .not_live()
          .feeds("gather.frag: voxel_shape; gather.frag: voxel_packed"),
      entry::number("voxel-start-offset", [](auto& s) -> auto& { return s.voxel_march.start_offset; }, describe_field(&V::start_offset))
          .read_by(voxel, "rsm-voxel")
          .feeds("gather.frag", "voxel_march", voxel_march, &V::start_offset),
      entry::number("voxel-end-offset", [](auto& s) -> auto& { return s.voxel_march.end_offset; }, describe_field(&V::end_offset))
          .read_by(voxel, "rsm-voxel")
          .feeds("gather.frag", "voxel_march", voxel_march, &V::end_offset),
      entry::number("temporal-blend", [](auto& s) -> auto& { return s.temporal.blend; }, describe_field(&temporal_settings<float>::blend))
          .read_by(gathers, gathering)
          .not_live()
          .feeds("temporal.frag", "temporal", temporal, &temporal_settings<float>::blend),
      entry::custom("seed", setting_type::integer, "", "seed of the sampling patterns",
                    [](const rsm_pipeline_settings& s) { return std::to_string(s.radial.seed); },
                    [](rsm_pipeline_settings& s, const std::string& text) { s.radial.seed = s.disk.seed = static_cast<std::uint32_t>(*parse_integer(text)); })
          .within(describe_field(&radial_pattern_settings<float>::seed).range)
          .read_by(gathers, gathering)
          .feeds("gather.frag", "settings", gather, &G::radial, &R::seed)
          .feeds("gather.frag", "settings", gather, &G::disk, &D::seed),
      entry::choice("post-filter", [](auto& s) -> auto& { return s.filter; }, {{"separable", post_filter::separable}, {"full", post_filter::full}},
                    "bilateral post filter of the indirect light: separable (2 x 17 taps) or the full 2D kernel")
          .read_by(gathers, gathering)
          .feeds("post.frag: VPLKIT_SEPARABLE"),
      entry::number("filter-kernel-size", [](auto& s) -> auto& { return s.bilateral.kernel_size; }, describe_field(&bilateral_settings<float>::kernel_size))
          .read_by(gathers, gathering)
          .feeds("blur_x.frag", "bilateral", bilateral, &B::kernel_size)
          .feeds("post.frag", "bilateral", bilateral, &B::kernel_size),
      entry::number("filter-spatial-sigma", [](auto& s) -> auto& { return s.bilateral.spatial_sigma; },
                    describe_field(&bilateral_settings<float>::spatial_sigma))
          .read_by(gathers, gathering)
          .feeds("blur_x.frag", "bilateral", bilateral, &B::spatial_sigma)
          .feeds("post.frag", "bilateral", bilateral, &B::spatial_sigma),
      entry::number("filter-depth-sigma", [](auto& s) -> auto& { return s.bilateral.depth_sigma; }, describe_field(&bilateral_settings<float>::depth_sigma))
          .read_by(gathers, gathering)
          .feeds("blur_x.frag", "bilateral", bilateral, &B::depth_sigma)
          .feeds("post.frag", "bilateral", bilateral, &B::depth_sigma),
      entry::number("filter-normal-power", [](auto& s) -> auto& { return s.bilateral.normal_power; },
                    describe_field(&bilateral_settings<float>::normal_power))
          .read_by(gathers, gathering)
          .feeds("blur_x.frag", "bilateral", bilateral, &B::normal_power)
          .feeds("post.frag", "bilateral", bilateral, &B::normal_power),
      entry::number("shadow-kernel-size", [](auto& s) -> auto& { return s.shadow.kernel_size; }, describe_field(&shadow_density_settings<float>::kernel_size))
          .feeds("gbuffer.frag", "shadow", shadow, &shadow_density_settings<float>::kernel_size),
      entry::number("shadow-depth-bias", [](auto& s) -> auto& { return s.shadow.depth_bias; }, describe_field(&shadow_density_settings<float>::depth_bias))
          .feeds("gbuffer.frag", "shadow", shadow, &shadow_density_settings<float>::depth_bias),
  };
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
