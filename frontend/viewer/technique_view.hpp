// One technique family in the viewer: its pipeline, the pose of its camera and light (and of the
// object, for final gathering), the layers it can show, and its settings as live controls. A move
// goes to the pipeline, which redraws only what the move invalidated (rsm_pipeline::draw_changed,
// lightwave_pipeline::draw, final_gather_pipeline::draw_changed); a changed setting builds a new
// pipeline, since the programs are compiled for the settings.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <vplkit/gl/program.hpp>

#include "frontend/gl/pass_timer.hpp"
#include "frontend/gl/render_target.hpp"
#include "frontend/scene/pose.hpp"
#include "frontend/techniques/final_gather/final_gather_pipeline.hpp"
#include "frontend/techniques/lightwave/lightwave_pipeline.hpp"
#include "frontend/techniques/rsm/rsm_pipeline.hpp"

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

/// Every family's settings and scenes: what the viewer can switch between.
struct viewer_scenes {
  scene rsm;                  ///< the RSM techniques' scene
  scene lightwave;            ///< the Light Wave techniques' scene (a spot light)
  final_gather_scene final_gather;
  rsm_pipeline_settings rsm_setup;
  lightwave_settings lightwave_setup;
  final_gather_settings final_gather_setup;
};

class technique_view {
 public:
  virtual ~technique_view() = default;
  virtual std::string technique() const = 0;
  /// Draws what the moves since the last frame invalidated; true when anything was drawn.
  virtual bool draw() = 0;
  virtual std::vector<view_layer> layers() const = 0;
  virtual layer_display display(view_layer layer) = 0;
  /// The indirect light of the last frame (what `vplkit render` writes as -indirect.pfm).
  virtual image read_indirect() const = 0;
  virtual std::vector<pass_time> collect_pass_times() = 0;
  virtual pose camera_pose() const = 0;
  virtual pose light_pose() const = 0;
  /// Throw vplkit::error, leaving the view as it was, for a pose the pipeline refuses.
  virtual void set_camera_pose(const pose& where) = 0;
  virtual void set_light_pose(const pose& where) = 0;
  virtual bool has_object() const { return false; }
  virtual glm::vec3 object_position() const { return glm::vec3(0.0f); }
  virtual void set_object_position(glm::vec3) {}
  /// How often each stage was drawn, e.g. "RSM 2, G-buffer to post filter 5": shows (and tests)
  /// what a move recomputed.
  virtual std::string draw_counts() const = 0;
  /// Writes the current poses (and the moved object) into `scenes`, so that a new view of the
  /// family starts where this one is.
  virtual void store_pose(viewer_scenes& scenes) const = 0;
  /// The settings as Dear ImGui controls. Returns new settings when one was changed and is
  /// valid (the caller builds a new view); writes the reason into `problem` when it is not.
  virtual bool edit_settings(viewer_scenes& scenes, std::string& problem) = 0;
};

/// Every technique make_technique_view knows: direct and rsm-*, lightwave-*, finalgather-* and envmap.
std::vector<std::string> technique_names();

/// The view of `technique` (any family) over `scenes`, with the family's settings from `scenes`
/// and the technique set. Throws vplkit::error when the pipeline refuses them (e.g. Light Wave
/// with a directional light).
std::unique_ptr<technique_view> make_technique_view(const shader_library& shaders, const viewer_scenes& scenes, const std::string& technique);

}  // namespace vplkit
