// The one interface of every technique family's pipeline (rsm_pipeline, lightwave_pipeline,
// final_gather_pipeline), through which the command line, the viewer and the sweep draw any
// technique (frontend/techniques/registry.hpp makes them). Cameras and lights are set the same
// way for every family; a pipeline tracks what a move invalidated:
// - draw(): every pass, whatever moved (the frame the papers time);
// - draw_changed(): only the passes the moves since the last frame invalidated (the viewer's
//   frames): nothing when nothing moved.
// Settings are changed in place where they only change uniforms (apply_settings: the viewer's
// live controls); a setting that changes a define or a buffer's size needs a new pipeline.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "frontend/core/error.hpp"
#include "frontend/core/setting.hpp"
#include "frontend/gl/pass_timer.hpp"
#include "frontend/gl/render_target.hpp"
#include "frontend/image/image.hpp"
#include "frontend/scene/scene.hpp"

namespace vplkit {

class pipeline {
 public:
  virtual ~pipeline() = default;

  /// Every pass.
  virtual void draw() = 0;
  /// The passes the moves since the last frame invalidated.
  virtual void draw_changed() = 0;
  /// The next frame of a sequence (`vplkit render --poses`, for the families whose
  /// technique_family::sequence_readers says so): a pipeline that accumulates over the frames
  /// blends this one with those before (the RSM's temporal accumulation); otherwise draw().
  virtual void draw_next() { draw(); }
  /// Moves the camera. Throws vplkit::error (and keeps the camera) for one the pipeline refuses.
  virtual void set_camera(const camera& view) = 0;
  /// Moves light `index` of the scene's lights. Throws vplkit::error (and keeps the light) for an
  /// index out of range or a light the pipeline refuses: an invalid light, or another kind than
  /// the one the pipeline was built for at that index.
  virtual void set_light(std::size_t index, const scene_light& light) = 0;
  virtual camera current_camera() const = 0;
  /// The scene's lights as the pipeline draws them now, in the scene's order.
  virtual std::vector<scene_light> current_lights() const = 0;
  /// Takes `settings` (of the technique it draws) in place when they change only uniforms: no
  /// program is compiled or linked and no buffer is made, and the next draw_changed() redraws
  /// with them the image a new pipeline with them would draw. Returns false, changing nothing,
  /// when they need a new pipeline: another technique, a define (a program's variant) or a
  /// buffer's size changes, the settings are invalid, or the family does not apply settings in
  /// place.
  virtual bool apply_settings(const technique_settings& settings) {
    static_cast<void>(settings);
    return false;
  }
  /// A dynamic object the technique gathers for (final gathering), moved by set_object_position.
  virtual bool has_object() const { return false; }
  virtual glm::vec3 object_position() const { return glm::vec3(0.0f); }
  virtual void set_object_position(glm::vec3) { throw error("this technique has no object to move"); }

  /// The pass times since the last call (the pass_timer's method).
  virtual std::vector<pass_time> collect_pass_times() = 0;
  /// The last frame's final radiance.
  virtual const texture_2d& output() const = 0;
  /// The last frame's indirect light as `vplkit render` writes it to -indirect.pfm.
  virtual const texture_2d& indirect_output() const = 0;
  /// The last frame's direct light as `vplkit render` writes it to -direct.pfm: the direct
  /// irradiance at each pixel's surface after the technique's shadows (every light's, summed),
  /// before the surface's albedo; the quantity of indirect_output() for direct light, and of
  /// `vplkit reference --method monte-carlo`'s -direct.pfm. 0 where there is no surface.
  virtual const texture_2d& direct_output() const = 0;
  /// Whether the technique computes indirect light at all (direct light only does not).
  virtual bool has_indirect() const = 0;
  /// The indirect shadow factor in red (Light Wave's accurate and integrated shadows), or null.
  virtual const texture_2d* indirect_shadow_output() const { return nullptr; }
  /// The unfiltered indirect light at the receivers it was gathered for (the RSM gather), if any.
  virtual std::optional<image> raw_indirect() const { return std::nullopt; }
  /// How many times the camera-dependent passes were drawn (draw_changed drew when it grows).
  virtual int view_draws() const = 0;
  /// How often each stage was drawn, e.g. "RSM 2, G-buffer to post filter 5".
  virtual std::string draw_counts() const = 0;
  /// One line: scene (triangles), technique, sizes and what the family adds (VPLs, cube map).
  virtual std::string describe() const = 0;
  /// The name of what it draws: the scene, or the object for final gathering.
  virtual std::string scene_name() const = 0;
};

}  // namespace vplkit
