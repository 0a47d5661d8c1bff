// A mesh on the GPU: one interleaved vertex buffer (position, normal, albedo at attribute
// locations 0, 1, 2), an index buffer, and the vertex array that binds them.
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

 private:
  gl_vertex_array vertex_array_;
  gl_buffer vertices_;
  gl_buffer indices_;
  GLsizei index_count_;
  GLsizei vertex_count_;
};

}  // namespace vplkit
