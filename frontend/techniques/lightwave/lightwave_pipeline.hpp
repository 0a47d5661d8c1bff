// The Light Wave pipeline of [LW] (chapter 4): VPLs laid out on the CPU by the lightwave
// kernels, shadow maps for the light and for some VPLs in one depth texture array, and a main
// pass whose fragment stage combines direct and indirect light with their shadows (Eq. 4.9).
// VPLs and shadow maps are rebuilt only when the light or the scene moves, as in the thesis.
// Two energies (lightwave_energy): the thesis's VPLs floating on hemispheres with Eq. 4.5, read
// from a float texture and summed by the main pass's vertex stage at every vertex, every frame;
// or (the default) VPLs where the rays of the spot's cone meet the scene, found in a map of what
// the light sees, each reflecting the flux its patch of the cone brings, summed once per light at
// the vertices of the scene subdivided (lightwave_capture.frag) and drawn into a screen buffer
// the main pass reads (docs/lightwave-shadows.md).
// Every kind of light: a spot (its cone's VPLs, one perspective shadow map), a point light (VPLs
// over the sphere, the direct light's shadow from six cube faces, cube_face_of), a sun (VPLs on
// parallel rays across an orthographic map, one orthographic shadow map; docs/errata.md, LW-9).
// Several lights (up to max_scene_lights, any mix): the first is drawn here, each further one by a
// pipeline of its own on the scene with that light alone (its own VPLs, shadow maps and, for the
// flux energy, receivers' sums), whose main pass adds its light onto the first's image with
// additive blending, on the first's depth; pass times carry the light's number ("light 1: shadow
// maps"). What does not depend on the light (the scene's mesh buffers, the output image, the flux
// energy's receivers, their textures and sum targets, the map of what a light sees and the indirect
// screen buffer) is made once and shared by every light's pipeline (shared_resources).
#pragma once

#include <cstdint>
#include <array>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include <vplkit/irradiance.hpp>
#include <vplkit/lightwave.hpp>
#include <vplkit/gl/program.hpp>

#include "frontend/gl/pass_timer.hpp"
#include "frontend/scene_gl/emission_pass.hpp"
#include "frontend/scene_gl/mesh_buffers.hpp"
#include "frontend/gl/render_target.hpp"
#include "frontend/scene/scene.hpp"
#include "frontend/techniques/lightwave/lightwave_planning.hpp"
#include "frontend/techniques/lightwave/lightwave_settings.hpp"
#include "frontend/techniques/pipeline.hpp"

namespace vplkit {

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
  /// Every pass: the VPLs, the shadow maps, the indirect buffer (flux energy), the main pass.
  void draw() override;
  /// What the moves since the last frame invalidated: the VPLs and shadow maps after set_light
  /// (and after set_camera for casters grouped by importance with the thesis energy, which follow
  /// the camera; the flux energy's do not), the main
  /// pass after any move; nothing when nothing moved.
  void draw_changed() override;
  /// Moves light `index`: its VPLs and shadow maps are rebuilt on the next frame. Throws
  /// vplkit::error for a light of another kind than the one it replaces (its programs and shadow
  /// maps are made for its kind), an invalid one or an index past the scene's lights.
  void set_light(std::size_t index, const scene_light& light) override;
  /// Moves the camera. The VPLs stay; the shadow maps are rebuilt on the next frame only where
  /// the casters follow the camera (casters_follow_camera: the thesis energy's casters grouped by
  /// importance, the accurate shadows' or a point light's integrated ones).
  void set_camera(const camera& view) override;
  camera current_camera() const override { return scene_.view; }
  std::vector<scene_light> current_lights() const override { return scene_.lights; }
  /// In place when the settings change no define, no target's or shadow map's size and no
  /// receiver mesh (lightwave_pipeline.cpp says which setting is which): the next frame redraws
  /// the main pass, after the VPLs and shadow maps where the change moves them.
  bool apply_settings(const technique_settings& settings) override;
  /// The pass times since the last render() or collect_pass_times().
  /// With several lights each pass's name starts with its light's ("light 1: shadow maps").
  std::vector<pass_time> collect_pass_times() override;
  /// The last frame's radiance and indirect shadow factor (red).
  const texture_2d& output() const override { return shared_->target.colour(0); }
  const texture_2d* indirect_shadow_output() const override;
  /// The indirect irradiance (-indirect.pfm, the quantity of every family): the indirect
  /// radiance of lightwave_frame::indirect over the surface's reflectance albedo / pi.
  const texture_2d& indirect_output() const override { return shared_->target.colour(3); }
  /// The lights' direct irradiance after their shadow maps (lightwave.frag's output 4).
  const texture_2d& direct_output() const override { return shared_->target.colour(4); }
  bool has_indirect() const override { return technique_.mode != lightwave_mode::direct; }
  int view_draws() const override { return main_draws_; }
  std::string draw_counts() const override;
  std::string describe() const override;
  std::string scene_name() const override { return scene_.name; }
  /// The lights drawn: the scene's (each its own VPLs and shadow maps).
  std::size_t light_count() const { return 1 + light_pipelines_.size(); }
  /// How many times the first light's VPLs and shadow maps have been built (1 after the first frame).
  /// The accessors below (VPLs, casters, captures) are the first light's.
  int rebuilds() const { return rebuilds_; }
  std::uint64_t shadow_map_bytes() const;
  /// The layout's VPLs (Eq. 5.1); the flux energy keeps those whose ray met a lit surface.
  /// A spot's: Eq. 5.1; a point light's: the sphere's (lightwave_sphere_vpl_count, or with the flux
  /// energy lightwave_sphere_sample_count); a sun's: the hemisphere layout's (thesis energy) or
  /// lightwave_parallel_sample_count (flux).
  int vpl_count() const;
  /// The light's own shadow maps (layers of the depth array before the VPLs'): 1, or a point light's 6 faces.
  int light_layers() const { return light_layers_; }
  /// GPU bytes this light's pipeline holds that another light's would share (the mesh buffers,
  /// the receivers' vertex buffers, textures and sum targets, the surface map and the indirect
  /// screen buffer): what sharing them saves per further light.
  std::uint64_t shared_bytes() const;
  /// Whether this pipeline and `other` draw from the same shared resources (tests).
  bool shares_resources_with(const lightwave_pipeline& other) const { return shared_ == other.shared_; }
  const lightwave_pipeline& light_pipeline(std::size_t k) const { return *light_pipelines_.at(k - 1); }
  /// The VPLs of the last build: thesis energy (vpls) or flux energy (flux_vpls, only those that
  /// carry light, in layout order; flux_vpl_layout_index gives each one's layout index).
  const std::vector<lightwave_vpl<float>>& vpls() const { return vpls_; }
  const std::vector<lightwave_flux_vpl<float>>& flux_vpls() const { return flux_vpls_; }
  const std::vector<int>& flux_vpl_layout_index() const { return flux_layout_index_; }
  /// The VPLs that carry light: vpls().size() or flux_vpls().size().
  int lit_vpl_count() const;
  /// Flux energy: the VPLs the receivers sum (lightwave_merge_ray_samples of flux_vpls()).
  const std::vector<lightwave_flux_vpl<float>>& receiver_vpls() const { return receiver_vpls_; }
  /// The VPLs the vertex stage sums: vpls().size() or receiver_vpls().size().
  int summed_vpl_count() const;
  const lightwave_layout_settings<float>& layout() const { return layout_; }
  const lightwave_cone_settings<float>& cone() const { return cone_; }
  /// Each vertex's indirect colour: the thesis energy's from the main pass's vertex stage at the
  /// scene's vertices (transform feedback), the flux energy's summed at the receivers' (the buffer
  /// the main pass reads, lightwave_capture.frag). The parity test compares it with the CPU sum.
  /// Rebuilds what a move invalidated first, untimed (pass times not yet collected are dropped).
  std::vector<glm::vec3> capture_vertex_indirect();
  /// The mesh whose vertices carry the indirect light: the scene's, or the flux energy's receivers.
  const mesh& drawn_mesh() const { return shared_->receiver_buffers ? shared_->receivers : scene_.geometry; }
  /// Flux energy: where each receiver vertex's indirect light is evaluated (lightwave_receiver_samples).
  const std::vector<glm::vec3>& receiver_samples() const { return shared_->receiver_samples; }
  const scene& source() const { return scene_; }
  const lightwave_settings& settings() const { return settings_; }
  /// The VPLs with shadow maps of the last build (accurate and integrated modes; the group
  /// fields are set for the importance variant only).
  const std::vector<lightwave_shadow_caster>& shadow_casters() const { return casters_; }

 private:
  /// What every light's pipeline draws with and that does not depend on the light: made by the
  /// first light's pipeline, shared by the further lights' (item 3 of issue 38: a further light
  /// costs its VPLs, its shadow maps and its image, not another copy of the scene).
  struct shared_resources {
    shared_resources(const mesh& geometry, const lightwave_settings& settings)
        : scene_mesh(geometry),
          target(settings.width, settings.height, {settings.format, settings.format, settings.format, settings.format, settings.format}, true) {}
    mesh_buffers scene_mesh;
    /// The image every light's main pass draws into: the first light's clears it and lays its
    /// depth, each further light's adds its light on that depth.
    framebuffer target;
    std::uint64_t mesh_bytes = 0;
    // Flux energy only.
    mesh receivers;                                       ///< lightwave_receivers
    std::optional<mesh_buffers> receiver_buffers;         ///< drawn, each light's indirect sums at attribute 3
    std::vector<glm::vec3> receiver_samples;              ///< lightwave_receiver_samples
    std::vector<texture_2d> receiver_textures;            ///< sample points, normals, albedos (lightwave_capture.frag)
    std::vector<framebuffer> receiver_sum_targets;        ///< a band per attachment, the passes' sums in turn
    std::size_t receiver_cells = 0;                       ///< texels of a band's grid
    std::optional<framebuffer> surfaces;                  ///< [position | 1], [normal], [albedo] as a light sees them
    std::vector<std::array<image, 3>> surface_texels;     ///< read back: one set per map (a point light's six faces)
    std::optional<framebuffer> indirect_target;           ///< the receivers' indirect light in screen space, one light at a time
  };
  /// A further light's pipeline: `first`'s shared resources, nothing of the scene uploaded again.
  lightwave_pipeline(const shader_library& shaders, const scene& source, const lightwave_settings& settings, std::shared_ptr<shared_resources> shared);
  /// The constructor's body after the shared resources are there.
  void set_up(const shader_library& shaders, const scene& source, bool make_shared);
  /// The light's own shadow maps' view-projections (1, or a point light's 6 faces).
  std::vector<glm::mat4> light_matrices() const;
  /// Where the VPL layouts start and look: a spot's position and axis, a point light's position
  /// and -y, a sun's virtual eye outside the scene's bounds and its direction.
  glm::vec3 light_origin() const;
  glm::vec3 light_axis() const;
  /// What the light sees through `view_projection` into surface_texels[slot].
  void draw_surfaces(const glm::mat4& view_projection, std::size_t slot);
  /// What the last set_light / set_camera invalidated: the VPLs (and the flux energy's indirect
  /// light), then the shadow maps.
  void rebuild();
  void build_vpls();
  /// The flux energy's VPLs: each ray of the cone looked up in a map of what the light sees.
  void build_flux_vpls();
  void build_shadow_maps();
  void draw_shadow_layers();
  void set_caster_uniforms(const lightwave_vpl_view& view);
  // The constructor's steps.
  shader_defines shader_defines_of() const;
  void load_main_programs(const shader_library& shaders, const shader_defines& defines);
  void set_up_receivers(const shader_library& shaders, const scene& source, bool make_shared);
  void set_up_vpl_blocks(const shader_library& shaders);
  void set_up_indirect_buffer(const shader_library& shaders, const scene& source, const shader_defines& defines, bool make_shared);
  void allocate_shadow_maps();
  /// Thesis energy: the vertex stage's indirect colour of every vertex of `vertices` into `buffer` (transform feedback).
  void capture_into(GLuint buffer, const mesh_buffers& vertices);
  /// Flux energy: every receiver's indirect light (lightwave_capture.frag) into indirect_buffer_.
  void sum_at_receivers();
  /// The scene's size and the light's frustum, for the maps and the VPLs.
  struct frame_geometry {
    float radius = 1.0f, near_plane = 0.01f, far_plane = 1.0f;
    glm::mat4 light_view{1.0f};
  };
  frame_geometry geometry() const;
  /// `first`: clear the image and draw; else add this light onto it (blending, depth equal to the
  /// first light's), its shadow factor (a ratio, not a light) left the first light's.
  void draw_main_pass(bool first);
  /// The accurate shadows' importance variant: casters grouped by the light they bring to points
  /// of the surface, and maps aimed at those points.
  bool casters_by_importance() const {
    return settings_.shadow_variant == lightwave_shadow_variant::importance && technique_.mode == lightwave_mode::accurate;
  }
  /// With the thesis energy those points are the ones the camera sees (its VPLs float off the
  /// surfaces, many below the floor), so the maps follow the camera; the flux energy's VPLs lie on
  /// the surfaces they light and its points cover the whole scene, so its maps depend on the light
  /// alone and a camera move redraws the main pass only, as the thesis's maps do (the shadows'
  /// distance to the one-bounce reference is the same either way on the study's scenes).
  bool casters_follow_camera() const { return (casters_by_importance() || integrated_by_importance()) && settings_.energy == lightwave_energy::thesis; }
  /// A point light's integrated shadows: its VPLs cover the sphere (floor, walls and ceiling), so
  /// the thesis's axis VPL and ring of the first hemisphere (the floor under the bulb, looking up)
  /// see little of what the rest light; its maps go to the medoids of the groups of equal light
  /// on the scene (lightwave_importance_casters, as the accurate shadows'), along their normals
  /// with the one field of view, and the in-between lookups run only between maps that look the
  /// same way (lightwave_integrated_pair_cos). A spot's and a sun's keep the thesis's ring.
  bool integrated_by_importance() const { return technique_.mode == lightwave_mode::integrated && kind_ == light_kind::point; }
  /// Whether the main pass draws a depth pre-pass first: the shadowed modes, whose fragments look
  /// up every indirect shadow map.
  bool depth_prepass() const { return technique_.mode >= lightwave_mode::accurate; }
  /// The camera's view-projection: the same matrix for the depth pre-pass and the main pass, whose
  /// depths must be equal.
  glm::mat4 camera_view_projection() const;
  void set_vertex_uniforms(const program& target) const;

  scene scene_;
  std::shared_ptr<shared_resources> shared_;
  light_kind kind_ = light_kind::spot;  ///< the first light's: the main pass's defines and the shadow maps' layout
  int light_layers_ = 1;                ///< its own shadow maps: 1, or a point light's 6 cube faces
  lightwave_settings settings_;
  lightwave_technique technique_;
  lightwave_layout_settings<float> layout_;
  lightwave_cone_settings<float> cone_;
  std::vector<lightwave_vpl<float>> vpls_;
  std::vector<lightwave_flux_vpl<float>> flux_vpls_;
  std::vector<lightwave_flux_vpl<float>> receiver_vpls_;
  std::vector<int> receiver_vpl_of_;  ///< for each flux VPL, its receiver VPL
  std::vector<int> flux_layout_index_;
  std::vector<glm::mat4> shadow_matrices_;
  std::vector<lightwave_shadow_caster> casters_;
  program receiver_sum_program_;
  int vpls_per_pass_ = 0;                       ///< flux energy: settings.vpls_per_pass, or a uniform block's worth
  std::size_t vpl_block_stride_ = 0;            ///< bytes from one pass's VPLs to the next's in vpl_block_buffer_
  gl_buffer vpl_block_buffer_;                  ///< flux energy: the receivers' VPLs, a uniform block per pass
  gl_vertex_array empty_vertex_array_;          ///< the full-screen triangle has no vertex data
  gl_buffer indirect_buffer_;                   ///< flux energy: this light's sums, the bands' grids of vec4 one after the other, receiver i's at i
  program depth_program_;
  program surface_program_;  ///< flux energy: what the light sees
  program main_program_;
  program capture_program_;
  program indirect_program_;                    ///< flux energy: the receivers' indirect light into indirect_target_
  gl_texture vpl_texture_;
  gl_texture shadow_maps_;
  gl_framebuffer shadow_framebuffer_;
  /// The first light's pipeline's, only when a material of the scene emits: drawn once onto the
  /// sum of every light's main pass.
  std::optional<emission_pass> emission_;
  glm::ivec2 shadow_size_{0};
  int shadow_layers_ = 1;  ///< allocated: 1 + the maps asked for; drawn: 1 + casters_ (fewer when fewer VPLs light the scene)
  pass_timer timer_;
  bool vpls_dirty_ = true;     ///< the VPLs (and the flux energy's indirect light) must be rebuilt
  bool shadows_dirty_ = true;  ///< the shadow maps must be rebuilt
  /// Flux energy: the VPLs must be summed at the receivers again (set with shadows_dirty_; implied
  /// by vpls_dirty_).
  bool sums_dirty_ = false;
  bool view_valid_ = false;    ///< the main pass matches the camera and the light
  int rebuilds_ = 0;
  int main_draws_ = 0;
  /// Lights 1 .. n - 1, each drawn by a pipeline on the scene with that light alone.
  std::vector<std::unique_ptr<lightwave_pipeline>> light_pipelines_;
  /// "light k: " before the pass names with several lights, else empty.
  std::string pass_prefix_;
};

}  // namespace vplkit

