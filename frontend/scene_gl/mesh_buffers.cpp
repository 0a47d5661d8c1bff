#include "frontend/scene_gl/mesh_buffers.hpp"

#include <algorithm>
#include <cstddef>
#include <limits>
#include <string>

#include "frontend/core/error.hpp"
#include "frontend/gl/debug_output.hpp"
#include "frontend/gl/render_target.hpp"

namespace vplkit {

namespace {

GLint gl_wrap(texture_wrap wrap) {
  switch (wrap) {
    case texture_wrap::clamp_to_edge: return GL_CLAMP_TO_EDGE;
    case texture_wrap::mirrored_repeat: return GL_MIRRORED_REPEAT;
    case texture_wrap::repeat: break;
  }
  return GL_REPEAT;
}

GLint gl_min_filter(const texture_sampler& sampler) {
  const bool linear = sampler.min == texture_filter::linear;
  if (!sampler.mipmaps) return linear ? GL_LINEAR : GL_NEAREST;
  if (sampler.between_levels == texture_filter::linear) return linear ? GL_LINEAR_MIPMAP_LINEAR : GL_NEAREST_MIPMAP_LINEAR;
  return linear ? GL_LINEAR_MIPMAP_NEAREST : GL_NEAREST_MIPMAP_NEAREST;
}

gl_sampler make_sampler(const texture_sampler& from) {
  gl_sampler made(generate_sampler());
  const GLuint sampler = made.get();
  glSamplerParameteri(sampler, GL_TEXTURE_WRAP_S, gl_wrap(from.wrap_s));
  glSamplerParameteri(sampler, GL_TEXTURE_WRAP_T, gl_wrap(from.wrap_t));
  glSamplerParameteri(sampler, GL_TEXTURE_MAG_FILTER, from.mag == texture_filter::linear ? GL_LINEAR : GL_NEAREST);
  glSamplerParameteri(sampler, GL_TEXTURE_MIN_FILTER, gl_min_filter(from));
  return made;
}

}  // namespace

mesh_buffers::mesh_buffers(const mesh& source, draw_chunking chunking)
    : vertex_array_(generate_vertex_array()),
      vertices_(generate_buffer()),
      indices_(generate_buffer()),
      index_count_(static_cast<GLsizei>(source.indices.size())),
      vertex_count_(static_cast<GLsizei>(source.vertices.size())),
      chunking_(chunking),
      materials_(source.material_ranges.empty() ? nullptr : source.materials) {
  // Checked before anything else: a chunk of 0 triangles would never finish drawing, and 3 x the
  // sizes must stay within GLsizei.
  constexpr GLsizei max_triangles = std::numeric_limits<GLsizei>::max() / 3;
  if (chunking.threshold_triangles < 0 || chunking.threshold_triangles > max_triangles || chunking.chunk_triangles < 1 ||
      chunking.chunk_triangles > max_triangles)
    throw error("mesh draw chunking: the threshold must be 0.." + std::to_string(max_triangles) + " triangles and the chunk 1.." +
                std::to_string(max_triangles) + ", not " + std::to_string(chunking.threshold_triangles) + " and " +
                std::to_string(chunking.chunk_triangles));
  check_materials(source, "mesh");
  // The GPU copy holds only the attributes that vary. An albedo that every vertex shares (an OBJ
  // without materials, any built-in object) is a constant attribute, and texture coordinates
  // without a textured range are never read, so they are left out too: a faceted 2^21-triangle
  // mesh is 24 bytes a vertex on the GPU instead of 44 (151 MiB instead of 277 beside the CPU's
  // copy). A constant attribute reaches the vertex shader as the same value at every vertex, so
  // the interpolated values and the images are the same bit for bit.
  per_vertex_albedo_ = std::any_of(source.vertices.begin(), source.vertices.end(),
                                   [&](const vertex& v) { return v.albedo != source.vertices.front().albedo; });
  per_vertex_texcoord_ = !source.material_ranges.empty();
  if (!source.vertices.empty()) constant_albedo_ = source.vertices.front().albedo;
  std::size_t stride = 6 * sizeof(float);
  const std::size_t albedo_offset = stride;
  if (per_vertex_albedo_) stride += 3 * sizeof(float);
  const std::size_t texcoord_offset = stride;
  if (per_vertex_texcoord_) stride += 2 * sizeof(float);

  glBindVertexArray(vertex_array_.get());
  glBindBuffer(GL_ARRAY_BUFFER, vertices_.get());
  glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(source.vertices.size() * stride), nullptr, GL_STATIC_DRAW);
  // Packed through a small staging block, so that no second whole copy of the mesh exists at once.
  constexpr std::size_t block_vertices = 16384;
  std::vector<float> staging;
  staging.reserve(block_vertices * stride / sizeof(float));
  for (std::size_t first = 0; first < source.vertices.size(); first += block_vertices) {
    const std::size_t last = std::min(source.vertices.size(), first + block_vertices);
    staging.clear();
    for (std::size_t i = first; i < last; ++i) {
      const vertex& v = source.vertices[i];
      staging.insert(staging.end(), {v.position.x, v.position.y, v.position.z, v.normal.x, v.normal.y, v.normal.z});
      if (per_vertex_albedo_) staging.insert(staging.end(), {v.albedo.r, v.albedo.g, v.albedo.b});
      if (per_vertex_texcoord_) staging.insert(staging.end(), {v.texcoord.x, v.texcoord.y});
    }
    glBufferSubData(GL_ARRAY_BUFFER, static_cast<GLintptr>(first * stride), static_cast<GLsizeiptr>(staging.size() * sizeof(float)), staging.data());
  }
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, indices_.get());
  glBufferData(GL_ELEMENT_ARRAY_BUFFER, static_cast<GLsizeiptr>(source.indices.size() * sizeof(std::uint32_t)),
               source.indices.data(), GL_STATIC_DRAW);
  const auto attribute = [stride](GLuint location, GLint components, std::size_t offset) {
    glEnableVertexAttribArray(location);
    glVertexAttribPointer(location, components, GL_FLOAT, GL_FALSE, static_cast<GLsizei>(stride), reinterpret_cast<const void*>(offset));
  };
  attribute(0, 3, 0);
  attribute(1, 3, 3 * sizeof(float));
  if (per_vertex_albedo_) attribute(2, 3, albedo_offset);
  if (per_vertex_texcoord_) attribute(5, 2, texcoord_offset);
  glBindVertexArray(0);
  check_gl("uploading a mesh of " + std::to_string(source.vertices.size()) + " vertices");

  // Segments: the plain triangles between the material ranges, and the ranges.
  std::size_t at = 0;
  for (const material_range& range : source.material_ranges) {
    if (range.first_index > at) segments_.push_back({at, static_cast<GLsizei>(range.first_index - at), -1});
    if (range.index_count > 0) segments_.push_back({range.first_index, static_cast<GLsizei>(range.index_count), static_cast<int>(range.material)});
    at = std::size_t{range.first_index} + range.index_count;
  }
  if (source.indices.size() > at) segments_.push_back({at, static_cast<GLsizei>(source.indices.size() - at), -1});
  if (!materials_) return;

  for (const texture& t : materials_->textures) {
    check_texture_size(t.levels.front().width, t.levels.front().height, "texture '" + t.name + "'");
    textures_.emplace_back(generate_texture());
    glBindTexture(GL_TEXTURE_2D, textures_.back().get());
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    // Row 0 of each level is the image's top, at t = 0: glTF's (0, 0) is the top-left corner.
    for (std::size_t level = 0; level < t.levels.size(); ++level) {
      const texture_level& pixels = t.levels[level];
      glTexImage2D(GL_TEXTURE_2D, static_cast<GLint>(level), GL_SRGB8_ALPHA8, pixels.width, pixels.height, 0, GL_RGBA, GL_UNSIGNED_BYTE, pixels.rgba8.data());
    }
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_BASE_LEVEL, 0);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAX_LEVEL, static_cast<GLint>(t.levels.size() - 1));
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    check_gl("uploading texture '" + t.name + "' (" + std::to_string(t.levels.front().width) + "x" + std::to_string(t.levels.front().height) + ")");
  }
  glBindTexture(GL_TEXTURE_2D, 0);
  for (const surface_material& material : materials_->materials) {
    samplers_.push_back(make_sampler(material.sampler));
    emission_samplers_.push_back(make_sampler(material.emission_sampler));
  }
  check_gl("making the samplers of " + std::to_string(samplers_.size()) + " materials");
}

void mesh_buffers::draw(const program& target) const {
  target.use();
  target.set("material_texture", material_texture_unit);
  glBindVertexArray(vertex_array_.get());
  set_constant_attributes();
  for (const segment& part : segments_) {
    bind_material(target, part.material);
    draw_triangles(part.first_index, part.count);
  }
  unbind_materials();
}

bool mesh_buffers::has_emission() const {
  return std::any_of(segments_.begin(), segments_.end(), [&](const segment& part) {
    return part.material >= 0 && emits(materials_->materials[static_cast<std::size_t>(part.material)]);
  });
}

void mesh_buffers::draw_emissive(const program& target) const {
  target.use();
  target.set("material_texture", material_texture_unit);
  target.set("material_emission_texture", emission_texture_unit);
  glBindVertexArray(vertex_array_.get());
  set_constant_attributes();
  for (const segment& part : segments_) {
    if (part.material < 0) continue;
    const surface_material& material = materials_->materials[static_cast<std::size_t>(part.material)];
    if (!emits(material)) continue;
    bind_material(target, part.material);
    const bool textured = material.emission_texture >= 0;
    target.set("material_emission", material.emission);
    target.set("material_emission_textured", textured ? 1 : 0);
    target.set("material_emission_texture_matrix", glm::vec4(material.emission_texture_matrix[0], material.emission_texture_matrix[1]));
    target.set("material_emission_texture_offset", material.emission_texture_offset);
    glActiveTexture(static_cast<GLenum>(GL_TEXTURE0 + emission_texture_unit));
    glBindTexture(GL_TEXTURE_2D, textured ? textures_[static_cast<std::size_t>(material.emission_texture)].get() : 0);
    glBindSampler(static_cast<GLuint>(emission_texture_unit), textured ? emission_samplers_[static_cast<std::size_t>(part.material)].get() : 0);
    draw_triangles(part.first_index, part.count);
  }
  glActiveTexture(static_cast<GLenum>(GL_TEXTURE0 + emission_texture_unit));
  glBindSampler(static_cast<GLuint>(emission_texture_unit), 0);
  glBindTexture(GL_TEXTURE_2D, 0);
  unbind_materials();
}

void mesh_buffers::bind_material(const program& target, int index) const {
  const surface_material* material = index >= 0 ? &materials_->materials[static_cast<std::size_t>(index)] : nullptr;
  const bool textured = material && material->texture >= 0;
  target.set("material_textured", textured ? 1 : 0);
  target.set("material_alpha_factor", material ? material->alpha_factor : 1.0f);
  target.set("material_alpha_cutoff", material && material->alpha_mask ? material->alpha_cutoff : -1.0f);
  if (material) {
    target.set("material_texture_matrix", glm::vec4(material->texture_matrix[0], material->texture_matrix[1]));
    target.set("material_texture_offset", material->texture_offset);
  }
  glActiveTexture(static_cast<GLenum>(GL_TEXTURE0 + material_texture_unit));
  glBindTexture(GL_TEXTURE_2D, textured ? textures_[static_cast<std::size_t>(material->texture)].get() : 0);
  glBindSampler(static_cast<GLuint>(material_texture_unit), textured ? samplers_[static_cast<std::size_t>(index)].get() : 0);
}

void mesh_buffers::unbind_materials() const {
  glBindVertexArray(0);
  glActiveTexture(static_cast<GLenum>(GL_TEXTURE0 + material_texture_unit));
  glBindSampler(static_cast<GLuint>(material_texture_unit), 0);
  glBindTexture(GL_TEXTURE_2D, 0);
  glActiveTexture(GL_TEXTURE0);
}

void mesh_buffers::draw_triangles(std::size_t first_index, GLsizei count) const {
  const auto draw = [](std::size_t first, GLsizei indices) {
    glDrawElements(GL_TRIANGLES, indices, GL_UNSIGNED_INT, reinterpret_cast<const void*>(first * sizeof(std::uint32_t)));
  };
  if (count <= 3 * chunking_.threshold_triangles) {
    draw(first_index, count);
    return;
  }
  // A driver may set up triangles far ahead of drawing them: llvmpipe bins a whole draw's
  // triangles while its rasterizer threads work through them, and the binned triangles of a
  // 2^21-triangle mesh took 90-180 MiB (38 MiB when llvmpipe rasterizes on the calling thread),
  // more the busier the machine. Drawn in chunks, each followed by a fence, waiting after each
  // chunk for the previous chunk's fence: at most two chunks are in flight, one drawn while the
  // next is set up. The triangles are drawn in the same order, so the images are the same bit
  // for bit.
  const GLsizei chunk = 3 * chunking_.chunk_triangles;
  GLsync in_flight = nullptr;
  for (GLsizei done = 0; done < count;) {
    const GLsizei indices = std::min(chunk, count - done);  // done + indices <= count: no overflow
    draw(first_index + static_cast<std::size_t>(done), indices);
    done += indices;
    if (in_flight) {
      // A wait that times out only lets more work queue up; the drawing is the same.
      glClientWaitSync(in_flight, GL_SYNC_FLUSH_COMMANDS_BIT, fence_timeout_ns);
      glDeleteSync(in_flight);
      in_flight = nullptr;
    }
    if (done < count) in_flight = glFenceSync(GL_SYNC_GPU_COMMANDS_COMPLETE, 0);
  }
}

void mesh_buffers::draw_points() const {
  glBindVertexArray(vertex_array_.get());
  set_constant_attributes();
  glDrawArrays(GL_POINTS, 0, vertex_count_);
  glBindVertexArray(0);
}

void mesh_buffers::set_constant_attributes() const {
  // A disabled array's attribute reads the context's current value, which another mesh or pass
  // may have changed since: set on every draw.
  if (!per_vertex_albedo_) glVertexAttrib3f(2, constant_albedo_.r, constant_albedo_.g, constant_albedo_.b);
  if (!per_vertex_texcoord_) glVertexAttrib2f(5, 0.0f, 0.0f);
}

void mesh_buffers::attach_vec4_attribute(GLuint location, GLuint buffer) const {
  glBindVertexArray(vertex_array_.get());
  glBindBuffer(GL_ARRAY_BUFFER, buffer);
  glEnableVertexAttribArray(location);
  glVertexAttribPointer(location, 4, GL_FLOAT, GL_FALSE, 4 * sizeof(float), nullptr);
  glBindVertexArray(0);
  glBindBuffer(GL_ARRAY_BUFFER, 0);
  check_gl("attaching vertex attribute " + std::to_string(location));
}

}  // namespace vplkit
