// One technique in the viewer: its pipeline (any family's, frontend/techniques/pipeline.hpp), the
// poses of its camera and light (and of the object, for final gathering), the layers it can show,
// and its settings as live controls made from their descriptions (frontend/core/setting.hpp),
// with the ranges and refusals of the command line. A move goes to the pipeline, which redraws
// only what the move invalidated (draw_changed). A changed setting that only changes uniforms is
// applied in place (pipeline::apply_settings: no program is compiled, the next frame redraws);
// one that changes a define or a buffer's size builds a new pipeline.
#pragma once

#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <vplkit/gl/program.hpp>

#include "frontend/core/setting.hpp"
#include "frontend/gl/pass_timer.hpp"
#include "frontend/gl/render_target.hpp"
#include "frontend/scene/pose.hpp"
#include "frontend/techniques/registry.hpp"

namespace vplkit {

/// What the window shows.
enum class view_layer {
  image,                  ///< the final image
  indirect,               ///< the indirect light alone (the -indirect.pfm of `vplkit render`), auto-exposed
  visibility_difference,  ///< RSM with visibility: |L(no visibility) - L(technique)| of the indirect light, 8x (Fig. 5.1c)
  indirect_shadow,        ///< Light Wave accurate/integrated: the indirect shadow factor as grey
};
const char* describe(view_layer layer);

/// How present.frag shows a layer: its textures and encoding.
struct layer_display {
  const texture_2d* image = nullptr;
  const texture_2d* other = nullptr;  ///< the second operand of the difference
  int mode = 0;                        ///< present.frag's mode
  bool auto_exposure = false;          ///< exposure from percentile_exposure of the indirect light
  float scale = 1.0f;                  ///< times the exposure (8 for the difference)
};

/// One family's state in the viewer, kept while another family is shown: its settings (the last
/// technique of the family), its scene (for a family that draws one) and the poses it was left at.
struct viewer_family {
  std::unique_ptr<technique_settings> settings;
  std::optional<scene> source;
  std::optional<camera> view;
  std::optional<std::vector<scene_light>> lights;
  /// The file's index of each of the scene's lights (vplkit view --lights 0,2), for the command
  /// text (light_arguments); absent: every light of the file, in order.
  std::optional<std::vector<std::size_t>> file_lights;
  std::optional<glm::vec3> object;

  viewer_family() = default;
  viewer_family(const viewer_family& other);
  viewer_family& operator=(const viewer_family& other);
  viewer_family(viewer_family&&) = default;
  viewer_family& operator=(viewer_family&&) = default;
};

/// Every family the viewer can switch between, by family name.
struct viewer_scenes {
  std::map<std::string, viewer_family> families;
  /// The family of `technique`. Throws vplkit::error when the viewer has none of its settings.
  viewer_family& of(const std::string& technique);
  const viewer_family& of(const std::string& technique) const;
};

class technique_view {
 public:
  /// The pipeline of `technique` with its family's settings and scene from `scenes`, at the poses
  /// stored there. Throws vplkit::error when the pipeline refuses them.
  technique_view(const shader_library& shaders, const viewer_scenes& scenes, const std::string& technique);
  std::string technique() const { return settings_->technique(); }
  /// Draws what the moves since the last frame invalidated; true when anything was drawn.
  bool draw();
  std::vector<view_layer> layers() const;
  layer_display display(view_layer layer);
  /// The indirect light of the last frame (what `vplkit render` writes as -indirect.pfm).
  image read_indirect() const { return pipeline_->indirect_output().read_image(); }
  std::vector<pass_time> collect_pass_times();
  pose camera_pose() const;
  /// The selected light's pose; throws vplkit::error when the scene has no light (light_count() 0).
  pose light_pose() const;
  /// The scene's lights: how many, which kind each, and which one the light controls move (0 at first).
  std::size_t light_count() const;
  light_kind light_kind_of(std::size_t index) const;
  std::size_t selected_light_index() const { return selected_light_; }
  /// Throws vplkit::error for an index the scene does not have.
  void select_light(std::size_t index);
  /// Throw vplkit::error, leaving the view as it was, for a pose the pipeline refuses.
  void set_camera_pose(const pose& where);
  void set_light_pose(const pose& where);
  /// The light's intensity (W/sr) or irradiance (W/m^2): its brightest channel.
  float light_intensity() const;
  /// The light's intensity set to `intensity`, its colour kept (set_light_intensity of scene.hpp).
  /// Throws vplkit::error, leaving the view as it was, for a value the light refuses.
  void set_light_intensity(float intensity);
  bool has_object() const { return pipeline_->has_object(); }
  glm::vec3 object_position() const { return pipeline_->object_position(); }
  void set_object_position(glm::vec3 centre) { pipeline_->set_object_position(centre); }
  /// How often each stage was drawn, e.g. "RSM 2, G-buffer to post filter 5": shows (and tests)
  /// what a move recomputed.
  std::string draw_counts() const { return pipeline_->draw_counts(); }
  /// Writes the current poses (and the moved object) into `scenes`, so that a new view of the
  /// family starts where this one is.
  void store_pose(viewer_scenes& scenes) const;
  /// The settings the technique reads, as Dear ImGui controls made from their descriptions.
  /// Returns true when one was changed and the settings are valid (stored in `scenes`; the caller
  /// builds a new view); writes the reason into `problem` when they are not.
  bool edit_settings(viewer_scenes& scenes, std::string& problem);
  /// Takes the family's settings stored in `scenes` (by edit_settings, or viewer::set_settings)
  /// in place when they change only uniforms, for the technique and its visibility baseline
  /// (which is dropped, to be built when shown again, where it cannot); true then, and the next
  /// draw() redraws. False, changing nothing, when the view must be built again.
  bool take_settings(const viewer_scenes& scenes);

 private:
  const shader_library& shaders_;
  std::unique_ptr<technique_settings> settings_;
  const scene* source_;
  std::unique_ptr<pipeline> pipeline_;
  std::unique_ptr<pipeline> difference_;  ///< the same frame without visibility, built when first shown
  std::size_t selected_light_ = 0;        ///< the light the light controls move
  scene_light selected_light() const;
  void set_selected_light(const scene_light& light);
};

/// The view of `technique` (any family) over `scenes`.
std::unique_ptr<technique_view> make_technique_view(const shader_library& shaders, const viewer_scenes& scenes, const std::string& technique);

}  // namespace vplkit
