// The Light Wave pipeline of [LW] (chapter 4): VPLs on hemispheres around the spot light
// (laid out on the CPU by the lightwave kernels and uploaded to a float texture), shadow maps for
// the light and for some VPLs in one depth texture array, and one main pass whose vertex stage
// sums Eq. 4.5 over every VPL and whose fragment stage combines direct and indirect light with
// their shadows (Eq. 4.9). VPLs and shadow maps are rebuilt only when the light or the scene
// moves, as in the thesis.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include <vplkit/irradiance.hpp>
#include <vplkit/lightwave.hpp>
#include <vplkit/gl/program.hpp>

#include "frontend/core/setting.hpp"
#include "frontend/gl/pass_timer.hpp"
#include "frontend/scene_gl/mesh_buffers.hpp"
#include "frontend/gl/render_target.hpp"
#include "frontend/scene/scene.hpp"
#include "frontend/techniques/pipeline.hpp"

namespace vplkit {

/// The most VPL shadow maps a frame uses (accurate or integrated): the size of the shader's
/// arrays of shadow matrices and casters, which it gets as VPLKIT_MAX_SHADOW_MAPS.
constexpr int lightwave_max_shadow_maps = 64;

enum class lightwave_mode { direct = 0, faked = 1, unshadowed = 2, accurate = 3, integrated = 4 };

enum class lightwave_shadow_variant { importance = 0, thesis = 1 };

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
  int per_ray = 5;             ///< VPLs per ray (stacked hemispheres)
  /// Distance the hemispheres approach; 0 = the distance from the light to the farthest corner
  /// of the scene's bounding box (the thesis: "varies based off the dimensions of the scene").
  float max_distance = 0.0f;
  int accurate_maps = 20;      ///< VPL shadow maps of the accurate shadows (0: none, the same as unshadowed)
  /// How the accurate shadows choose, aim and combine their maps (the integrated shadows keep
  /// the thesis's maps, whose shared projection their in-between lookups need; both modes skip
  /// lookups behind a map's camera):
  /// - importance (the default): VPLs drawn in proportion to their diffuse weight on the visible
  ///   scene, each map aimed at the region its VPL lights, each lookup weighted by that VPL's
  ///   weight at the fragment over its probability, lookups outside a map not voting;
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
  std::uint32_t seed = 1;         ///< draws the VPLs of the accurate shadow maps
  lightwave_shading_settings<float> shading;
  irradiance_settings<float> irradiance;
  texel_format format = texel_format::rgba16f;
};

/// The description of every setting a user sets (frontend/core/setting.hpp).
const std::vector<setting<lightwave_settings, lightwave_technique>>& lightwave_settings_table();

/// Empty when usable, else the reason: the table's ranges, the VPL count the main pass can loop
/// over, the shadow maps the layout allows, and the kernels' settings.
std::string validate(const lightwave_settings& settings);

/// Bytes of a depth texture array of `maps` layers of width x height 32-bit depths: the memory
/// figure of Eq. 5.4 / 5.5 (3840 x 2160 x 21 x 4 bytes = 664.45 MiB).
std::uint64_t lightwave_shadow_map_bytes(int width, int height, int maps);

/// Indices of the VPLs that get shadow maps in the thesis's way: `accurate_maps` distinct VPLs
/// drawn uniformly with the seed (accurate), or the axis VPL and four at a quarter turn apart,
/// 45 degrees off the axis, of the innermost hemisphere (integrated: "equidistant, for maximum
/// coverage").
std::vector<int> lightwave_shadow_vpls(lightwave_mode mode, const lightwave_settings& settings);

/// A surface point the shadow casters are chosen and aimed for.
struct lightwave_receiver_point {
  glm::vec3 position;
  glm::vec3 normal;
};

/// A VPL that casts an accurate indirect shadow, and the probability with which it was drawn.
struct lightwave_shadow_caster {
  int vpl = 0;
  float probability = 1.0f;
};

/// `count` distinct VPLs drawn in proportion to their total diffuse weight (lightwave_vpl_weight)
/// over `points`, by systematic sampling of the cumulative weights with an offset from `seed`;
/// probability = min(1, count x weight / total). Fewer when fewer VPLs light any point.
std::vector<lightwave_shadow_caster> lightwave_importance_vpls(const std::vector<lightwave_vpl<float>>& vpls,
                                                               const std::vector<lightwave_receiver_point>& points, int count, std::uint32_t seed);

/// The view-projection of a shadow map for `vpl` that holds the points it lights: looking at
/// their weighted mean direction, with the field of view of the farthest of them plus a margin
/// (at most 160 degrees; points beyond do not vote). Looks along the VPL's normal with
/// `fallback_fov_degrees` when it lights none of them.
glm::mat4 lightwave_aimed_shadow_matrix(const lightwave_vpl<float>& vpl, const std::vector<lightwave_receiver_point>& points, float near_plane,
                                        float far_plane, float aspect, float fallback_fov_degrees);

struct lightwave_frame {
  image radiance;  ///< the final image
  /// The indirect shadow factor of each pixel in the red channel (1 = unshadowed; 1 for the
  /// modes without indirect shadows and where no surface is).
  image indirect_shadow;
  /// The indirect radiance each pixel adds to its direct light (Eq. 4.9's indirect term after
  /// its shadow factor; Eq. 5.2's addition for the faked mode; 0 for direct light only).
  image indirect;
  std::vector<pass_time> pass_times;
};

class lightwave_pipeline final : public pipeline {
 public:
  lightwave_pipeline(const shader_library& shaders, const scene& source, const lightwave_settings& settings);
  /// draw(), then the images read back.
  lightwave_frame render();
  /// Every pass: the VPLs and shadow maps, then the main pass.
  void draw() override;
  /// What the moves since the last frame invalidated: the VPLs and shadow maps after set_light
  /// (and after set_camera for the importance variant, whose casters follow the camera), the main
  /// pass after any move; nothing when nothing moved.
  void draw_changed() override;
  /// Moves the spot light: VPLs and shadow maps are rebuilt on the next frame. Throws
  /// vplkit::error for a directional light or an invalid one.
  void set_light(const scene_light& light) override;
  /// Moves the camera. The VPLs stay; the shadow maps are rebuilt on the next frame only for the
  /// importance variant of the accurate shadows, whose casters are drawn and aimed for the
  /// visible surface.
  void set_camera(const camera& view) override;
  camera current_camera() const override { return scene_.view; }
  scene_light current_light() const override { return scene_.light; }
  /// The pass times since the last render() or collect_pass_times().
  std::vector<pass_time> collect_pass_times() override { return timer_.collect(); }
  /// The last frame's radiance, indirect shadow factor (red) and indirect radiance textures.
  const texture_2d& output() const override { return target_.colour(0); }
  const texture_2d* indirect_shadow_output() const override;
  const texture_2d& indirect_output() const override { return target_.colour(2); }
  bool has_indirect() const override { return technique_.mode != lightwave_mode::direct; }
  int view_draws() const override { return main_draws_; }
  std::string draw_counts() const override;
  std::string describe() const override;
  std::string scene_name() const override { return scene_.name; }
  /// How many times VPLs and shadow maps have been built (1 after the first frame).
  int rebuilds() const { return rebuilds_; }
  std::uint64_t shadow_map_bytes() const;
  int vpl_count() const { return lightwave_vpl_count(settings_.angle_deg, settings_.per_ray); }
  const std::vector<lightwave_vpl<float>>& vpls() const { return vpls_; }
  const lightwave_layout_settings<float>& layout() const { return layout_; }
  /// Runs the main pass's vertex stage on the scene's vertices with transform feedback and
  /// returns each vertex's indirect colour (the parity test compares it with the CPU sum).
  std::vector<glm::vec3> capture_vertex_indirect();
  const scene& source() const { return scene_; }
  const lightwave_settings& settings() const { return settings_; }
  /// The VPLs with shadow maps of the last build (accurate and integrated modes).
  const std::vector<lightwave_shadow_caster>& shadow_casters() const { return casters_; }

 private:
  void rebuild();
  void draw_main_pass();
  /// The accurate shadows' importance variant: casters drawn and maps aimed for the visible
  /// surface, so they depend on the camera.
  bool casters_follow_camera() const {
    return settings_.shadow_variant == lightwave_shadow_variant::importance && technique_.mode == lightwave_mode::accurate;
  }
  void set_vertex_uniforms(const program& target) const;

  scene scene_;
  lightwave_settings settings_;
  lightwave_technique technique_;
  lightwave_layout_settings<float> layout_;
  std::vector<lightwave_vpl<float>> vpls_;
  std::vector<glm::mat4> shadow_matrices_;
  std::vector<lightwave_shadow_caster> casters_;
  mesh_buffers mesh_;
  program depth_program_;
  program main_program_;
  program capture_program_;
  gl_texture vpl_texture_;
  gl_texture shadow_maps_;
  gl_framebuffer shadow_framebuffer_;
  glm::ivec2 shadow_size_{0};
  int shadow_layers_ = 1;  ///< allocated: 1 + the maps asked for; drawn: 1 + casters_ (fewer when fewer VPLs light the scene)
  framebuffer target_;
  pass_timer timer_;
  bool dirty_ = true;        ///< the VPLs and shadow maps must be rebuilt
  bool view_valid_ = false;  ///< the main pass matches the camera and the light
  int rebuilds_ = 0;
  int main_draws_ = 0;
};

}  // namespace vplkit
