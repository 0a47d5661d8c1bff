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
#pragma once

#include <cstdint>
#include <array>
#include <optional>
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

/// What the VPLs carry. thesis: strength 1 - attenuation, no distance falloff, on hemispheres
/// in space (Eq. 4.1, 4.2, 4.5: the Tables 5.x); flux: the flux the light brings to each ray's patch
/// of its cone, reflected where the ray meets the scene, with a diffuse bounce's falloff.
enum class lightwave_energy { thesis = 0, flux = 1 };

/// The side of the square map of what the spot light sees (position, normal, albedo) in which the
/// flux layout looks its rays up: under half a degree a texel for a cone 120 degrees across, finer than
/// the layout's samples (the VPL sits where its ray meets the texel's plane, not at the texel).
constexpr int lightwave_surface_map_size = 256;

/// A grid of width x rows >= `receivers` texels, receiver i at texel (i % width, i / width), for
/// the fragment pass that sums the flux energy's VPLs: rows a multiple of 4 (a software
/// rasteriser shades 4x4 blocks; a 2-row grid left half of each block's lanes idle, +40 % on the
/// boxes) and as few as rows of at most 1024 allow; the width a multiple of 4 too, wider than 1024
/// where the rows would pass `max_side` (the caller checks the width against the GL's largest
/// texture).
glm::ivec2 lightwave_receiver_grid(std::size_t receivers, int max_side);

/// The grid of one band of lightwave_capture.frag, which sums lightwave_sum_receivers receivers
/// per fragment: lightwave_receiver_grid of ceil(receivers / lightwave_sum_receivers) texels with
/// at most max_texture_side / lightwave_sum_receivers rows, so that the bands stacked hold every
/// receiver in one texture of at most max_texture_side rows.
glm::ivec2 lightwave_sum_grid(std::size_t receivers, int max_texture_side);

/// The passes (uniform blocks) that sum `vpls` VPLs per_pass at a time: at least one.
int lightwave_vpl_pass_count(std::size_t vpls, int per_pass);

/// The receivers' VPLs as the uniform blocks of lightwave_capture.frag's passes: per_pass VPLs a
/// block (the last one's tail zero), three vec4 each, [position | radius], [normal | 0], [flux | 0];
/// block k at byte k x stride_bytes (a multiple of 16 and of the GL's offset alignment, at least
/// 48 x per_pass). At least one block.
std::vector<glm::vec4> lightwave_vpl_blocks(const std::vector<lightwave_flux_vpl<float>>& vpls, int per_pass, std::size_t stride_bytes);

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

/// Empty when usable, else the reason: the table's ranges, the VPL count the main pass can loop
/// over, the shadow maps the layout allows, and the kernels' settings.
std::string validate(const lightwave_settings& settings);

/// The mesh whose vertices the flux energy's indirect light is summed at: `geometry` subdivided
/// (subdivide_long_edges) until no edge exceeds settings.receiver_spacing times its bounding
/// radius, the bound grown by half until at most settings.receiver_triangles triangles result.
/// The thesis sums Eq. 4.5 at the scene's own vertices, which a diffuse bounce's falloff cannot
/// afford: a wall's corner vertices see the floor that lights it edge-on (docs/lightwave-shadows.md).
mesh lightwave_receivers(const mesh& geometry, const lightwave_settings& settings);

/// Where the flux energy evaluates each vertex's indirect light: the mean of the centroids of the
/// triangles that use the vertex, moved into the vertex's tangent plane. Inside a surface that is
/// the vertex, near enough; on its border it lies inside the surface, a third of a triangle in:
/// a wall's bottom vertex sits in the plane of the floor that lights the wall and gets none of its
/// light (the floor is seen edge-on), while the wall just above gets the most, and interpolating
/// from the corner would darken the whole band of triangles along it.
std::vector<glm::vec3> lightwave_receiver_samples(const mesh& receivers);

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

/// One accurate indirect shadow map of the importance variant: the group of VPLs it stands for
/// and the VPL it is rendered from.
struct lightwave_shadow_caster {
  int vpl = 0;  ///< the VPL the map is rendered from (an index into the pipeline's VPLs)
  /// The group as one light, for the share of a fragment's indirect light the map stands for:
  /// its members' power-weighted position and normal, their spread (the RMS distance from that
  /// position, with their own patch radii), and their total power (the channel mean of the flux,
  /// or the thesis's 1 - attenuation).
  glm::vec3 position{0.0f};
  glm::vec3 normal{0.0f, 1.0f, 0.0f};
  float radius = 0.0f;
  float power = 0.0f;
  std::vector<int> members;  ///< the group's VPLs (indices into the pipeline's VPLs)
};

/// What lightwave_cluster_casters needs of a VPL.
struct lightwave_cluster_vpl {
  glm::vec3 position{0.0f};
  glm::vec3 normal{0.0f, 1.0f, 0.0f};
  float importance = 0.0f;  ///< its light on the visible scene; 0: no group
  float power = 0.0f;
  float radius = 0.0f;
};

/// Splits the VPLs of importance > 0 into `count` groups (fewer when fewer VPLs light anything),
/// each compact and of about equal importance: a k-d split at the importance median along the
/// widest extent of position and normal (the normal scaled by `normal_scale`, scene units),
/// recursively. Each group's map is rendered from its medoid: the member nearest the group's
/// importance-weighted mean position and normal, the one point whose view stands best for the
/// group's. Deterministic: no seed, so the shadows do not depend on one.
std::vector<lightwave_shadow_caster> lightwave_cluster_casters(const std::vector<lightwave_cluster_vpl>& vpls, int count, float normal_scale);

/// The flux VPLs the receivers sum: the samples of one ray of the layout (layout index modulo
/// `rays`) that met one plane (unit normals within 1e-3 of each other, positions within
/// `plane_tolerance` of the first's plane) merged into one VPL: their flux summed, at their
/// flux-weighted mean position, with the radius of their patches' total area (sqrt of the sum
/// of the radii squared). Beyond a few patch radii the merged VPL gives the receivers the light
/// of its samples (the same flux from the same patch of surface); closer, the exitance of their
/// joint patch. Samples of a ray that met different surfaces stay apart. The order: by the first
/// sample's place in `vpls`. The capture sums per_ray times fewer VPLs. `merged_index`, when
/// given, receives for each of `vpls` the merged VPL it went into.
std::vector<lightwave_flux_vpl<float>> lightwave_merge_ray_samples(const std::vector<lightwave_flux_vpl<float>>& vpls, const std::vector<int>& layout_index,
                                                                   int rays, float plane_tolerance, std::vector<int>* merged_index = nullptr);

/// The view-projection of a shadow map from `eye` that holds the points of weight > 0: looking at
/// their weighted mean direction, with the field of view of the farthest of them plus a margin
/// (at most 160 degrees; points beyond do not vote). Looks along `fallback_direction` with
/// `fallback_fov_degrees` when no point has weight.
glm::mat4 lightwave_aimed_shadow_matrix(const glm::vec3& eye, const glm::vec3& fallback_direction, const std::vector<lightwave_receiver_point>& points,
                                        const std::vector<float>& weights, float near_plane, float far_plane, float aspect, float fallback_fov_degrees);

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
  /// (and after set_camera for the importance variant with the thesis energy, whose casters follow
  /// the camera; the flux energy's do not), the main
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
  /// The layout's VPLs (Eq. 5.1); the flux energy keeps those whose ray met a lit surface.
  int vpl_count() const { return lightwave_vpl_count(settings_.angle_deg, settings_.per_ray); }
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
  const mesh& drawn_mesh() const { return receiver_buffers_ ? receivers_ : scene_.geometry; }
  /// Flux energy: where each receiver vertex's indirect light is evaluated (lightwave_receiver_samples).
  const std::vector<glm::vec3>& receiver_samples() const { return receiver_samples_; }
  const scene& source() const { return scene_; }
  const lightwave_settings& settings() const { return settings_; }
  /// The VPLs with shadow maps of the last build (accurate and integrated modes; the group
  /// fields are set for the importance variant only).
  const std::vector<lightwave_shadow_caster>& shadow_casters() const { return casters_; }

 private:
  /// What the last set_light / set_camera invalidated: the VPLs (and the flux energy's indirect
  /// light), then the shadow maps.
  void rebuild();
  void build_vpls();
  /// The flux energy's VPLs: each ray of the cone looked up in a map of what the light sees.
  void build_flux_vpls(const glm::mat4& light_view_projection);
  void build_shadow_maps();
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
  void draw_main_pass();
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
  bool casters_follow_camera() const { return casters_by_importance() && settings_.energy == lightwave_energy::thesis; }
  /// Whether the main pass draws a depth pre-pass first: the shadowed modes, whose fragments look
  /// up every indirect shadow map.
  bool depth_prepass() const { return technique_.mode >= lightwave_mode::accurate; }
  /// The camera's view-projection: the same matrix for the depth pre-pass and the main pass, whose
  /// depths must be equal.
  glm::mat4 camera_view_projection() const;
  void set_vertex_uniforms(const program& target) const;

  scene scene_;
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
  mesh_buffers mesh_;
  mesh receivers_;                              ///< flux energy: lightwave_receivers
  std::optional<mesh_buffers> receiver_buffers_;  ///< flux energy: drawn, with the indirect at attribute 3
  std::vector<glm::vec3> receiver_samples_;     ///< flux energy: lightwave_receiver_samples
  std::vector<texture_2d> receiver_textures_;   ///< flux energy: sample points, normals, albedos (lightwave_capture.frag)
  std::vector<framebuffer> receiver_sum_targets_;  ///< flux energy: a band per attachment, the passes' sums in turn
  program receiver_sum_program_;
  int vpls_per_pass_ = 0;                       ///< flux energy: settings.vpls_per_pass, or a uniform block's worth
  std::size_t vpl_block_stride_ = 0;            ///< bytes from one pass's VPLs to the next's in vpl_block_buffer_
  gl_buffer vpl_block_buffer_;                  ///< flux energy: the receivers' VPLs, a uniform block per pass
  gl_vertex_array empty_vertex_array_;          ///< the full-screen triangle has no vertex data
  gl_buffer indirect_buffer_;                   ///< flux energy: the bands' grids of vec4 one after the other, receiver i's at i
  program depth_program_;
  program surface_program_;  ///< flux energy: what the light sees
  std::array<image, 3> surface_texels_;  ///< flux energy: its positions, normals and albedos read back
  program main_program_;
  program capture_program_;
  program indirect_program_;                    ///< flux energy: the receivers' indirect light into indirect_target_
  std::optional<framebuffer> indirect_target_;
  gl_texture vpl_texture_;
  gl_texture shadow_maps_;
  gl_framebuffer shadow_framebuffer_;
  glm::ivec2 shadow_size_{0};
  int shadow_layers_ = 1;  ///< allocated: 1 + the maps asked for; drawn: 1 + casters_ (fewer when fewer VPLs light the scene)
  framebuffer target_;
  std::optional<framebuffer> surfaces_;  ///< flux energy: [position | 1], [normal], [albedo] as the light sees them
  pass_timer timer_;
  bool vpls_dirty_ = true;     ///< the VPLs (and the flux energy's indirect light) must be rebuilt
  bool shadows_dirty_ = true;  ///< the shadow maps must be rebuilt
  bool view_valid_ = false;    ///< the main pass matches the camera and the light
  int rebuilds_ = 0;
  int main_draws_ = 0;
};

}  // namespace vplkit
