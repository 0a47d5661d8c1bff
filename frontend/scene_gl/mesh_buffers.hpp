// A mesh on the GPU: one interleaved vertex buffer (position, normal, albedo and texture
// coordinate at attribute locations 0, 1, 2 and 5; 3 and 4 are left to per-vertex results a
// pipeline attaches; an albedo that every vertex shares, and the texture coordinates of a mesh
// without textured ranges, are constant attributes instead of buffer data), an index buffer, the
// vertex array that binds them, and the textures (SRGB8_ALPHA8 with the mip chain
// frontend/scene/material.hpp made) and sampler objects of the mesh's materials.
#pragma once

#include <memory>
#include <vector>

#include "frontend/gl/gl_object.hpp"
#include <vplkit/gl/program.hpp>
#include "frontend/scene/scene.hpp"

namespace vplkit {

/// The texture unit a material's base-colour texture is bound to while a mesh draws (the
/// pipelines' own textures for mesh passes use the units below it; full-screen passes, which draw
/// no mesh, may use it and above: the RSM gather binds a point light's six face RSMs to 8..13).
constexpr int material_texture_unit = 8;
/// The unit of a material's emission texture while draw_emissive draws it.
constexpr int emission_texture_unit = material_texture_unit + 1;

/// How draw() splits a long run of triangles (one material range, or the plain triangles
/// between ranges): a run of more than `threshold_triangles` is drawn in chunks of
/// `chunk_triangles`, in order, with at most two chunks in flight (mesh_buffers.cpp says why).
/// The defaults bound llvmpipe's binned triangles for a 2^21-triangle mesh; a test sets tiny
/// values so that a small mesh takes the chunked path (tests/frontend/scene_gl/test_mesh_buffers.cpp).
struct draw_chunking {
  GLsizei threshold_triangles = 1 << 20;  ///< >= 0
  GLsizei chunk_triangles = 1 << 16;      ///< >= 1
};

class mesh_buffers {
 public:
  /// Throws vplkit::error for a `chunking` outside the ranges above.
  explicit mesh_buffers(const mesh& source, draw_chunking chunking = {});
  /// Draws every triangle with `target`, which must include shaders/surface_material.glsl: for
  /// each material range its texture and sampler are bound to material_texture_unit and the
  /// material's uniforms set; the plain triangles between ranges draw untextured and opaque.
  /// Uses `target`.
  void draw(const program& target) const;
  /// Whether a material range of the mesh emits (frontend/scene/material.hpp).
  bool has_emission() const;
  /// Draws the emissive material ranges only, with `target` (an emission pass's program,
  /// shaders/emission.frag): draw()'s material uniforms and textures, and per range its emission
  /// (material_emission), emission texture (bound to emission_texture_unit, with its own sampler)
  /// and its transform.
  void draw_emissive(const program& target) const;
  /// Every vertex once, as points (for transform feedback over the vertex stage).
  void draw_points() const;
  /// Binds `buffer`, one vec4 of floats per vertex, to attribute `location` of the vertex array
  /// (a per-vertex result computed on the GPU, e.g. copied from a render target's RGBA texels).
  void attach_vec4_attribute(GLuint location, GLuint buffer) const;
  GLsizei vertex_count() const { return vertex_count_; }

 private:
  /// Consecutive indices drawn with one material (-1: plain).
  struct segment {
    std::size_t first_index;
    GLsizei count;
    int material;
  };
  gl_vertex_array vertex_array_;
  gl_buffer vertices_;
  gl_buffer indices_;
  GLsizei index_count_;
  GLsizei vertex_count_;
  /// Sets the constant attributes (albedo, texture coordinate) that this mesh keeps out of its buffer.
  void set_constant_attributes() const;
  /// Material `index`'s (-1: plain) uniforms, base-colour texture and sampler, for one segment.
  void bind_material(const program& target, int index) const;
  /// Unbinds the vertex array and the material's texture and sampler after a draw.
  void unbind_materials() const;
  /// Draws `count` indices from `first_index` of the bound vertex array: one draw call, or for
  /// more than chunking_.threshold_triangles, chunks of chunking_.chunk_triangles with at most
  /// two in flight.
  void draw_triangles(std::size_t first_index, GLsizei count) const;
  draw_chunking chunking_;
  static constexpr GLuint64 fence_timeout_ns = GLuint64{10} * 1000 * 1000 * 1000;

  std::vector<segment> segments_;
  bool per_vertex_albedo_ = true;
  bool per_vertex_texcoord_ = true;
  glm::vec3 constant_albedo_{0.0f};
  std::shared_ptr<const material_library> materials_;
  std::vector<gl_texture> textures_;
  std::vector<gl_sampler> samplers_;  ///< one per material
  std::vector<gl_sampler> emission_samplers_;  ///< one per material, for its emission texture
};

}  // namespace vplkit
