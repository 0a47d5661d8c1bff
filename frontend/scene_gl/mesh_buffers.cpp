#include "frontend/scene_gl/mesh_buffers.hpp"

#include <cstddef>

#include "frontend/gl/debug_output.hpp"

namespace vplkit {

mesh_buffers::mesh_buffers(const mesh& source)
    : vertex_array_(generate_vertex_array()),
      vertices_(generate_buffer()),
      indices_(generate_buffer()),
      index_count_(static_cast<GLsizei>(source.indices.size())),
      vertex_count_(static_cast<GLsizei>(source.vertices.size())) {
  glBindVertexArray(vertex_array_.get());
  glBindBuffer(GL_ARRAY_BUFFER, vertices_.get());
  glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(source.vertices.size() * sizeof(vertex)),
               source.vertices.data(), GL_STATIC_DRAW);
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, indices_.get());
  glBufferData(GL_ELEMENT_ARRAY_BUFFER, static_cast<GLsizeiptr>(source.indices.size() * sizeof(std::uint32_t)),
               source.indices.data(), GL_STATIC_DRAW);
  const auto attribute = [](GLuint location, std::size_t offset) {
    glEnableVertexAttribArray(location);
    glVertexAttribPointer(location, 3, GL_FLOAT, GL_FALSE, sizeof(vertex), reinterpret_cast<const void*>(offset));
  };
  attribute(0, offsetof(vertex, position));
  attribute(1, offsetof(vertex, normal));
  attribute(2, offsetof(vertex, albedo));
  glBindVertexArray(0);
  check_gl("uploading a mesh of " + std::to_string(source.vertices.size()) + " vertices");
}

void mesh_buffers::draw() const {
  glBindVertexArray(vertex_array_.get());
  glDrawElements(GL_TRIANGLES, index_count_, GL_UNSIGNED_INT, nullptr);
  glBindVertexArray(0);
}

void mesh_buffers::draw_points() const {
  glBindVertexArray(vertex_array_.get());
  glDrawArrays(GL_POINTS, 0, vertex_count_);
  glBindVertexArray(0);
}

void mesh_buffers::attach_vec3_attribute(GLuint location, GLuint buffer) const {
  glBindVertexArray(vertex_array_.get());
  glBindBuffer(GL_ARRAY_BUFFER, buffer);
  glEnableVertexAttribArray(location);
  glVertexAttribPointer(location, 3, GL_FLOAT, GL_FALSE, 3 * sizeof(float), nullptr);
  glBindVertexArray(0);
  glBindBuffer(GL_ARRAY_BUFFER, 0);
  check_gl("attaching vertex attribute " + std::to_string(location));
}

}  // namespace vplkit
