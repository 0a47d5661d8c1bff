#include "frontend/techniques/rsm/rsm_pipeline.hpp"

#include <algorithm>
#include <chrono>
#include <tuple>
#include <cmath>
#include <cstring>

#include <glm/gtc/matrix_transform.hpp>

#include <vplkit/hash.hpp>
#include <vplkit/gl/settings_uniforms.hpp>

#include "frontend/gl/debug_output.hpp"
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
  };
  return techniques;
}

const rsm_technique& find_rsm_technique(const std::string& name) { return find_by_name(rsm_techniques(), name, "technique"); }

const std::vector<setting<rsm_pipeline_settings, rsm_technique>>& rsm_settings_table() {
  using entry = setting<rsm_pipeline_settings, rsm_technique>;
  const auto gathers = [](const rsm_technique& t) { return t.indirect; };
  const auto radial = [](const rsm_technique& t) { return t.indirect && t.pattern == rsm_pattern::radial; };
  const auto disk = [](const rsm_technique& t) { return t.indirect && t.pattern == rsm_pattern::disk; };
  const auto with_visibility = [](const rsm_technique& t) { return t.indirect && t.visibility != rsm_visibility::none; };
  const std::string gathering = "the techniques that gather indirect light";
  const rsm_gather_preset<float> defaults = default_rsm_gather_preset<float>(), thesis = thesis_rsm_gather_preset<float>();
  const auto preset_text = [](const rsm_gather_preset<float>& p) {
    return "radius " + format_real(p.radius_fraction) + ", " + std::to_string(p.paths) + " x " + std::to_string(p.samples_per_path) + ", " +
           std::to_string(p.slots) + " slots";
  };
  static const std::vector<entry> table = {
      entry::custom("size", setting_type::size, "pixels", "final image size, N or WxH",
                    [](const rsm_pipeline_settings& s) { return s.width == s.height ? std::to_string(s.width) : std::to_string(s.width) + "x" + std::to_string(s.height); },
                    [](rsm_pipeline_settings& s, const std::string& text) { std::tie(s.width, s.height) = *parse_extent(text); })
          .within(closed_range(1, max_image_side))
          .not_live(),
      entry::choice("format", [](auto& s) -> auto& { return s.format; }, {{"rgba16f", texel_format::rgba16f}, {"rgba32f", texel_format::rgba32f}},
                    "float format of the render targets (the RSM is packed: RGBA32UI)"),
      entry::number("min-distance", [](auto& s) -> auto& { return s.irradiance.min_distance; }, describe_field(&irradiance_settings<float>::min_distance))
          .feeds("post.frag: irradiance.min_distance; gather.frag: settings.irradiance.min_distance"),
      entry::number("rsm-size", [](auto& s) -> auto& { return s.rsm_size; }, closed_range(1, max_image_side), "texels", "square RSM resolution")
          .feeds("rsm.frag: rsm_size; gbuffer.frag: rsm_size; gather.frag: settings.rsm_size"),
      entry::number("indirect-divisor", [](auto& s) -> auto& { return s.indirect_divisor; }, closed_range(1, 8), "",
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
              const auto is = [&s](const rsm_gather_preset<float>& p) {
                return s.radius == p.radius_fraction && s.radial.paths == p.paths && s.radial.samples_per_path == p.samples_per_path && s.slots == p.slots;
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
          .feeds("gather.frag: settings.radial.ring_ratio; gather.frag: settings.disk.max_radius"),
      [&] {
        entry texels = entry::custom(
            "max-radius", setting_type::real, "RSM texels", "the sampling radius in RSM texels (instead of --radius)",
            [](const rsm_pipeline_settings& s) { return format_real(s.radius * static_cast<float>(s.rsm_size)); },
            [](rsm_pipeline_settings& s, const std::string& text) { s.radius = static_cast<float>(*parse_real(text)) / static_cast<float>(s.rsm_size); });
        texels.range = above(0.0);
        texels.in_effect = false;  // radius is
        texels.excludes = "radius";
        texels.read_by(gathers, gathering);
        return texels;
      }(),
      entry::number("paths", [](auto& s) -> auto& { return s.radial.paths; }, describe_field(&radial_pattern_settings<float>::paths))
          .read_by(radial, "the radial pattern")
          .feeds("gather.frag: settings.radial.paths"),
      entry::number("samples-per-path", [](auto& s) -> auto& { return s.radial.samples_per_path; },
                    describe_field(&radial_pattern_settings<float>::samples_per_path))
          .read_by(radial, "the radial pattern")
          .feeds("gather.frag: settings.radial.samples_per_path"),
      entry::number("slots", [](auto& s) -> auto& { return s.slots; }, describe_field(&elevation_slots<float>::count))
          .read_by(with_visibility, "the micro linear buffer")
          .feeds("gather.frag: settings.slots.count; gather.frag: VPLKIT_SLOT_COUNT"),
      entry::number("min-radius", [](auto& s) -> auto& { return s.radial.min_radius; }, describe_field(&radial_pattern_settings<float>::min_radius))
          .read_by(radial, "the radial pattern")
          .feeds("gather.frag: settings.radial.min_radius"),
      entry::number("rotation-jitter", [](auto& s) -> auto& { return s.radial.rotation_jitter; },
                    describe_field(&radial_pattern_settings<float>::rotation_jitter))
          .read_by(radial, "the radial pattern")
          .feeds("gather.frag: settings.radial.rotation_jitter"),
      entry::number("angle-jitter", [](auto& s) -> auto& { return s.radial.angle_jitter; }, describe_field(&radial_pattern_settings<float>::angle_jitter))
          .read_by(radial, "the radial pattern")
          .feeds("gather.frag: settings.radial.angle_jitter"),
      entry::number("scale-jitter", [](auto& s) -> auto& { return s.radial.scale_jitter; }, describe_field(&radial_pattern_settings<float>::scale_jitter))
          .read_by(radial, "the radial pattern")
          .feeds("gather.frag: settings.radial.scale_jitter"),
      entry::number("disk-samples", [](auto& s) -> auto& { return s.disk.samples; }, describe_field(&disk_pattern_settings<float>::samples))
          .read_by(disk, "the original RSM's disk")
          .feeds("gather.frag: settings.disk.samples"),
      entry::choice("disk-weights", [](auto& s) -> auto& { return s.disk.printed_weights; }, {{"unbiased", false}, {"printed", true}},
                    "original RSM: unbiased (xi, the inverse of the samples' density) or printed (the original's xi^2, biased low; "
                    "docs/errata.md RSMV-9)")
          .read_by(disk, "the original RSM's disk")
          .feeds("gather.frag: settings.disk.printed_weights"),
      entry::choice("disk-pattern", [](auto& s) -> auto& { return s.disk.per_pixel_shift; }, {{"per-pixel", true}, {"fixed", false}},
                    "original RSM: per-pixel (each pixel shifts the samples, so the receivers' errors are independent and average out) "
                    "or fixed (the original's: the same samples for every pixel of a frame, one error across the image; docs/errata.md RSMV-9)")
          .read_by(disk, "the original RSM's disk")
          .feeds("gather.frag: settings.disk.per_pixel_shift"),
      entry::number("coverage-blocks", [](auto& s) -> auto& { return s.coverage_blocks; },
                    describe_field(&rsm_gather_settings<float>::coverage_blocks))
          .read_by(gathers, gathering)
          .feeds("gather.frag: settings.coverage_blocks; rsm_coarse.frag: coverage_blocks"),
      entry::number("coverage-interleave", [](auto& s) -> auto& { return s.coverage_interleave; },
                    describe_field(&rsm_gather_settings<float>::coverage_interleave))
          .read_by(gathers, gathering)
          .feeds("gather.frag: settings.coverage_interleave"),
      entry::number("temporal-blend", [](auto& s) -> auto& { return s.temporal.blend; }, describe_field(&temporal_settings<float>::blend))
          .read_by(gathers, gathering)
          .not_live()
          .feeds("temporal.frag: temporal.blend"),
      entry::custom("seed", setting_type::integer, "", "seed of the sampling patterns",
                    [](const rsm_pipeline_settings& s) { return std::to_string(s.radial.seed); },
                    [](rsm_pipeline_settings& s, const std::string& text) { s.radial.seed = s.disk.seed = static_cast<std::uint32_t>(*parse_integer(text)); })
          .within(describe_field(&radial_pattern_settings<float>::seed).range)
          .read_by(gathers, gathering)
          .feeds("gather.frag: settings.radial.seed; gather.frag: settings.disk.seed"),
      entry::choice("post-filter", [](auto& s) -> auto& { return s.filter; }, {{"separable", post_filter::separable}, {"full", post_filter::full}},
                    "bilateral post filter of the indirect light: separable (2 x 17 taps) or the full 2D kernel")
          .read_by(gathers, gathering)
          .feeds("post.frag: VPLKIT_SEPARABLE"),
      entry::number("filter-kernel-size", [](auto& s) -> auto& { return s.bilateral.kernel_size; }, describe_field(&bilateral_settings<float>::kernel_size))
          .read_by(gathers, gathering)
          .feeds("blur_x.frag: bilateral.kernel_size; post.frag: bilateral.kernel_size"),
      entry::number("filter-spatial-sigma", [](auto& s) -> auto& { return s.bilateral.spatial_sigma; },
                    describe_field(&bilateral_settings<float>::spatial_sigma))
          .read_by(gathers, gathering)
          .feeds("blur_x.frag: bilateral.spatial_sigma; post.frag: bilateral.spatial_sigma"),
      entry::number("filter-depth-sigma", [](auto& s) -> auto& { return s.bilateral.depth_sigma; }, describe_field(&bilateral_settings<float>::depth_sigma))
          .read_by(gathers, gathering)
          .feeds("blur_x.frag: bilateral.depth_sigma; post.frag: bilateral.depth_sigma"),
      entry::number("filter-normal-power", [](auto& s) -> auto& { return s.bilateral.normal_power; },
                    describe_field(&bilateral_settings<float>::normal_power))
          .read_by(gathers, gathering)
          .feeds("blur_x.frag: bilateral.normal_power; post.frag: bilateral.normal_power"),
      entry::number("shadow-kernel-size", [](auto& s) -> auto& { return s.shadow.kernel_size; }, describe_field(&shadow_density_settings<float>::kernel_size))
          .feeds("gbuffer.frag: shadow.kernel_size"),
      entry::number("shadow-depth-bias", [](auto& s) -> auto& { return s.shadow.depth_bias; }, describe_field(&shadow_density_settings<float>::depth_bias))
          .feeds("gbuffer.frag: shadow.depth_bias"),
  };
  return table;
}

namespace {

// The patterns with their radius in texels, as make_rsm_gather_settings sets it, for validation.
std::pair<radial_pattern_settings<float>, disk_pattern_settings<float>> patterns_in_texels(const rsm_pipeline_settings& settings) {
  std::pair<radial_pattern_settings<float>, disk_pattern_settings<float>> patterns{settings.radial, settings.disk};
  patterns.first.max_radius = patterns.second.max_radius = rsm_radius_in_texels(settings.radius, glm::ivec2(settings.rsm_size));
  return patterns;
}

}  // namespace

std::string validate(const rsm_pipeline_settings& settings) {
  try {
    find_rsm_technique(settings.technique);
  } catch (const error& failure) {
    return failure.what();
  }
  if (const std::string problem = check_settings(rsm_settings_table(), settings); !problem.empty()) return problem;
  const auto [radial, disk] = patterns_in_texels(settings);
  for (const setting_problem& problem : {validate(radial), validate(disk), validate(settings.irradiance), validate(settings.shadow), validate(settings.bilateral),
                                         validate(settings.temporal)})
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

light_frustum make_light_frustum(const scene& source, int rsm_size) { return make_light_frustum(source, bounds(source.geometry), rsm_size); }

light_frustum make_light_frustum(const scene& source, const bounding_box& box, int rsm_size) {
  light_frustum frustum;
  const float radius = std::max(box.radius(), 1e-3f);
  if (source.light.kind == light_kind::spot) {
    const spot_light<float>& light = source.light.spot;
    const glm::vec3 up = std::abs(light.direction.y) > 0.99f ? glm::vec3(0, 0, -1) : glm::vec3(0, 1, 0);
    frustum.view = glm::lookAt(light.position, light.position + light.direction, up);
    const float half_angle = spot_light_frustum_half_angle(light);
    frustum.tan_half_fov = std::tan(half_angle);
    const float far_plane = glm::length(light.position - box.centre()) + 2.0f * radius;
    frustum.view_projection = glm::perspective(2.0f * half_angle, 1.0f, 0.01f * radius, far_plane) * frustum.view;
  } else {
    const glm::vec3 direction = source.light.directional.direction;
    const glm::vec3 up = std::abs(direction.y) > 0.99f ? glm::vec3(0, 0, -1) : glm::vec3(0, 1, 0);
    frustum.view = glm::lookAt(box.centre() - 2.0f * radius * direction, box.centre(), up);
    frustum.view_projection = glm::ortho(-radius, radius, -radius, radius, 0.5f * radius, 3.5f * radius) * frustum.view;
    frustum.half_extent = radius;
    const float texel = 2.0f * radius / static_cast<float>(rsm_size);
    frustum.texel_area = texel * texel;
  }
  return frustum;
}

rsm_frame_constants make_frame_constants(const scene& source, const rsm_pipeline_settings& settings) {
  return make_frame_constants(source, bounds(source.geometry), source.geometry.triangle_count(), settings);
}

rsm_frame_constants make_frame_constants(const scene& source, const bounding_box& box, std::size_t triangles, const rsm_pipeline_settings& settings) {
  if (const std::string problem = validate(settings); !problem.empty()) throw error("RSM pipeline settings: " + problem);
  const setting_problem light_problem = source.light.kind == light_kind::spot ? validate(source.light.spot) : validate(source.light.directional);
  if (light_problem) throw error("scene " + source.name + ": " + light_problem.message());
  if (triangles == 0) throw error("scene " + source.name + " has no triangles");
  rsm_frame_constants constants;
  constants.technique = find_rsm_technique(settings.technique);
  constants.light = make_light_frustum(source, box, settings.rsm_size);
  constants.primary = source.light;
  constants.gather = make_rsm_gather_settings(settings.radial, settings.disk, settings.radius, settings.slots, glm::ivec2(settings.rsm_size));
  constants.gather.irradiance = settings.irradiance;
  constants.gather.coverage_blocks = settings.coverage_blocks;
  constants.gather.coverage_interleave = settings.coverage_interleave;
  constants.gather.perspective = source.light.kind == light_kind::spot ? 1 : 0;
  const bool spot = source.light.kind == light_kind::spot;
  constants.unprojection = make_rsm_unprojection(spot ? constants.light.tan_half_fov : constants.light.half_extent, spot, glm::ivec2(settings.rsm_size));
  constants.camera_view = camera_view_matrix(source.view);
  constants.camera_view_projection =
      camera_projection_matrix(source.view, static_cast<float>(settings.width) / static_cast<float>(settings.height)) * constants.camera_view;
  constants.shadow = settings.shadow;
  constants.bilateral = settings.bilateral;
  constants.filter = settings.filter;
  constants.temporal = settings.temporal;
  constants.image_size = glm::ivec2(settings.width, settings.height);
  constants.indirect_divisor = settings.indirect_divisor;
  constants.indirect_size = (constants.image_size + settings.indirect_divisor - 1) / settings.indirect_divisor;
  return constants;
}

namespace {

const char* flag(bool value) { return value ? "1" : "0"; }

bool is_directional(const scene& source) { return source.light.kind == light_kind::directional; }

// Whether the frame reduces the RSM to coarse lights: a gathering technique with coverage.
bool with_coverage(const rsm_frame_constants& constants) { return constants.technique.indirect && constants.gather.coverage_blocks > 0; }

// Whether sequences accumulate: a gathering technique with a blend below 1.
bool with_temporal(const rsm_frame_constants& constants) { return constants.technique.indirect && constants.temporal.blend < 1.0f; }

void set_light_uniforms(const program& target, const rsm_frame_constants& constants) {
  if (constants.primary.kind == light_kind::spot) set_uniforms(target, "spot", constants.primary.spot);
  else set_uniforms(target, "directional", constants.primary.directional);
}

}  // namespace

rsm_pipeline::rsm_pipeline(const shader_library& shaders, const scene& source, const rsm_pipeline_settings& settings)
    : scene_{source.name, mesh{}, source.view, source.light, source.notes},
      bounds_(bounds(source.geometry)),
      triangles_(source.geometry.triangle_count()),
      settings_(settings),
      constants_(make_frame_constants(source, bounds_, triangles_, settings)),
      mesh_(source.geometry),
      rsm_program_(load_program(shaders, "scene.vert", "rsm.frag", {{"VPLKIT_LIGHT_DIRECTIONAL", flag(is_directional(source))}})),
      gbuffer_program_(load_program(shaders, "scene.vert", "gbuffer.frag")),
      rsm_target_(settings.rsm_size, settings.rsm_size, {texel_format::rgba32ui}, true),
      coarse_target_(std::max(constants_.gather.coverage_blocks, 1), std::max(constants_.gather.coverage_blocks, 1),
                     {texel_format::rgba32f, texel_format::rgba32f, texel_format::rgba32f}, false),
      gbuffer_target_(settings.width, settings.height, {settings.format, settings.format, settings.format}, true),
      indirect_target_(constants_.indirect_size.x, constants_.indirect_size.y, {settings.format}, false),
      history_targets_{framebuffer(with_temporal(constants_) ? constants_.indirect_size.x : 1, with_temporal(constants_) ? constants_.indirect_size.y : 1,
                                   {settings.format}, false),
                       framebuffer(with_temporal(constants_) ? constants_.indirect_size.x : 1, with_temporal(constants_) ? constants_.indirect_size.y : 1,
                                   {settings.format}, false)},
      blur_x_target_(settings.filter == post_filter::separable ? constants_.indirect_size.x : 1,
                     settings.filter == post_filter::separable ? constants_.indirect_size.y : 1, {settings.format}, false),
      post_target_(settings.width, settings.height, {settings.format, settings.format}, false),
      empty_vertex_array_(generate_vertex_array()) {
  const rsm_technique& technique = constants_.technique;
  const bool separable = settings.filter == post_filter::separable;
  if (technique.indirect) {
    gather_program_ = load_program(shaders, "fullscreen.vert", "gather.frag",
                                   {{"VPLKIT_RSM_PATTERN", std::to_string(static_cast<int>(technique.pattern))},
                                    {"VPLKIT_VISIBILITY", std::to_string(static_cast<int>(technique.visibility))},
                                    {"VPLKIT_SLOT_COUNT", std::to_string(constants_.gather.slots.count)},
                                    {"VPLKIT_RSM_COVERAGE", flag(with_coverage(constants_))}});
    if (with_coverage(constants_)) coarse_program_ = load_program(shaders, "fullscreen.vert", "rsm_coarse.frag");
    if (with_temporal(constants_)) temporal_program_ = load_program(shaders, "fullscreen.vert", "temporal.frag");
    if (separable) blur_x_program_ = load_program(shaders, "fullscreen.vert", "blur_x.frag");
  }
  post_program_ = load_program(shaders, "fullscreen.vert", "post.frag",
                               {{"VPLKIT_INDIRECT", flag(technique.indirect)},
                                {"VPLKIT_SEPARABLE", flag(separable)},
                                {"VPLKIT_LIGHT_DIRECTIONAL", flag(is_directional(source))}});

  set_settings_uniforms();
  set_pose_uniforms();
  check_gl("setting up the RSM pipeline");
}

// The uniforms that come from the settings; the pose's are set by set_pose_uniforms.
void rsm_pipeline::set_settings_uniforms() {
  const rsm_technique& technique = constants_.technique;
  const bool separable = settings_.filter == post_filter::separable;
  rsm_program_.set("rsm_size", glm::ivec2(settings_.rsm_size));
  gbuffer_program_.set("rsm_size", glm::ivec2(settings_.rsm_size));
  set_uniforms(gbuffer_program_, "shadow", constants_.shadow);
  gbuffer_program_.set("rsm_packed", 0);

  if (technique.indirect) {
    set_uniforms(gather_program_, "settings", constants_.gather);
    gather_program_.set("indirect_divisor", constants_.indirect_divisor);
    gather_program_.set("gbuffer_size", constants_.image_size);
    int unit = 0;
    for (const char* name : {"rsm_packed", "gbuffer_position_depth", "gbuffer_normal"}) gather_program_.set(name, unit++);
    if (with_coverage(constants_)) {
      for (const char* name : {"coarse_position_extent", "coarse_normal", "coarse_flux"}) gather_program_.set(name, unit++);
      coarse_program_.set("rsm_size", glm::ivec2(settings_.rsm_size));
      coarse_program_.set("coverage_blocks", constants_.gather.coverage_blocks);
      coarse_program_.set("rsm_packed", 0);
    }
    if (with_temporal(constants_)) {
      set_uniforms(temporal_program_, "temporal", constants_.temporal);
      temporal_program_.set("indirect_divisor", constants_.indirect_divisor);
      temporal_program_.set("indirect_size", constants_.indirect_size);
      temporal_program_.set("gbuffer_size", constants_.image_size);
      int temporal_unit = 0;
      for (const char* name : {"indirect_buffer", "history_buffer", "gbuffer_position_depth"}) temporal_program_.set(name, temporal_unit++);
    }
    if (separable) {
      set_uniforms(blur_x_program_, "bilateral", constants_.bilateral);
      blur_x_program_.set("indirect_divisor", constants_.indirect_divisor);
      blur_x_program_.set("indirect_size", constants_.indirect_size);
      blur_x_program_.set("gbuffer_size", constants_.image_size);
      blur_x_program_.set("indirect_buffer", 0);
      blur_x_program_.set("gbuffer_normal", 1);
    }
  }
  set_uniforms(post_program_, "bilateral", constants_.bilateral);
  set_uniforms(post_program_, "irradiance", constants_.gather.irradiance);
  post_program_.set("indirect_divisor", constants_.indirect_divisor);
  post_program_.set("indirect_size", constants_.indirect_size);
  post_program_.set("gbuffer_size", constants_.image_size);
  int unit = 0;
  for (const char* name : {"indirect_buffer", "gbuffer_position_depth", "gbuffer_albedo_density", "gbuffer_normal"})
    post_program_.set(name, unit++);
}

bool rsm_pipeline::apply_settings(const technique_settings& settings) {
  const auto* typed = dynamic_cast<const described_settings<rsm_pipeline_settings, rsm_technique>*>(&settings);
  if (!typed) return false;
  const rsm_pipeline_settings& next = typed->value();
  if (!validate(next).empty()) return false;
  const rsm_frame_constants constants = make_frame_constants(scene_, bounds_, triangles_, next);
  // What the programs' defines and the targets' sizes and formats come from (the constructor).
  const bool same_build = next.technique == settings_.technique && next.width == settings_.width && next.height == settings_.height &&
                          next.rsm_size == settings_.rsm_size && next.format == settings_.format && next.filter == settings_.filter &&
                          constants.indirect_size == constants_.indirect_size && constants.gather.slots.count == constants_.gather.slots.count &&
                          constants.gather.coverage_blocks == constants_.gather.coverage_blocks &&
                          with_coverage(constants) == with_coverage(constants_) && with_temporal(constants) == with_temporal(constants_);
  if (!same_build) return false;
  settings_ = next;
  constants_ = constants;
  set_settings_uniforms();
  set_pose_uniforms();
  check_gl("applying the RSM pipeline's settings");
  // The G-buffer to the post filter again, and no history from the old settings. The RSM and the
  // coverage's coarse lights depend on the light, the RSM's size and the blocks only, which a
  // change in place keeps.
  view_valid_ = false;
  history_valid_ = false;
  sequence_frame_ = 0;
  return true;
}

void rsm_pipeline::set_pose_uniforms() {
  const light_frustum& light = constants_.light;
  rsm_program_.set("view_projection", light.view_projection);
  rsm_program_.set("light_view", light.view);
  rsm_program_.set("tan_half_fov", light.tan_half_fov);
  rsm_program_.set("texel_area", light.texel_area);
  set_light_uniforms(rsm_program_, constants_);
  gbuffer_program_.set("view_projection", constants_.camera_view_projection);
  gbuffer_program_.set("camera_view", constants_.camera_view);
  gbuffer_program_.set("light_view", light.view);
  gbuffer_program_.set("light_view_projection", light.view_projection);
  if (with_coverage(constants_)) set_uniforms(coarse_program_, "unprojection", constants_.unprojection);
  gbuffer_program_.set("light_projection", light.view_projection * glm::inverse(light.view));
  if (constants_.technique.indirect) {
    set_uniforms(gather_program_, "unprojection", constants_.unprojection);
    gather_program_.set("light_view", light.view);
    gather_program_.set("light_view_projection", light.view_projection);
  }
  set_light_uniforms(post_program_, constants_);
}

void rsm_pipeline::move_to(const camera& view, const scene_light& light) {
  const camera previous_view = scene_.view;
  const scene_light previous_light = scene_.light;
  scene_.view = view;
  scene_.light = light;
  try {
    constants_ = make_frame_constants(scene_, bounds_, triangles_, settings_);
  } catch (...) {
    scene_.view = previous_view;
    scene_.light = previous_light;
    throw;
  }
  set_pose_uniforms();
}

void rsm_pipeline::set_camera(const camera& view) {
  check_camera(view, "scene " + scene_.name);
  move_to(view, scene_.light);
  view_valid_ = false;
}

void rsm_pipeline::set_light(const scene_light& light) {
  if (light.kind != scene_.light.kind)
    throw error("scene " + scene_.name + ": the RSM pipeline was built for a " + (scene_.light.kind == light_kind::spot ? "spot" : "directional") +
                " light; make a new pipeline for another kind");
  check_light(light, "scene " + scene_.name);
  move_to(scene_.view, light);
  rsm_valid_ = view_valid_ = false;
}

rsm_frame rsm_pipeline::render() {
  draw();
  rsm_frame frame;
  frame.radiance = post_target_.read_image(0);
  frame.indirect = post_target_.read_image(1);
  frame.pass_times = timer_.collect();
  return frame;
}

bool rsm_pipeline::accumulates() const { return with_temporal(constants_); }

void rsm_pipeline::set_pattern_frame(std::uint32_t frame) {
  rsm_gather_settings<float> gather = constants_.gather;
  if (frame > 0) {
    gather.radial.seed = hash_combine(gather.radial.seed, frame);
    gather.disk.seed = hash_combine(gather.disk.seed, frame);
  }
  set_uniforms(gather_program_, "settings", gather);
}

rsm_frame rsm_pipeline::render_next() {
  if (!accumulates()) return render();
  set_pattern_frame(sequence_frame_);
  draw_passes(true, true);
  ++sequence_frame_;
  rsm_frame frame;
  frame.radiance = post_target_.read_image(0);
  frame.indirect = post_target_.read_image(1);
  frame.pass_times = timer_.collect();
  return frame;
}

void rsm_pipeline::draw() { draw_passes(true); }

void rsm_pipeline::draw_changed() {
  if (!rsm_valid_ || !view_valid_) draw_passes(!rsm_valid_);
}

void rsm_pipeline::draw_passes(bool with_rsm, bool accumulate) {
  const rsm_technique& technique = constants_.technique;
  if (!accumulate && (history_valid_ || sequence_frame_ > 0)) {
    // A frame outside a sequence: no history, and the settings' own pattern.
    history_valid_ = false;
    sequence_frame_ = 0;
    if (technique.indirect) set_pattern_frame(0);
  }
  last_accumulated_ = accumulate;
  glClearColor(0.0f, 0.0f, 0.0f, 0.0f);  // depth 0 marks "no surface" in every buffer
  glDisable(GL_BLEND);
  glDisable(GL_CULL_FACE);

  glEnable(GL_DEPTH_TEST);
  if (with_rsm) {
    timer_.begin("RSM generation");
    rsm_target_.bind();
    const GLuint empty_texel[4] = {0, 0, 0, 0};  // glClear's float colour is undefined for an integer target
    glClearBufferuiv(GL_COLOR, 0, empty_texel);
    glClear(GL_DEPTH_BUFFER_BIT);
    mesh_.draw(rsm_program_);
    timer_.end();
    if (with_coverage(constants_)) {
      timer_.begin("coverage lights");
      glDisable(GL_DEPTH_TEST);
      glBindVertexArray(empty_vertex_array_.get());
      coarse_target_.bind();
      rsm_target_.colour(0).bind(0);
      coarse_program_.use();
      glDrawArrays(GL_TRIANGLES, 0, 3);
      glBindVertexArray(0);
      glEnable(GL_DEPTH_TEST);
      timer_.end();
    }
    rsm_valid_ = true;
    ++rsm_draws_;
  }

  timer_.begin("G-buffer generation");
  gbuffer_target_.bind();
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  rsm_target_.colour(0).bind(0);
  mesh_.draw(gbuffer_program_);
  timer_.end();

  glDisable(GL_DEPTH_TEST);
  glBindVertexArray(empty_vertex_array_.get());
  if (technique.indirect) {
    timer_.begin("RSM sampling");
    indirect_target_.bind();
    rsm_target_.colour(0).bind(0);
    gbuffer_target_.colour(0).bind(1);
    gbuffer_target_.colour(2).bind(2);
    if (with_coverage(constants_))
      for (int i = 0; i < 3; ++i) coarse_target_.colour(static_cast<std::size_t>(i)).bind(3 + i);
    gather_program_.use();
    glDrawArrays(GL_TRIANGLES, 0, 3);
    timer_.end();
  }
  // The filter's input: the gather, or (sequences) the gather accumulated over the frames.
  const framebuffer* filter_input = &indirect_target_;
  if (accumulate) {
    timer_.begin("temporal accumulation");
    const int written = 1 - history_index_;
    history_targets_[written].bind();
    indirect_target_.colour(0).bind(0);
    history_targets_[history_index_].colour(0).bind(1);
    gbuffer_target_.colour(0).bind(2);
    last_temporal_inputs_ = {history_valid_, history_view_, history_view_projection_};
    temporal_program_.set("history_valid", history_valid_ ? 1 : 0);
    temporal_program_.set("previous_view", history_view_);
    temporal_program_.set("previous_view_projection", history_view_projection_);
    temporal_program_.use();
    glDrawArrays(GL_TRIANGLES, 0, 3);
    timer_.end();
    history_index_ = written;
    history_valid_ = true;
    history_view_ = constants_.camera_view;
    history_view_projection_ = constants_.camera_view_projection;
    filter_input = &history_targets_[written];
  }

  timer_.begin("post processing");
  const bool separable = technique.indirect && settings_.filter == post_filter::separable;
  if (separable) {
    blur_x_target_.bind();
    filter_input->colour(0).bind(0);
    gbuffer_target_.colour(2).bind(1);
    blur_x_program_.use();
    glDrawArrays(GL_TRIANGLES, 0, 3);
  }
  post_target_.bind();
  (separable ? blur_x_target_ : *filter_input).colour(0).bind(0);
  for (int i = 0; i < 3; ++i) gbuffer_target_.colour(static_cast<std::size_t>(i)).bind(i + 1);
  post_program_.use();
  glDrawArrays(GL_TRIANGLES, 0, 3);
  timer_.end();
  glBindVertexArray(0);
  check_gl("rendering scene " + scene_.name + " with " + technique.name);
  view_valid_ = true;
  ++view_draws_;
}

double rsm_pipeline::draw_wall_clock_ms() {
  glFinish();
  const auto start = std::chrono::steady_clock::now();
  draw();
  glFinish();
  const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  timer_.collect();  // the queries of this frame are not wanted
  return ms;
}

std::string rsm_pipeline::draw_counts() const {
  return "RSM " + std::to_string(rsm_draws_) + ", G-buffer to post filter " + std::to_string(view_draws_);
}

std::string rsm_pipeline::describe() const {
  return "scene " + scene_.name + " (" + std::to_string(triangles_) + " triangles), technique " + settings_.technique + ", " +
         std::to_string(settings_.width) + "x" + std::to_string(settings_.height) + ", RSM " + std::to_string(settings_.rsm_size) + "^2, indirect " +
         std::to_string(constants_.indirect_size.x) + "x" + std::to_string(constants_.indirect_size.y);
}

std::optional<image> rsm_pipeline::raw_indirect() const {
  if (!constants_.technique.indirect) return std::nullopt;
  return indirect_target_.read_image(0);
}

rsm_pass_buffers rsm_pipeline::read_buffers() const {
  rsm_pass_buffers buffers;
  buffers.rsm.width = rsm_target_.width();
  buffers.rsm.height = rsm_target_.height();
  const std::vector<std::uint32_t> words = rsm_target_.read_uint(0);
  buffers.rsm.texels.resize(words.size() / 4);
  std::memcpy(buffers.rsm.texels.data(), words.data(), words.size() * sizeof(std::uint32_t));
  for (std::size_t i = 0; i < 3; ++i) buffers.gbuffer[i] = gbuffer_target_.read_image(i);
  if (with_coverage(constants_))
    for (std::size_t i = 0; i < 3; ++i) buffers.coarse[i] = coarse_target_.read_image(i);
  if (constants_.technique.indirect) {
    buffers.indirect = indirect_target_.read_image(0);
    if (last_accumulated_) {
      buffers.accumulated = history_targets_[history_index_].read_image(0);
      buffers.history = history_targets_[1 - history_index_].read_image(0);
    }
    if (settings_.filter == post_filter::separable) buffers.blurred_x = blur_x_target_.read_image(0);
  }
  return buffers;
}

}  // namespace vplkit
