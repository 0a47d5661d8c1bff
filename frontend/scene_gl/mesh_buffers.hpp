// A mesh on the GPU: one interleaved vertex buffer (position, normal, albedo at attribute
// locations 0, 1, 2), an index buffer, and the vertex array that binds them; optionally more
// per-vertex vec3 attributes from other buffers.
#pragma once

#include "frontend/gl/gl_object.hpp"
#include "frontend/scene/scene.hpp"

namespace vplkit {

class mesh_buffers {
 public:
  explicit mesh_buffers(const mesh& source);
  void draw() const;
  /// Every vertex once, as points (for transform feedback over the vertex stage).
  void draw_points() const;
  /// Binds `buffer`, one vec3 of floats per vertex, to attribute `location` of the vertex array
  /// (a per-vertex result computed on the GPU, e.g. captured by transform feedback).
  void attach_vec3_attribute(GLuint location, GLuint buffer) const;
  GLsizei vertex_count() const { return vertex_count_; }

 private:
  gl_vertex_array vertex_array_;
  gl_buffer vertices_;
  gl_buffer indices_;
  GLsizei index_count_;
  GLsizei vertex_count_;
};

}  // namespace vplkit
