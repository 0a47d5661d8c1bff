#include "frontend/techniques/lightwave/lightwave_settings.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <tuple>

#include "frontend/core/error.hpp"
#include "frontend/core/named_table.hpp"
#include "frontend/image/image.hpp"

namespace vplkit {

const std::vector<lightwave_technique>& lightwave_techniques() {
  static const std::vector<lightwave_technique> techniques = {
      {"lightwave-direct", lightwave_mode::direct, "direct light only, shadow-mapped"},
      {"lightwave-faked", lightwave_mode::faked, "faked indirect light (Eq. 5.2, --faked-multiplier)"},
      {"lightwave-unshadowed", lightwave_mode::unshadowed, "VPL indirect light without indirect shadows"},
      {"lightwave-accurate", lightwave_mode::accurate, "VPL indirect light, accurate indirect shadows (--shadow-maps)"},
      {"lightwave-integrated", lightwave_mode::integrated, "VPL indirect light, integrated indirect shadows (--integrated-steps)"},
  };
  return techniques;
}

const lightwave_technique& find_lightwave_technique(const std::string& name) { return find_by_name(lightwave_techniques(), name, "Light Wave technique"); }


const std::vector<setting<lightwave_settings, lightwave_technique>>& lightwave_settings_table() {
  using entry = setting<lightwave_settings, lightwave_technique>;
  const auto modes = [](std::vector<lightwave_mode> any) {
    return [any](const lightwave_technique& t) { return std::find(any.begin(), any.end(), t.mode) != any.end(); };
  };
  const auto vpl_light = modes({lightwave_mode::unshadowed, lightwave_mode::accurate, lightwave_mode::integrated});
  const auto shadow_maps = modes({lightwave_mode::accurate, lightwave_mode::integrated});
  std::vector<int> ray_angles;
  for (int angle = 1; angle <= 90; ++angle)
    if (lightwave_ray_angle_divides(angle)) ray_angles.push_back(angle);
  // The kernel structs the frame uploads (the member paths of .feeds() read them).
  const auto irradiance = [](const lightwave_settings& s) { return s.irradiance; };
  const auto shading = [](const lightwave_settings& s) { return s.shading; };
  static const std::vector<entry> table = {
      entry::custom("size", setting_type::size, "pixels", "final image size, N or WxH (the thesis: 1280x720)",
                    [](const lightwave_settings& s) { return s.width == s.height ? std::to_string(s.width) : std::to_string(s.width) + "x" + std::to_string(s.height); },
                    [](lightwave_settings& s, const std::string& text) { std::tie(s.width, s.height) = *parse_extent(text); })
          .within(schema::closed_range(1, max_image_side))
          .not_live(),
      entry::choice("format", [](auto& s) -> auto& { return s.format; }, {{"rgba16f", texel_format::rgba16f}, {"rgba32f", texel_format::rgba32f}},
                    "float format of the render targets"),
      entry::number("min-distance", [](auto& s) -> auto& { return s.irradiance.min_distance; }, describe_field(&irradiance_settings<float>::min_distance))
          .feeds("lightwave.frag", "irradiance", irradiance, &irradiance_settings<float>::min_distance)
          .feeds("lightwave_capture.frag", "irradiance", irradiance, &irradiance_settings<float>::min_distance),
      entry::number("seed", [](auto& s) -> auto& { return s.seed; }, schema::closed_range(0, 4294967295.0), "",
                    "seed of the VPL draw of the accurate shadows' thesis variant (the importance variant has none)")
          .read_by(modes({lightwave_mode::accurate}), "the accurate shadows"),
      entry::choice("vpl-energy", [](auto& s) -> auto& { return s.energy; }, {{"flux", lightwave_energy::flux}, {"thesis", lightwave_energy::thesis}},
                    "flux (each VPL reflects the flux its patch of the spot's cone brings, with a diffuse bounce's falloff) or thesis "
                    "(Eq. 4.5's VPLs on hemispheres, without flux: the Tables 5.x)")
          .read_by(vpl_light, "the VPL light")
          .feeds("lightwave.frag: VPLKIT_LIGHTWAVE_ENERGY; lightwave.vert: VPLKIT_LIGHTWAVE_ENERGY"),
      entry::number("ray-angle", [](auto& s) -> auto& { return s.angle_deg; }, describe_field(&lightwave_layout_settings<float>::angle_deg))
          .allowing(ray_angles)
          .read_by(vpl_light, "the VPL light")
          .feeds("lightwave.vert: vpl_texture; lightwave.vert: vpl_count; lightwave_capture.frag: pass_vpl_count"),
      entry::number("vpls-per-ray", [](auto& s) -> auto& { return s.per_ray; }, describe_field(&lightwave_layout_settings<float>::per_ray))
          .read_by(vpl_light, "the VPL light")
          .feeds("lightwave.vert: vpl_texture; lightwave.vert: vpl_count; lightwave_capture.frag: pass_vpl_count"),
      entry::number("vpl-max-distance", [](auto& s) -> auto& { return s.max_distance; }, schema::closed_range(0, max_scene_coordinate), "scene units",
                    "thesis energy: the distance the hemispheres approach (0: from the scene's size)")
          .read_by(vpl_light, "the VPL light")
          .feeds("lightwave.vert: vpl_texture"),
      entry::number("shadow-maps", [](auto& s) -> auto& { return s.accurate_maps; }, schema::closed_range(0, lightwave_max_shadow_maps), "",
                    "VPL shadow maps of the accurate shadows (0: none)")
          .read_by(modes({lightwave_mode::accurate}), "the accurate shadows")
          .feeds("lightwave.frag: indirect_maps; lightwave.frag: shadow_matrix"),
      entry::choice("shadow-variant", [](auto& s) -> auto& { return s.shadow_variant; },
                    {{"importance", lightwave_shadow_variant::importance}, {"thesis", lightwave_shadow_variant::thesis}},
                    "importance (the VPLs split into groups of equal light on the visible scene, one map per group from its medoid aimed at "
                    "what it lights, each map shadowing its group's share; no seed) or thesis (uniform VPLs, maps along their normals, the plain mean)")
          .read_by(modes({lightwave_mode::accurate}), "the accurate shadows")
          .feeds("lightwave.frag: VPLKIT_LIGHTWAVE_SHADOW_VARIANT"),
      entry::number("integrated-maps", [](auto& s) -> auto& { return s.integrated_maps; }, schema::closed_range(2, lightwave_max_shadow_maps), "",
                    "shadow maps of the integrated shadows: the axis VPL and a ring of the innermost hemisphere")
          .read_by(modes({lightwave_mode::integrated}), "the integrated shadows")
          .feeds("lightwave.frag: indirect_maps; lightwave.frag: shadow_matrix"),
      entry::number("integrated-steps", [](auto& s) -> auto& { return s.integrated_steps; }, schema::closed_range(0, 64), "",
                    "in-between lookups per pair of maps (the thesis: 2, 4, 6, 10)")
          .read_by(modes({lightwave_mode::integrated}), "the integrated shadows")
          .feeds("lightwave.frag: integrated_steps"),
      entry::number("shadow-map-scale", [](auto& s) -> auto& { return s.shadow_map_scale; }, schema::open_closed_range(0, 16), "screens",
                    "shadow map size in screens (the thesis: 3)")
          .feeds("lightwave.frag: shadow_maps"),
      entry::number("vpl-field-of-view", [](auto& s) -> auto& { return s.vpl_field_of_view; }, {1, 179, true, true}, "degrees",
                    "field of view of a VPL's shadow map where it looks along the VPL's normal (thesis variant, integrated shadows)")
          .read_by(shadow_maps, "the indirect shadows")
          .feeds("lightwave.frag: shadow_matrix"),
      entry::number("faked-multiplier", [](auto& s) -> auto& { return s.faked_multiplier; }, schema::closed_range(0.5, 4), "Eq. 5.2",
                    "m of Eq. 5.2 (the thesis uses 1.1 to 1.5)")
          .read_by(modes({lightwave_mode::faked}), "the faked indirect light")
          .feeds("lightwave.frag: faked_multiplier"),
      entry::number("specular-strength", [](auto& s) -> auto& { return s.shading.specular_strength; },
                    describe_field(&lightwave_shading_settings<float>::specular_strength))
          .read_by(vpl_light, "the VPL light")
          .feeds("lightwave.vert", "shading", shading, &lightwave_shading_settings<float>::specular_strength),
      entry::number("specular-exponent", [](auto& s) -> auto& { return s.shading.specular_exponent; },
                    describe_field(&lightwave_shading_settings<float>::specular_exponent))
          .read_by(vpl_light, "the VPL light")
          .feeds("lightwave.vert", "shading", shading, &lightwave_shading_settings<float>::specular_exponent),
  };
  return table;
}

std::string validate(const lightwave_settings& settings) {
  try {
    find_lightwave_technique(settings.technique);
  } catch (const error& failure) {
    return failure.what();
  }
  if (const std::string problem = check_settings(lightwave_settings_table(), settings); !problem.empty()) return problem;
  for (const setting_problem& problem : {validate_lightwave_layout(settings.angle_deg, settings.per_ray), validate(settings.shading), validate(settings.irradiance)})
    if (problem) return problem.message();
  const lightwave_derived_settings derived = derive(settings);
  // A size derived from settings names them (the texture would fail with a size alone).
  const int shadow_side = std::max(derived.shadow_map_size.x, derived.shadow_map_size.y);
  if (shadow_side > max_image_side) {
    std::ostringstream scale;
    scale << settings.shadow_map_scale;
    return "shadow-map-scale " + scale.str() + " with a " + std::to_string(settings.width) + "x" +
           std::to_string(settings.height) + " image (size) makes shadow maps of " + std::to_string(shadow_side) + " texels per side, more than " +
           std::to_string(max_image_side);
  }
  const int vpls = derived.vpls;
  // The thesis energy's vertex stage loops over every VPL (the flux energy's passes over at most
  // vpls_per_pass), and llvmpipe ends a loop after 65535 iterations.
  if (vpls > 65535) return "at most 65535 VPLs (the per-vertex loop; llvmpipe stops loops there), got " + std::to_string(vpls);
  // The flux energy puts its VPLs where its rays meet the scene: no hemispheres to place.
  if (settings.energy == lightwave_energy::flux && settings.max_distance != 0.0f)
    return "vpl-max-distance places the thesis's hemispheres and is read with vpl-energy thesis; the flux energy puts its VPLs where its rays "
           "meet the scene (leave vpl-max-distance at 0)";
  if (!(settings.receiver_spacing > 0.0f && settings.receiver_spacing <= 4.0f)) return "receiver spacing must be in (0, 4] (a fraction of the scene's bounding radius)";
  if (settings.receiver_triangles < 1 || settings.receiver_triangles > (1 << 22)) return "receiver triangles must be in [1, 4194304]";
  if (settings.vpls_per_pass < 0 || settings.vpls_per_pass > 65535) return "VPLs per pass must be 0 (a uniform block's worth) or in [1, 65535]";
  if (settings.accurate_maps > vpls)
    return "more accurate shadow maps (" + std::to_string(settings.accurate_maps) + ") than VPLs (" + std::to_string(vpls) + ")";
  const int ring = 360 / settings.angle_deg;
  if (settings.integrated_maps > 1 + ring)
    return "integrated-maps must be at most " + std::to_string(1 + ring) + " (the axis VPL and a ring of the innermost hemisphere at " +
           std::to_string(settings.angle_deg) + " degrees), got " + std::to_string(settings.integrated_maps);
  return {};
}


lightwave_derived_settings derive(const lightwave_settings& settings) {
  lightwave_derived_settings derived;
  derived.shadow_map_size = glm::ivec2(static_cast<int>(std::lround(settings.shadow_map_scale * static_cast<float>(settings.width))),
                                       static_cast<int>(std::lround(settings.shadow_map_scale * static_cast<float>(settings.height))));
  derived.vpls = lightwave_vpl_count(settings.angle_deg, settings.per_ray);
  const lightwave_mode mode = find_lightwave_technique(settings.technique).mode;
  derived.indirect_maps = mode == lightwave_mode::accurate ? settings.accurate_maps : mode == lightwave_mode::integrated ? settings.integrated_maps : 0;
  return derived;
}

}  // namespace vplkit
