// The final-gathering pipeline of [FG] for one dynamic object in a room (the built-in box or the
// user's scene): 1. a G-buffer of the camera view; per light of the scene (none: unlit):
// 2. the room's light eye depths from the light (a spot's or a sun's map, a point light's six
// faces: its shadows in the cube map and the view), 3. the cube map around the object's centre o
// (6 faces, radiance and distance, the object left out), the lights' radiances added,
// 4. the light's shadowed direct irradiance at the G-buffer's surfaces, added; then 5. each face
// averaged down to M x M, 6. (baseline only) the irradiance environment map, 7. shading: the
// room with its direct light, the object with direct light plus the indirect irradiance of the
// variant. Its CPU mirror shades from the read-back small cube map, G-buffer and direct light
// with the same kernels.
#pragma once

#include <string>
#include <vector>

#include <glm/glm.hpp>

#include <vplkit/final_gather.hpp>
#include <vplkit/irradiance.hpp>
#include <vplkit/gl/program.hpp>

#include "frontend/techniques/final_gather/final_gather_scene.hpp"
#include "frontend/techniques/final_gather/final_gather_settings.hpp"
#include "frontend/gl/pass_timer.hpp"
#include "frontend/scene_gl/emission_pass.hpp"
#include "frontend/scene_gl/mesh_buffers.hpp"
#include "frontend/gl/render_target.hpp"
#include "frontend/scene/camera.hpp"
#include "frontend/scene/scene.hpp"
#include "frontend/techniques/pipeline.hpp"

namespace vplkit {

struct final_gather_frame {
  image radiance;  ///< the final image
  image indirect;  ///< the object's indirect irradiance
  std::vector<pass_time> pass_times;
};

/// The buffers the CPU mirror reads.
struct final_gather_buffers {
  image small_cube;       ///< 6 M x M: [radiance | distance]
  image environment_map;  ///< 6 K x K: [irradiance | 1] (baseline only, else empty)
  image gbuffer[3];       ///< [position | kind], [normal | -], [albedo | -]
  image direct;           ///< [the lights' direct irradiance, shadowed by the room | 0]
};

/// The side of a light's depth map of the room (final_gather_shadow.glsl; each of a point
/// light's six faces): texels of about 1/1000 of the room at the distances a room's spot lights
/// it from, which the slope-scaled bias of a few footprints keeps free of acne without losing the
/// contact shadows of furniture.
inline constexpr int final_gather_light_depth_size = 1024;

class final_gather_pipeline final : public pipeline {
 public:
  final_gather_pipeline(const shader_library& shaders, const final_gather_scene& source, const final_gather_settings& settings);
  /// draw(), then the images read back.
  final_gather_frame render();
  /// Every pass without reading anything back (a frame as the paper times it).
  void draw() override;
  /// The passes the moves since the last frame invalidated: the cube map (and the averaged and
  /// convolved maps) after set_light or set_object_position, the G-buffer and the shading after
  /// any move; nothing when nothing moved. The viewer draws its frames this way.
  void draw_changed() override;
  void set_camera(const camera& view) override;
  /// Light `index` of the scene (any kind); throws vplkit::error for an invalid light or index.
  void set_light(std::size_t index, const scene_light& light) override;
  camera current_camera() const override { return scene_.view; }
  std::vector<scene_light> current_lights() const override;
  /// In place when only min-distance changes (final_gather_pipeline.cpp says why the others need a
  /// new pipeline): the next frame redraws the cube map and the view. The object's position is a
  /// pose (set_object_position), as the camera and the light are, and is not compared.
  bool apply_settings(const technique_settings& settings) override;
  bool has_object() const override { return true; }
  glm::vec3 object_position() const override { return scene_.reference_point; }
  /// Moves the object (and its reference point) so that its centre is at `centre`. The cube map
  /// is checked on the next frame: an object reaching into a wall or out of the room throws there.
  void set_object_position(glm::vec3 centre) override;
  /// How many times the cube map was drawn, and the G-buffer and shading.
  int cube_draws() const { return cube_draws_; }
  int view_draws() const override { return view_draws_; }
  std::string draw_counts() const override;
  std::string describe() const override;
  std::string scene_name() const override { return scene_.name; }
  /// The pass times since the last render() or collect_pass_times().
  std::vector<pass_time> collect_pass_times() override { return timer_.collect(); }
  /// The last frame's radiance and the object's indirect irradiance (black elsewhere).
  const texture_2d& output() const override { return output_.colour(0); }
  const texture_2d& indirect_output() const override { return output_.colour(1); }
  /// The room's and the object's direct irradiance: every light's, after its own shadow map.
  const texture_2d& direct_output() const override { return output_.colour(2); }
  bool has_indirect() const override { return true; }
  final_gather_buffers read_buffers() const;
  const final_gather_scene& source() const { return scene_; }
  const final_gather_settings& settings() const { return settings_; }
  final_gather_variant variant() const { return technique_.variant; }

 private:
  final_gather_scene scene_;
  final_gather_settings settings_;
  final_gather_technique technique_;
  mesh_buffers room_;
  mesh_buffers object_;
  program light_depth_program_;
  program cube_program_;
  program downsample_program_;
  program environment_program_;
  program gbuffer_program_;
  program shade_program_;
  program direct_program_;
  framebuffer light_depth_;  ///< one tile per face of the light drawn (six while a point light is there)
  framebuffer faces_;
  framebuffer small_cube_;
  framebuffer environment_;
  framebuffer gbuffer_;
  framebuffer direct_;
  framebuffer output_;
  gl_vertex_array empty_vertex_array_;
  std::optional<emission_pass> emission_;  ///< only when a material of the room or the object emits
  pass_timer timer_;
  bool cube_valid_ = false;
  bool view_valid_ = false;
  int cube_draws_ = 0;
  int view_draws_ = 0;

  void set_pose_uniforms();
  glm::mat4 camera_view_projection() const;
  void draw_passes(bool with_cube);
  /// Light `light`'s uniforms (the faces' and the direct light's) and its depth map(s).
  void draw_light_depth(std::size_t light);
  /// The cube map's faces lit by light `light` (SIZE_MAX: none, black), added to the earlier lights' unless `first`.
  void draw_cube_faces(std::size_t light, bool first, float room_size);
  void draw_direct(std::size_t light);
  void finish_cube_map();
  std::string pass_name(const char* pass, std::size_t light) const;
};

}  // namespace vplkit
