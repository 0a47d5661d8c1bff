// Light Wave's settings: its techniques, the settings struct with the thesis's defaults, the table
// every option, control and sweep axis comes from (frontend/core/setting.hpp), validate() and the
// one derive() both validation and the pipeline use.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include <vplkit/irradiance.hpp>
#include <vplkit/lightwave.hpp>

#include "frontend/core/setting.hpp"
#include "frontend/gl/render_target.hpp"
#include "frontend/techniques/lightwave/lightwave_planning.hpp"

namespace vplkit {

struct lightwave_technique {
  const char* name = "";
  lightwave_mode mode = lightwave_mode::accurate;
  const char* description = "";
};

/// lightwave-direct, lightwave-faked, lightwave-unshadowed, lightwave-accurate, lightwave-integrated.
const std::vector<lightwave_technique>& lightwave_techniques();
const lightwave_technique& find_lightwave_technique(const std::string& name);


/// Every setting, with the thesis's defaults.
struct lightwave_settings {
  std::string technique = "lightwave-accurate";
  int width = 1280;            ///< the thesis: 1280 x 720
  int height = 720;
  int angle_deg = 5;           ///< between VPL rays
  int per_ray = 5;             ///< VPLs per ray (thesis: stacked hemispheres; flux: samples of the ray's patch)
  /// flux (the default) or thesis; see lightwave_energy.
  lightwave_energy energy = lightwave_energy::flux;
  /// Thesis energy: distance the hemispheres approach; 0 = the distance from the light to the
  /// farthest corner of the scene's bounding box (the thesis: "varies based off the dimensions of
  /// the scene"). The flux energy puts its VPLs on the surfaces and must leave it 0.
  float max_distance = 0.0f;
  int accurate_maps = 20;      ///< VPL shadow maps of the accurate shadows (0: none, the same as unshadowed)
  /// How the accurate shadows choose, aim and combine their maps (the integrated shadows keep
  /// the thesis's maps, whose shared projection their in-between lookups need; both modes skip
  /// lookups behind a map's camera):
  /// - importance (the default): the VPLs that light the visible scene split into as many
  ///   compact groups of equal light as there are maps (lightwave_cluster_casters), one map per
  ///   group from its medoid VPL, aimed at what that VPL lights; each map shadows the share of a
  ///   fragment's indirect light its group brings there, trusted the less the larger the group
  ///   looks from the fragment (lightwave_group_confidence), fading to lit towards the map's
  ///   border and nothing where it does not cover the fragment; no seed;
  /// - thesis: VPLs drawn uniformly, each map looking along its VPL's normal with
  ///   vpl_field_of_view, the plain mean of the lookups, outside a map counting as lit.
  lightwave_shadow_variant shadow_variant = lightwave_shadow_variant::importance;
  int integrated_maps = 5;     ///< shadow maps from the innermost hemisphere (integrated shadows)
  int integrated_steps = 10;   ///< in-between lookups per pair of maps (2, 4, 6, 10 in the thesis)
  float shadow_map_scale = 3.0f;  ///< shadow map size = this x the screen (the thesis: 3)
  /// Field of view of a VPL's shadow map in the thesis variant, degrees (the thesis does not give
  /// it). 120 degrees covers the part of the 240-degree lobe where it is at least 2/3 of its
  /// peak. The importance variant fits each map to the region its VPL lights instead.
  float vpl_field_of_view = 120.0f;
  float faked_multiplier = 1.3f;  ///< m of Eq. 5.2 (the thesis: 1.1 .. 1.5; 1.3 ranked best)
  /// Flux energy: the indirect light is summed at the vertices of the scene subdivided until no
  /// edge is longer than this fraction of its bounding radius (lightwave_receivers), at most
  /// receiver_triangles triangles (the bound grows until it fits). Once per light position: a
  /// diffuse bounce does not depend on the camera, and the main pass reads it as a vertex attribute.
  float receiver_spacing = 1.0f / 8.0f;
  int receiver_triangles = 32768;
  /// Flux energy: the VPLs the receivers sum in one pass (lightwave_capture.frag); 0: as many as
  /// one uniform block of the GL holds (GL_MAX_UNIFORM_BLOCK_SIZE / 48 bytes), at most 1365 (64 KiB).
  /// Any count gives the same sums to the bit; fewer a pass means more passes.
  int vpls_per_pass = 0;
  std::uint32_t seed = 1;         ///< draws the VPLs of the accurate shadow maps of the thesis variant
  lightwave_shading_settings<float> shading;  ///< thesis energy (Eq. 4.5's specular term)
  irradiance_settings<float> irradiance;      ///< the direct light's and the flux VPLs' distance clamp
  texel_format format = texel_format::rgba16f;
};

/// The description of every setting a user sets (frontend/core/setting.hpp).
const std::vector<setting<lightwave_settings, lightwave_technique>>& lightwave_settings_table();

/// What the frame reads that is derived from the settings, derived here once: validate() checks
/// it, the pipeline allocates and lays out by it.
struct lightwave_derived_settings {
  glm::ivec2 shadow_map_size{0};  ///< shadow-map-scale x the image, rounded
  int vpls = 0;                   ///< the layout's VPLs (Eq. 5.1)
  int indirect_maps = 0;          ///< the VPL shadow maps of the technique (accurate or integrated; 0 otherwise)
};
/// Settings whose ranges check_settings accepted.
lightwave_derived_settings derive(const lightwave_settings& settings);

/// Empty when usable, else the reason: the table's ranges, the VPL count the main pass can loop
/// over, the shadow maps the layout allows, and the kernels' settings.
std::string validate(const lightwave_settings& settings);


}  // namespace vplkit
