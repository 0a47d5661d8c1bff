#include "frontend/techniques/lightwave/lightwave_settings.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <functional>

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


// The table in groups, each a function, in the table's order: the targets, the VPLs, the
// indirect shadows, the shading. An entry is its field's member path: the default is the struct's
// initialiser, and get and set come from the path.
namespace {

using entry = setting<lightwave_settings, lightwave_technique>;
using S = lightwave_settings;
using I = irradiance_settings<float>;
using H = lightwave_shading_settings<float>;

// The techniques of any of `modes`.
std::function<bool(const lightwave_technique&)> modes(std::vector<lightwave_mode> any) {
  return [any](const lightwave_technique& t) { return std::find(any.begin(), any.end(), t.mode) != any.end(); };
}
bool vpl_light(const lightwave_technique& t) { return t.mode != lightwave_mode::direct && t.mode != lightwave_mode::faked; }
bool accurate(const lightwave_technique& t) { return t.mode == lightwave_mode::accurate; }

// The kernel structs the frame uploads (the member paths of .feeds() read them).
I irradiance(const S& s) { return s.irradiance; }
H shading(const S& s) { return s.shading; }

std::vector<entry> target_settings() {
  return {
      entry::extent("size", path_of(&S::width), path_of(&S::height), schema::closed_range(1, max_image_side), "pixels",
                    "final image size, N or WxH (the thesis: 1280x720)")
          .builds("the targets")
          .not_live(),
      entry::choice("format", path_of(&S::format), {{"rgba16f", texel_format::rgba16f}, {"rgba32f", texel_format::rgba32f}}, "float format of the render targets")
          .builds("the targets"),
      entry::number("min-distance", path_of(&S::irradiance, &I::min_distance))
          .feeds("lightwave.frag", "irradiance", irradiance, &I::min_distance)
          .feeds("lightwave_capture.frag", "irradiance", irradiance, &I::min_distance),
      entry::number("seed", path_of(&S::seed), schema::closed_range(0, 4294967295.0), "",
                    "seed of the VPL draw of the accurate shadows' thesis variant (the importance variant has none)")
          .read_by(accurate, "the accurate shadows"),
  };
}

std::vector<entry> vpl_settings() {
  std::vector<int> ray_angles;
  for (int angle = 1; angle <= 90; ++angle)
    if (lightwave_ray_angle_divides(angle)) ray_angles.push_back(angle);
  return {
      entry::choice("vpl-energy", path_of(&S::energy), {{"flux", lightwave_energy::flux}, {"thesis", lightwave_energy::thesis}},
                    "flux (each VPL reflects the flux its patch of the spot's cone brings, with a diffuse bounce's falloff) or thesis "
                    "(Eq. 4.5's VPLs on hemispheres, without flux: the Tables 5.x)")
          .read_by(vpl_light, "the VPL light")
          .defines("lightwave.frag: VPLKIT_LIGHTWAVE_ENERGY")
          .defines("lightwave.vert: VPLKIT_LIGHTWAVE_ENERGY"),
      entry::number("ray-angle", path_of(&S::angle_deg), describe_field(&lightwave_layout_settings<float>::angle_deg))
          .allowing(ray_angles)
          .read_by(vpl_light, "the VPL light")
          .feeds("lightwave.vert: vpl_texture; lightwave.vert: vpl_count; lightwave_capture.frag: pass_vpl_count"),
      entry::number("vpls-per-ray", path_of(&S::per_ray), describe_field(&lightwave_layout_settings<float>::per_ray))
          .read_by(vpl_light, "the VPL light")
          .feeds("lightwave.vert: vpl_texture; lightwave.vert: vpl_count; lightwave_capture.frag: pass_vpl_count"),
      entry::number("vpl-max-distance", path_of(&S::max_distance), schema::closed_range(0, max_scene_coordinate), "scene units",
                    "thesis energy: the distance the hemispheres approach (0: from the scene's size)")
          .read_by(vpl_light, "the VPL light")
          .feeds("lightwave.vert: vpl_texture"),
  };
}

// The shadow maps' array has a layer per map of the technique (derive: indirect_maps) and the
// rounded size of shadow-map-scale screens: what the array is made with.
std::string shadow_layers(const S& s) { return std::to_string(derive(s).indirect_maps); }

std::vector<entry> shadow_settings() {
  return {
      entry::number("shadow-maps", path_of(&S::accurate_maps), schema::closed_range(0, lightwave_max_shadow_maps), "", "VPL shadow maps of the accurate shadows (0: none)")
          .read_by(accurate, "the accurate shadows")
          .feeds("lightwave.frag: indirect_maps; lightwave.frag: shadow_matrix")
          .builds("the shadow maps' layers", shadow_layers),
      entry::choice("shadow-variant", path_of(&S::shadow_variant), {{"importance", lightwave_shadow_variant::importance}, {"thesis", lightwave_shadow_variant::thesis}},
                    "importance (the VPLs split into groups of equal light on the visible scene, one map per group from its medoid aimed at "
                    "what it lights, each map shadowing its group's share; no seed) or thesis (uniform VPLs, maps along their normals, the plain mean)")
          .read_by(accurate, "the accurate shadows")
          .defines("lightwave.frag: VPLKIT_LIGHTWAVE_SHADOW_VARIANT"),
      entry::number("integrated-maps", path_of(&S::integrated_maps), schema::closed_range(2, lightwave_max_shadow_maps), "",
                    "shadow maps of the integrated shadows: the axis VPL and a ring of the innermost hemisphere (a point light's: placed by importance)")
          .read_by(modes({lightwave_mode::integrated}), "the integrated shadows")
          .feeds("lightwave.frag: indirect_maps; lightwave.frag: shadow_matrix")
          .builds("the shadow maps' layers", shadow_layers),
      entry::number("integrated-steps", path_of(&S::integrated_steps), schema::closed_range(0, 64), "", "in-between lookups per pair of maps (the thesis: 2, 4, 6, 10)")
          .read_by(modes({lightwave_mode::integrated}), "the integrated shadows")
          .feeds("lightwave.frag: integrated_steps"),
      entry::number("shadow-map-scale", path_of(&S::shadow_map_scale), schema::open_closed_range(0, 16), "screens", "shadow map size in screens (the thesis: 3)")
          .feeds("lightwave.frag: shadow_maps")
          .builds("the shadow maps' size", [](const S& s) {
            const glm::ivec2 size = derive(s).shadow_map_size;
            return std::to_string(size.x) + "x" + std::to_string(size.y);
          }),
      entry::number("vpl-field-of-view", path_of(&S::vpl_field_of_view), {1, 179, true, true}, "degrees",
                    "field of view of a VPL's shadow map where it looks along the VPL's normal (thesis variant, integrated shadows)")
          .read_by(modes({lightwave_mode::accurate, lightwave_mode::integrated}), "the indirect shadows")
          .feeds("lightwave.frag: shadow_matrix"),
  };
}

std::vector<entry> shading_settings() {
  return {
      entry::number("faked-multiplier", path_of(&S::faked_multiplier), schema::closed_range(0.5, 4), "Eq. 5.2", "m of Eq. 5.2 (the thesis uses 1.1 to 1.5)")
          .read_by(modes({lightwave_mode::faked}), "the faked indirect light")
          .feeds("lightwave.frag: faked_multiplier"),
      entry::number("specular-strength", path_of(&S::shading, &H::specular_strength))
          .read_by(vpl_light, "the VPL light")
          .feeds("lightwave.vert", "shading", shading, &H::specular_strength),
      entry::number("specular-exponent", path_of(&S::shading, &H::specular_exponent))
          .read_by(vpl_light, "the VPL light")
          .feeds("lightwave.vert", "shading", shading, &H::specular_exponent),
  };
}

}  // namespace

const std::vector<setting<lightwave_settings, lightwave_technique>>& lightwave_settings_table() {
  static const std::vector<entry> table = [] {
    std::vector<entry> all;
    for (std::vector<entry> group : {target_settings(), vpl_settings(), shadow_settings(), shading_settings()})
      for (entry& one : group) all.push_back(std::move(one));
    return all;
  }();
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
