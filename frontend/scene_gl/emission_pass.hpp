// Emissive materials drawn as seen, the one way for every technique family (the RSM techniques,
// Light Wave, final gathering, and the viewer through them): after a family has composed its
// final image, a pass draws the mesh's emissive triangles (mesh_buffers::draw_emissive) with
// the family's camera and adds their emission (shaders/emission.frag) to the final radiance where
// their depth equals the family's own depth of the view. scene.vert's position is invariant, so a
// visible emitter's fragments match the depth the family drew to the bit (no tolerance), and a
// hidden one's do not. Only the final image gets it: the indirect and direct outputs stay the
// light they are. Emission lights nothing.
//
// Why a pass and not an emission channel in each G-buffer: the RSM family's and final
// gathering's final images are composed by full-screen passes from G-buffers that have no spare
// RGB channel (the RSM G-buffer's one spare scalar is the shadow density), and Light Wave draws
// geometry; one pass over the depth every family already has reaches all three with one shader
// and no change to their G-buffers, and a scene without emission draws nothing more.
#pragma once

#include <glm/glm.hpp>

#include <vplkit/gl/program.hpp>

#include "frontend/gl/gl_object.hpp"
#include "frontend/gl/render_target.hpp"
#include "frontend/scene_gl/mesh_buffers.hpp"

namespace vplkit {

/// A family makes one only when its meshes emit (has_emission): a scene without emission pays
/// nothing (no program, no pass).
class emission_pass {
 public:
  /// Loads scene.vert with emission.frag.
  explicit emission_pass(const shader_library& shaders);
  /// Adds the emission of `mesh`'s emissive triangles, seen through `view_projection` from
  /// `eye`, to the RGB of `radiance` (its alpha stays) where their depth equals `depth`'s: a
  /// depth32f texture of radiance's size that the family drew the view's surfaces into with the
  /// same view_projection. Leaves blending, depth test and writes off, depth function LESS.
  void draw(const mesh_buffers& mesh, const glm::mat4& view_projection, const glm::vec3& eye, const texture_2d& radiance, const texture_2d& depth) const;

 private:
  program program_;
  gl_framebuffer framebuffer_;
};

}  // namespace vplkit
