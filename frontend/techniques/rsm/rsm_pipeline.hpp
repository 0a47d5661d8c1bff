// The four-pass deferred pipeline of [RSMV] (chapter 4): 1. RSM generation, 2. G-buffer
// generation (with the shadow density of Alg. 4), 3. RSM sampling (the gather, at a reduced
// resolution), 4. post processing (bilateral upsampling and blur, direct + indirect). With
// coverage (vplkit/rsm_coverage.hpp), a pass after the RSM reduces it to the coarse lights that the
// gather adds for the receivers its pattern cannot reach.
// Techniques: direct light only, the original RSM (disk pattern, 400 samples), and the radial
// pattern without visibility or with Alg. 2, 3 or 6.
#pragma once

#include <array>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include <vplkit/bilateral.hpp>
#include <vplkit/irradiance.hpp>
#include <vplkit/rsm_coarse_visibility.hpp>
#include <vplkit/rsm_gather.hpp>
#include <vplkit/rsm_packing.hpp>
#include <vplkit/shadow.hpp>
#include <vplkit/temporal_accumulation.hpp>
#include <vplkit/voxel_visibility.hpp>
#include <vplkit/gl/program.hpp>

#include "frontend/techniques/rsm/rsm_settings.hpp"
#include "frontend/gl/pass_timer.hpp"
#include "frontend/scene_gl/emission_pass.hpp"
#include "frontend/scene_gl/mesh_buffers.hpp"
#include "frontend/gl/render_target.hpp"
#include "frontend/scene/camera.hpp"
#include "frontend/techniques/pipeline.hpp"

namespace vplkit {

/// Light-space matrices of the RSM: perspective for a spot light (a square frustum around the
/// outer cone), orthographic for a directional light (around the scene's bounds).
struct light_frustum {
  glm::mat4 view{1.0f};
  glm::mat4 view_projection{1.0f};
  float tan_half_fov = 0.0f;  ///< spot light
  float half_extent = 0.0f;   ///< directional light: half the side of the orthographic frustum
  float texel_area = 0.0f;    ///< directional light: area one RSM texel covers across the light
};
/// For light `light` of `source`; a point light's face `face` (0..5, vplkit/cube_map.hpp): a
/// 90-degree perspective view along the face's axis (tan_half_fov = 1).
light_frustum make_light_frustum(const scene& source, int rsm_size, std::size_t light = 0, int face = 0);
/// The same for light `light` of `source` around a mesh whose bounds are `box` (source.geometry is not read).
light_frustum make_light_frustum(const scene& source, const bounding_box& box, int rsm_size, std::size_t light = 0, int face = 0);

/// The constants of a frame that the GL passes and their CPU mirror share (one derivation).
struct rsm_frame_constants {
  rsm_technique technique;
  rsm_gather_settings<float> gather;
  light_frustum light;
  rsm_unprojection<float> unprojection;  ///< the packed RSM's centre rays (from light)
  glm::mat4 light_view_inverse{1.0f};    ///< rsm-voxel: the light's eye space back to the world (the grid's space)
  voxel_march_settings<float> voxel_march;  ///< rsm-voxel: the march's offsets
  scene_light primary;
  std::size_t light_index = 0;  ///< which of the scene's lights this view draws
  int face = -1;                ///< a point light's cube face (0..5, vplkit/cube_map.hpp); -1 for a spot or a sun
  glm::mat4 camera_view{1.0f};
  glm::mat4 camera_view_projection{1.0f};
  shadow_density_settings<float> shadow;
  bilateral_settings<float> bilateral;
  post_filter filter = post_filter::full;
  temporal_settings<float> temporal;
  glm::ivec2 image_size{0};
  glm::ivec2 indirect_size{0};
  int indirect_divisor = 2;
};
/// The constants of the frame's passes for light `light` of `source` (each light view is drawn with
/// its own); `face`: which face of a point light (0..5), unused for the other kinds.
rsm_frame_constants make_frame_constants(const scene& source, const rsm_pipeline_settings& settings, std::size_t light = 0, int face = 0);
/// The same for the camera and light `light` of `source` around a mesh of `triangles` triangles whose
/// bounds are `box` (source.geometry is not read: the pipeline keeps these, not a copy of the mesh).
rsm_frame_constants make_frame_constants(const scene& source, const bounding_box& box, std::size_t triangles, const rsm_pipeline_settings& settings,
                                         std::size_t light = 0, int face = 0);
/// The light views of `source` in order: a spot or a sun is one view, a point light six (its cube
/// faces 0..5). Throws for a scene without lights or with more than max_scene_lights.
std::vector<rsm_frame_constants> make_view_constants(const scene& source, const bounding_box& box, std::size_t triangles,
                                                     const rsm_pipeline_settings& settings);

/// A point light's cube for the coarse lights' visibility of one of its views (gather.frag's
/// cube_frames and rsm_face_depths' layers): the rotation from the gathering face's eye space to
/// the cube's axes, and which view draws each face.
struct coarse_cube_views {
  cube_depth_frames<float> frames;
  std::array<std::size_t, 6> view_of_face{};
};
/// The cube of view `view` of `views` when its gather judges the coverage's coarse lights against
/// the light's six depth maps: coverage on, any technique but rsm-voxel (judges_coarse_lights_by_segment),
/// a point light's face with all six faces among `views`. Nothing otherwise (a spot's or a sun's
/// coarse lights stay unoccluded: its one map does not see the segment outside its frustum).
std::optional<coarse_cube_views> coarse_cube_of(const std::vector<rsm_frame_constants>& views, std::size_t view);

/// The RSM as the GPU stores it: one packed texel per pixel light (vplkit/rsm_packing.hpp), rows
/// bottom-up; all bits 0 where nothing was rendered.
struct packed_rsm {
  int width = 0;
  int height = 0;
  std::vector<glm::uvec4> texels;
};

/// The intermediate buffers of a frame, read back for the CPU mirror and for tests.
struct rsm_pass_buffers {
  packed_rsm rsm;    ///< the RSM (RGBA32UI)
  image coarse[3];   ///< the coverage's coarse lights: [position | extent], [normal | 0], [flux | 0] (empty without coverage)
  image gbuffer[3];  ///< [position | depth], [albedo | shadow density], [normal | -]
  image indirect;    ///< [irradiance | depth] (empty for direct light only)
  image accumulated; ///< after temporal accumulation: [irradiance | depth] (empty unless the last frame was render_next's with a history)
  image history;     ///< the accumulated buffer of the frame before, which pass 3b read (empty with `accumulated`)
  image blurred_x;   ///< the separable filter's x pass (empty for the full filter)
  std::shared_ptr<const voxel_grid> voxels;  ///< rsm-voxel: the grid the gather marched (null otherwise)
};

struct rsm_frame {
  image radiance;  ///< the final image
  image indirect;  ///< filtered indirect irradiance at full resolution
  std::vector<pass_time> pass_times;
};

/// Several lights (spot, directional and point, any mix, up to max_scene_lights), each one or more
/// light views (make_view_constants): each view has its own RSM (redrawn only when its light
/// moves), coverage lights, G-buffer shadow density and gather; the post pass of each adds its
/// direct and filtered indirect light to the output, so the image of several lights is the sum of
/// the images of each. A point light's face adds the direct light of the receivers whose
/// direction from the light falls in it (cube_face_of), shadowed by its RSM's depth. Temporal
/// accumulation draws one view.
class rsm_pipeline final : public pipeline {
 public:
  /// Validates, loads the programs and uploads the scene. Throws vplkit::error with the reason.
  rsm_pipeline(const shader_library& shaders, const scene& source, const rsm_pipeline_settings& settings);
  /// draw(), then the images read back.
  rsm_frame render();
  /// The next frame of a sequence (render --poses): with temporal accumulation (settings.temporal.blend
  /// < 1) the gather's pattern turns (seed k for the k-th frame since the last render()) and its
  /// output is blended with the previous frame's, reprojected (pass 3b); otherwise render(). The
  /// first frame after render() or construction has no history.
  rsm_frame render_next();
  /// render_next() without reading anything back (what `vplkit render --poses` draws through
  /// the pipeline interface).
  void draw_next() override;
  /// Whether render_next accumulates (settings.temporal.blend < 1 and a technique that gathers).
  bool accumulates() const;
  /// What pass 3b of the last frame read besides the buffers (read_buffers): whether it had a
  /// history, and the camera of the frame the history was rendered with.
  struct temporal_inputs {
    bool history_valid = false;
    glm::mat4 previous_view{1.0f};
    glm::mat4 previous_view_projection{1.0f};
  };
  const temporal_inputs& last_temporal_inputs() const { return last_temporal_inputs_; }
  /// The four passes without reading anything back (a frame as Table 5.3 times it: the light
  /// may have moved, so the RSM is drawn as well).
  void draw() override;
  /// The passes that the moves since the last frame invalidated: after set_camera only the
  /// G-buffer, the gather and the post filter; after set_light the RSM as well; nothing when
  /// nothing moved. The viewer draws its frames this way.
  void draw_changed() override;
  /// Moves the camera (the RSM stays valid).
  void set_camera(const camera& view) override;
  /// Moves the light. Throws vplkit::error for an invalid light or one of another kind than the
  /// scene's (the programs are built for a spot or a directional light).
  void set_light(std::size_t index, const scene_light& light) override;
  /// In place when only uniforms change: the same technique, slots, coverage blocks, filter,
  /// temporal accumulation on or off, sizes and format; the next draw_changed() redraws the
  /// G-buffer to the post filter (the RSM does not depend on what may change in place).
  bool apply_settings(const technique_settings& settings) override;
  camera current_camera() const override { return scene_.view; }
  std::vector<scene_light> current_lights() const override { return scene_.lights; }
  /// How many times the RSM has been drawn.
  int rsm_draws() const { return rsm_draws_; }
  /// How many times the camera-dependent passes (G-buffer to post filter) have been drawn.
  int view_draws() const override { return view_draws_; }
  std::string draw_counts() const override;
  std::string describe() const override;
  std::string scene_name() const override { return scene_.name; }
  /// The pass times since the last render() or collect_pass_times().
  std::vector<pass_time> collect_pass_times() override { return timer_.collect(); }
  const rsm_pipeline_settings& settings() const { return settings_; }
  /// draw() timed by wall clock between two glFinish calls: the frame's cost on any renderer
  /// (llvmpipe's timer queries measure only the span of its last rasterizer tiles).
  double draw_wall_clock_ms();
  /// The constants light view `view` is drawn with (make_view_constants' order).
  const rsm_frame_constants& constants(std::size_t view = 0) const { return views_.at(view); }
  std::size_t view_count() const { return views_.size(); }
  /// rsm-voxel: the scene's occupancy grid (null for the other techniques) and the wall-clock ms
  /// its CPU build took when the pipeline was made (reported apart from the frame's cost).
  const std::shared_ptr<const voxel_grid>& voxels() const { return voxels_; }
  double voxel_build_ms() const { return voxel_build_ms_; }
  /// The intermediate buffers of the last frame for light view `view`: its RSM, coarse lights and
  /// gather; the G-buffer is the last view's (its positions and normals are every view's, its
  /// shadow density the last view's).
  rsm_pass_buffers read_buffers(std::size_t view = 0) const;
  /// The cube whose depth maps view `view`'s gather reads for the coarse lights (coarse_cube_of).
  std::optional<coarse_cube_views> coarse_cube(std::size_t view) const { return coarse_cube_of(views_, view); }
  /// The final radiance texture of the last frame.
  const texture_2d& output() const override { return post_target_.colour(0); }
  /// The filtered indirect irradiance of the last frame at the image's size (black for direct light).
  const texture_2d& indirect_output() const override { return post_target_.colour(1); }
  /// The shadowed direct irradiance of the last frame (every view's, summed by the post pass).
  const texture_2d& direct_output() const override { return post_target_.colour(2); }
  bool has_indirect() const override { return constants_.technique.indirect; }
  /// The gather's output at the indirect buffer's receivers, before the post filter (summed over the light views).
  std::optional<image> raw_indirect() const override;

 private:
  void set_pose_uniforms();
  /// The uniforms that come from the settings (the constructor's, and apply_settings's).
  void set_settings_uniforms();
  /// The camera and light of the next frame; leaves both as they were when the frame constants
  /// cannot be made.
  void move_to(const camera& view, const std::vector<scene_light>& lights);
  /// Every light's passes; all_rsms: every RSM, else only those of the lights that moved.
  void draw_passes(bool all_rsms, bool accumulate = false);
  /// Makes view `view`'s constants the current ones and sets the programs' uniforms from them.
  void bind_view(std::size_t view);
  // The constructor's and draw_passes' steps.
  void load_programs(const shader_library& shaders);
  void draw_rsm(std::size_t view);
  void draw_gbuffer(std::size_t view);
  void draw_gather(std::size_t view);
  const framebuffer& accumulate_history();
  /// The post pass of view `view`, added to the output of the views before it.
  void draw_post(const framebuffer& filter_input, std::size_t view);
  /// A pass's timer name: with several views it carries the light (and a point light's face).
  std::string pass_name(const char* pass, std::size_t view) const;
  // The programs that depend on the light's kind, indexed by light_kind (the current view's).
  const program& rsm_program() const { return rsm_programs_[static_cast<std::size_t>(constants_.primary.kind)]; }
  const program& post_program() const { return post_programs_[static_cast<std::size_t>(constants_.primary.kind)]; }
  /// The gather's pattern seeds for frame `frame` of a sequence (0: the settings' own).
  void set_pattern_frame(std::uint32_t frame);

  /// The scene's name, camera and light; not its mesh, which lives on the GPU (mesh_) and in the
  /// caller's scene: a copy here doubled the memory a large mesh takes.
  scene scene_;
  bounding_box bounds_;
  std::size_t triangles_ = 0;
  rsm_pipeline_settings settings_;
  std::vector<rsm_frame_constants> views_;  ///< one per light view
  rsm_frame_constants constants_;           ///< the view being drawn (bind_view)
  mesh_buffers mesh_;
  program rsm_programs_[3];
  program gbuffer_program_;
  program coarse_program_;
  program gather_program_;
  program temporal_program_;
  program blur_x_program_;
  program blur_y_program_;  ///< the y pass for 2 x 2 pixels at once (quad_blur; else post.frag runs it per pixel)
  program post_programs_[3];
  std::shared_ptr<const voxel_grid> voxels_;
  double voxel_build_ms_ = 0.0;
  std::optional<texture_2d> voxel_texture_;
  std::vector<framebuffer> rsm_targets_;       ///< one per view
  /// Per light index: a point light's six faces' eye-space depths, one R32UI layer per face (each
  /// face's RSM's first word, copied after the face is drawn), which gather.frag's coarse
  /// visibility reads in one fetch where six samplers needed an if chain that llvmpipe runs for
  /// every lane (docs/scenes.md, "Cost"); an empty texture for the lights whose gathers do not
  /// judge their coarse lights (coarse_cube_of).
  std::vector<gl_texture> cube_depths_;
  std::vector<framebuffer> coarse_targets_;    ///< one per view (1 x 1 without coverage)
  framebuffer gbuffer_target_;
  std::vector<framebuffer> indirect_targets_;  ///< one per view
  framebuffer history_targets_[2];  ///< temporal accumulation, ping-pong (1 x 1 when the pipeline does not accumulate)
  framebuffer blur_x_target_;
  framebuffer blur_y_target_;  ///< blur_y.frag's red, green and blue planes (1 x 1 unless quad_blur)
  framebuffer post_target_;
  gl_vertex_array empty_vertex_array_;
  std::optional<emission_pass> emission_;  ///< only when a material of the scene emits
  pass_timer timer_;
  std::vector<char> rsm_valid_;  ///< per view: its RSM matches its light
  bool view_valid_ = false;  ///< the G-buffer to post filter match the camera and the RSM
  int rsm_draws_ = 0;
  int view_draws_ = 0;
  // Temporal accumulation: the frame index in the sequence, the target the last frame wrote, whether
  // it holds a history, and the camera it was seen with.
  std::uint32_t sequence_frame_ = 0;
  std::uint32_t pattern_frame_ = 0;  ///< the seed frame of the gather's pattern (set_pattern_frame)
  int history_index_ = 0;
  bool history_valid_ = false;
  bool last_accumulated_ = false;
  glm::mat4 history_view_{1.0f};
  glm::mat4 history_view_projection_{1.0f};
  temporal_inputs last_temporal_inputs_;
};

}  // namespace vplkit
