// Light Wave's flux energy at the receivers, the GL half (lightwave_planning.hpp has the CPU
// half): the receivers' textures and sum targets, the VPLs' uniform blocks, and the passes of
// lightwave_capture.frag that sum every receiver VPL at every receiver into the buffer the main
// pass reads.
#include "frontend/techniques/lightwave/lightwave_pipeline.hpp"

#include <algorithm>
#include <cstdint>
#include <numeric>

#include <vplkit/gl/settings_uniforms.hpp>

#include "frontend/gl/debug_output.hpp"
#include "frontend/core/error.hpp"

namespace vplkit {

// The flux energy's receivers: the scene subdivided, their sample points, normals and albedos in
// the textures lightwave_capture.frag reads (made once, shared by every light), and this light's
// buffer its sums land in.
void lightwave_pipeline::set_up_receivers(const shader_library& shaders, const scene& source, bool make_shared) {
  surface_program_ = load_program(shaders, "scene.vert", "lightwave_surfaces.frag");
  constexpr auto bands = static_cast<std::size_t>(lightwave_sum_receivers);
  if (make_shared) {
    shared_->surfaces.emplace(lightwave_surface_map_size, lightwave_surface_map_size,
                              std::vector<texel_format>{texel_format::rgba32f, texel_format::rgba32f, texel_format::rgba32f}, true);
    shared_->receivers = lightwave_receivers(source.geometry, settings_.receiver_spacing, settings_.receiver_triangles);
    shared_->receiver_samples = lightwave_receiver_samples(shared_->receivers);
    shared_->receiver_buffers.emplace(shared_->receivers);
    // The sum at the receivers, lightwave_sum_receivers per texel of a grid (lightwave_capture.frag):
    // receiver r is cell t = r % cells of band k = r / cells, read at texel (t % width, k x rows +
    // t / width) of three textures (its sample point, normal and albedo), its sum written to
    // attachment k of the sums' target at texel (t % width, t / width).
    const std::size_t count = shared_->receivers.vertices.size();
    GLint max_side = 0;
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &max_side);
    const glm::ivec2 grid = lightwave_sum_grid(count, max_side);
    check_texture_size(grid.x, grid.y * lightwave_sum_receivers, "the Light Wave receivers' grid (" + std::to_string(count) + " receivers)");
    const std::size_t cells = static_cast<std::size_t>(grid.x) * static_cast<std::size_t>(grid.y);
    shared_->receiver_cells = cells;
    // Empty texels get a unit normal, so that their lanes compute no NaN (their sums are written as zero anyway).
    std::vector<glm::vec4> points(bands * cells, glm::vec4(0.0f)), normals(bands * cells, glm::vec4(0.0f, 0.0f, 1.0f, 0.0f)),
        albedos(bands * cells, glm::vec4(0.0f));
    for (std::size_t i = 0; i < count; ++i) {
      points[i] = glm::vec4(shared_->receiver_samples[i], 0.0f);
      normals[i] = glm::vec4(shared_->receivers.vertices[i].normal, 0.0f);
      albedos[i] = glm::vec4(shared_->receivers.vertices[i].albedo, 0.0f);
    }
    for (const std::vector<glm::vec4>* texels : {&points, &normals, &albedos})
      shared_->receiver_textures.emplace_back(grid.x, grid.y * lightwave_sum_receivers, texel_format::rgba32f, texels->data());
    for (int k = 0; k < 2; ++k) shared_->receiver_sum_targets.emplace_back(grid.x, grid.y, std::vector<texel_format>(bands, texel_format::rgba32f), false);
  }
  // The sums land in this light's attribute buffer band after band, each the grid's texels in
  // RGBA floats (the copy a plain memcpy on any GL), read as a vec3 attribute (attached to the
  // shared receivers' vertex array before each light's indirect pass).
  indirect_buffer_ = gl_buffer(generate_buffer());
  glBindBuffer(GL_ARRAY_BUFFER, indirect_buffer_.get());
  glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(bands * shared_->receiver_cells * sizeof(glm::vec4)), nullptr, GL_DYNAMIC_COPY);
  glBindBuffer(GL_ARRAY_BUFFER, 0);
}

// The flux energy's VPLs, a uniform block per pass of lightwave_capture.frag.
void lightwave_pipeline::set_up_vpl_blocks(const shader_library& shaders) {
  // The VPLs of a pass in one uniform block: three vec4 each (std140), the blocks of successive
  // passes at offsets the GL accepts.
  GLint block_bytes = 0, offset_alignment = 0;
  glGetIntegerv(GL_MAX_UNIFORM_BLOCK_SIZE, &block_bytes);
  glGetIntegerv(GL_UNIFORM_BUFFER_OFFSET_ALIGNMENT, &offset_alignment);
  constexpr int bytes_per_vpl = 3 * static_cast<int>(sizeof(glm::vec4));
  const int block_vpls = block_bytes / bytes_per_vpl;
  // By default a 64 KiB block's worth (GL 3.3 guarantees 16 KiB; some drivers report blocks far
  // larger than a shader should declare).
  vpls_per_pass_ = settings_.vpls_per_pass == 0 ? std::min(block_vpls, 65536 / bytes_per_vpl) : settings_.vpls_per_pass;
  if (vpls_per_pass_ < 1 || vpls_per_pass_ > block_vpls)
    throw error("Light Wave: " + std::to_string(vpls_per_pass_) + " VPLs per pass need a uniform block of " + std::to_string(vpls_per_pass_ * bytes_per_vpl) +
                " bytes; this GL allows " + std::to_string(block_bytes) + " (at most " + std::to_string(block_vpls) + " VPLs per pass)");
  const std::size_t alignment = std::lcm(static_cast<std::size_t>(std::max(offset_alignment, 1)), sizeof(glm::vec4));
  const std::size_t block_size = static_cast<std::size_t>(vpls_per_pass_) * bytes_per_vpl;
  vpl_block_stride_ = (block_size + alignment - 1) / alignment * alignment;
  vpl_block_buffer_ = gl_buffer(generate_buffer());
  receiver_sum_program_ = load_program(shaders, "fullscreen.vert", "lightwave_capture.frag",
                                       {{"VPLKIT_LIGHTWAVE_PASS_VPLS", std::to_string(vpls_per_pass_)},
                                        {"VPLKIT_LIGHTWAVE_SUM_RECEIVERS", std::to_string(lightwave_sum_receivers)}});
  glUniformBlockBinding(receiver_sum_program_.id(), glGetUniformBlockIndex(receiver_sum_program_.id(), "lightwave_pass_vpls"), 0);
  empty_vertex_array_ = gl_vertex_array(generate_vertex_array());
}

void lightwave_pipeline::sum_at_receivers() {
  static_assert(lightwave_sum_receivers == 4, "lightwave_capture.frag reads the previous pass's sums from four samplers, partial_sum0..3");
  // The first pass continues from zero.
  shared_->receiver_sum_targets[1].bind();
  glClearColor(0.0f, 0.0f, 0.0f, 0.0f);
  glClear(GL_COLOR_BUFFER_BIT);
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_BLEND);
  const program& p = receiver_sum_program_;
  p.use();
  p.set("receiver_points", 0);
  p.set("receiver_normals", 1);
  p.set("receiver_albedos", 2);
  for (int k = 0; k < lightwave_sum_receivers; ++k) p.set("partial_sum" + std::to_string(k), 3 + k);
  p.set("receiver_count", static_cast<int>(shared_->receivers.vertices.size()));
  set_uniforms(p, "irradiance", settings_.irradiance);
  for (std::size_t k = 0; k < shared_->receiver_textures.size(); ++k) shared_->receiver_textures[k].bind(static_cast<int>(k));
  glBindVertexArray(empty_vertex_array_.get());
  const int passes = lightwave_vpl_pass_count(receiver_vpls_.size(), vpls_per_pass_), count = static_cast<int>(receiver_vpls_.size());
  for (int pass = 0; pass < passes; ++pass) {
    const framebuffer& target = shared_->receiver_sum_targets[static_cast<std::size_t>(pass % 2)];
    target.bind();
    const framebuffer& previous = shared_->receiver_sum_targets[static_cast<std::size_t>((pass + 1) % 2)];
    for (int k = 0; k < lightwave_sum_receivers; ++k) previous.colour(static_cast<std::size_t>(k)).bind(3 + k);
    glBindBufferRange(GL_UNIFORM_BUFFER, 0, vpl_block_buffer_.get(), static_cast<GLintptr>(static_cast<std::size_t>(pass) * vpl_block_stride_),
                      static_cast<GLsizeiptr>(static_cast<std::size_t>(vpls_per_pass_) * 3 * sizeof(glm::vec4)));
    p.set("pass_vpl_count", std::min(vpls_per_pass_, count - pass * vpls_per_pass_));
    p.set("last_pass", pass + 1 == passes ? 1 : 0);
    glDrawArrays(GL_TRIANGLES, 0, 3);
  }
  glBindVertexArray(0);
  glBindBufferBase(GL_UNIFORM_BUFFER, 0, 0);
  // Into the main pass's attribute buffer without a trip through host memory, band after band.
  const framebuffer& result = shared_->receiver_sum_targets[static_cast<std::size_t>((passes - 1) % 2)];
  const std::size_t band_bytes = static_cast<std::size_t>(result.width()) * static_cast<std::size_t>(result.height()) * sizeof(glm::vec4);
  glPixelStorei(GL_PACK_ALIGNMENT, 4);
  glBindBuffer(GL_PIXEL_PACK_BUFFER, indirect_buffer_.get());
  for (int k = 0; k < lightwave_sum_receivers; ++k) {
    result.bind_for_reading(static_cast<std::size_t>(k));
    glReadPixels(0, 0, result.width(), result.height(), GL_RGBA, GL_FLOAT, reinterpret_cast<void*>(static_cast<std::uintptr_t>(k) * band_bytes));
  }
  glBindBuffer(GL_PIXEL_PACK_BUFFER, 0);
  check_gl("summing the Light Wave VPLs at the receivers");
}

}  // namespace vplkit
