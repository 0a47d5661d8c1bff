// vplkit::parity's runs (vplkit/parity/parity.hpp): a kernel checked against its target's
// limits, then run as a fragment, vertex or compute shader on a headless GL context, or as a
// compute shader on Vulkan, and its outputs read back.
#include <vplkit/parity/parity.hpp>

#include <algorithm>
#include <cstring>
#include <limits>

#include "frontend/core/error.hpp"
#include "frontend/gl/debug_output.hpp"
#include "frontend/gl/gl_object.hpp"
#include "frontend/gl/render_target.hpp"
#include "frontend/parity/internal.hpp"
#include "frontend/parity/vulkan_compute.hpp"

namespace vplkit::parity {
using detail::check_grid;
using detail::compute_source;
using detail::context_for;
using detail::default_context_again;
using detail::fragment_source;
using detail::shaders_for;
using detail::vertex_source;

void detail::check_grid(const std::string& what, const kernel_inputs& inputs) {
  if (inputs.width < 1 || inputs.height < 1)
    throw error(what + "the input grid is " + std::to_string(inputs.width) + "x" + std::to_string(inputs.height) +
                "; it must be at least 1x1");
  const auto check_size = [&](const char* kind, std::size_t index, std::size_t size) {
    if (size != inputs.size())
      throw error(what + kind + " input " + std::to_string(index) + " has " + std::to_string(size) + " values for a " +
                  std::to_string(inputs.width) + "x" + std::to_string(inputs.height) + " grid (" + std::to_string(inputs.size()) +
                  " texels)");
  };
  for (std::size_t i = 0; i < inputs.floats.size(); ++i) check_size("float", i, inputs.floats[i].size());
  for (std::size_t i = 0; i < inputs.uints.size(); ++i) check_size("uint", i, inputs.uints[i].size());
}

namespace {

GLint gl_limit(GLenum name) {
  GLint value = 0;
  glGetIntegerv(name, &value);
  return value;
}

const char* run_name(shader_stage stage) {
  return stage == shader_stage::fragment ? "run_fragment" : stage == shader_stage::vertex ? "run_vertex" : "run_compute";
}

// Which stages a target runs, before anything is made: a clear refusal that names the targets
// that do, rather than a context or compile error.
void check_target(const std::string& what, shader_stage stage, target where, const kernel_resources& resources) {
  if (stage == shader_stage::compute && (where == target::gl33 || where == target::gles3))
    throw error(what + "target " + target_name(where) + " has no compute shaders (" +
                (where == target::gl33 ? "GL 3.3; they came with GL 4.3" : "OpenGL ES 3.0, which WebGL2 is, has none; they came with ES 3.1") +
                "): run_compute runs on gl45 and vulkan; use run_fragment or run_vertex here");
  if (stage != shader_stage::compute && where == target::vulkan)
    throw error(what + "vplkit::parity runs Vulkan kernels as compute shaders only: use run_compute on vulkan, or run_fragment / "
                       "run_vertex on gl33, gl45 or gles3");
  if (where == target::vulkan && resources.uniforms)
    throw error(what + "a uniform setter sets GL default-block uniforms, which Vulkan has not: pass the values in a kernel_block "
                       "(settings_block) instead");
  // A short table would be uploaded past its end; two tables of one name declare one GLSL name
  // twice, a compile error that would not say which tables.
  std::vector<std::string> names;
  const auto check_table = [&](const std::string& kind, std::size_t i, const auto& table) {
    if (table.name.empty() || table.width < 1 || table.height < 1 ||
        table.texels.size() != static_cast<std::size_t>(table.width) * static_cast<std::size_t>(table.height))
      throw error(what + kind + std::to_string(i) + " '" + table.name + "' is " + std::to_string(table.width) + "x" +
                  std::to_string(table.height) + " with " + std::to_string(table.texels.size()) +
                  " texels: it needs a name and width * height texels, at least 1x1");
    if (std::find(names.begin(), names.end(), table.name) != names.end())
      throw error(what + kind + std::to_string(i) + " is named '" + table.name + "' like a table before it: each table needs a name of its own");
    names.push_back(table.name);
  };
  for (std::size_t i = 0; i < resources.tables.size(); ++i) check_table("table ", i, resources.tables[i]);
  for (std::size_t i = 0; i < resources.uint_tables.size(); ++i) check_table("uint table ", i, resources.uint_tables[i]);
  for (std::size_t i = 0; i < resources.blocks.size(); ++i) {
    const kernel_block& block = resources.blocks[i];
    if (block.type.empty() || block.member.empty() || block.bytes.empty())
      throw error(what + "uniform block " + std::to_string(i) + " ('" + block.type + " " + block.member +
                  "') needs a GLSL type, a member name and its std140 bytes");
  }
}

// What a run asks of its stage, checked against this context's limits before anything is made,
// so that too many inputs or outputs are named as such rather than surfacing as a list of GL
// errors from the texture uploads or the link. GL 3.3 guarantees 16 texture units per stage, 16
// vertex attributes, 8 draw buffers and 4 separate transform feedback outputs.
void check_run(const std::string& what, const kernel_source& source, const kernel_inputs& inputs, shader_stage stage, target where,
               const kernel_resources& resources) {
  check_grid(what, inputs);
  if (source.float_outputs < 0 || source.uint_outputs < 0)
    throw error(what + "float_outputs " + std::to_string(source.float_outputs) + " and uint_outputs " + std::to_string(source.uint_outputs) +
                ": an output count cannot be negative");
  if (source.float_outputs + source.uint_outputs == 0) throw error(what + "the kernel has no outputs: set float_outputs or uint_outputs");
  const char* stage_text = stage == shader_stage::fragment ? "a fragment" : stage == shader_stage::vertex ? "a vertex" : "a compute";
  const auto check_limit = [&](std::size_t count, const std::string& things, std::size_t limit, const std::string& limit_text) {
    if (count > limit)
      throw error(what + std::to_string(count) + " " + things + ", but " + stage_text + " shader has at most " + std::to_string(limit) + " (" +
                  limit_text + " of this " + (where == target::vulkan ? "device" : "context") +
                  "): split the kernel into runs with fewer, or pack more values into each vec4");
  };
  const auto gl_count = [](GLenum name) { return static_cast<std::size_t>(std::max(gl_limit(name), 0)); };
  const std::size_t input_count = inputs.floats.size() + inputs.uints.size();
  const std::string inputs_text = "inputs (" + std::to_string(inputs.floats.size()) + " float, " + std::to_string(inputs.uints.size()) + " uint)";
  const std::size_t output_count = static_cast<std::size_t>(source.float_outputs) + static_cast<std::size_t>(source.uint_outputs);
  const std::string outputs_text = "outputs (" + std::to_string(source.float_outputs) + " float, " + std::to_string(source.uint_outputs) + " uint)";
  const std::size_t tables = resources.tables.size() + resources.uint_tables.size();
  const std::string tables_text = tables ? " and " + std::to_string(tables) + " tables" : "";
  if (stage == shader_stage::fragment) {
    check_limit(input_count + tables, inputs_text + tables_text + ", each a texture", gl_count(GL_MAX_TEXTURE_IMAGE_UNITS), "GL_MAX_TEXTURE_IMAGE_UNITS");
    check_limit(output_count, outputs_text + ", each a render target", gl_count(GL_MAX_DRAW_BUFFERS), "GL_MAX_DRAW_BUFFERS");
  } else if (stage == shader_stage::vertex) {
    check_limit(input_count, inputs_text + ", each a vertex attribute", gl_count(GL_MAX_VERTEX_ATTRIBS), "GL_MAX_VERTEX_ATTRIBS");
    check_limit(tables, "tables, each a texture", gl_count(GL_MAX_VERTEX_TEXTURE_IMAGE_UNITS), "GL_MAX_VERTEX_TEXTURE_IMAGE_UNITS");
    check_limit(output_count, outputs_text + ", each captured by transform feedback", gl_count(GL_MAX_TRANSFORM_FEEDBACK_SEPARATE_ATTRIBS),
                "GL_MAX_TRANSFORM_FEEDBACK_SEPARATE_ATTRIBS");
    // One vertex per texel, drawn with a GLsizei count.
    if (inputs.size() > static_cast<std::size_t>(std::numeric_limits<GLsizei>::max()))
      throw error(what + "a " + std::to_string(inputs.width) + "x" + std::to_string(inputs.height) + " grid is more vertices than one draw takes (" +
                  std::to_string(std::numeric_limits<GLsizei>::max()) + ")");
  } else {
    const bool vulkan = where == target::vulkan;
    const std::size_t storage_limit =
        vulkan ? detail::vulkan_device_limits().storage_buffers : gl_count(GL_MAX_COMPUTE_SHADER_STORAGE_BLOCKS);
    check_limit(input_count + output_count + tables, inputs_text + ", " + outputs_text + tables_text + ", each a storage buffer", storage_limit,
                vulkan ? "maxPerStageDescriptorStorageBuffers" : "GL_MAX_COMPUTE_SHADER_STORAGE_BLOCKS");
    const std::size_t groups = (inputs.size() + 63) / 64;
    std::size_t group_limit = 0;
    if (vulkan) {
      group_limit = detail::vulkan_device_limits().work_groups;
    } else {
      GLint value = 0;
      glGetIntegeri_v(GL_MAX_COMPUTE_WORK_GROUP_COUNT, 0, &value);
      group_limit = static_cast<std::size_t>(std::max(value, 0));
    }
    if (groups > group_limit)
      throw error(what + "a " + std::to_string(inputs.width) + "x" + std::to_string(inputs.height) + " grid needs " + std::to_string(groups) +
                  " work groups of 64, more than one dispatch takes (" + std::to_string(group_limit) + ")");
  }
}

// The GL side of tables and blocks: each table a texture on the units after the inputs' (the
// vec4 tables RGBA32F, then the uvec4 tables RGBA32UI), each block a buffer the program fills
// (program::set_uniform_block); then the user's setter.
std::vector<texture_2d> bind_gl_resources(const program& kernel, const kernel_resources& resources, int first_unit, bool textures) {
  std::vector<texture_2d> made;
  if (textures) {
    made.reserve(resources.tables.size() + resources.uint_tables.size());
    const auto bind = [&](const auto& table, texel_format format) {
      const int unit = first_unit + static_cast<int>(made.size());
      made.emplace_back(table.width, table.height, format, table.texels.data());
      made.back().bind(unit);
      kernel.set(table.name + "_table", unit);
    };
    for (const kernel_table& table : resources.tables) bind(table, texel_format::rgba32f);
    for (const kernel_uint_table& table : resources.uint_tables) bind(table, texel_format::rgba32ui);
  }
  for (const kernel_block& block : resources.blocks) kernel.set_uniform_block(block.member + "_block", block.bytes.data(), block.bytes.size());
  if (resources.uniforms) resources.uniforms(kernel);
  return made;
}

template <typename Value>
std::vector<std::byte> bytes_of(const std::vector<Value>& values) {
  std::vector<std::byte> bytes(values.size() * sizeof(Value));
  if (!bytes.empty()) std::memcpy(bytes.data(), values.data(), bytes.size());
  return bytes;
}

template <typename Value>
std::vector<Value> values_of(const std::vector<std::byte>& bytes, std::size_t count) {
  std::vector<Value> values(count);
  std::memcpy(values.data(), bytes.data(), std::min(bytes.size(), count * sizeof(Value)));
  return values;
}

kernel_outputs run_gl_fragment(const std::string& what, const kernel_source& source, const kernel_inputs& inputs, target where,
                               const kernel_resources& resources) {
  const shader_library& shaders = shaders_for(std::string(run_name(shader_stage::fragment)) + " of " + source.name);
  default_context_again restore;
  context_for(where, std::string(run_name(shader_stage::fragment)) + " of " + source.name);
  check_run(what, source, inputs, shader_stage::fragment, where, resources);
  const std::string full_screen_triangle =
      glsl_preamble(where) + "void main() {\n  vec2 corner = vec2(float((gl_VertexID << 1) & 2), float(gl_VertexID & 2));\n"
                             "  gl_Position = vec4(corner * 4.0 - 1.0, 0.0, 1.0);\n}\n";
  program kernel = link_program("parity fragment kernel " + source.name + " (" + target_name(where) + ")",
                                {{shader_stage::vertex, shaders.expand_text(full_screen_triangle, "<parity full-screen triangle>")},
                                 {shader_stage::fragment, shaders.expand_text(fragment_source(source, inputs, where, resources), "<parity " + source.name + ">")}});
  std::vector<texture_2d> textures;
  for (const auto& input : inputs.floats) textures.emplace_back(inputs.width, inputs.height, texel_format::rgba32f, input.data());
  for (const auto& input : inputs.uints) textures.emplace_back(inputs.width, inputs.height, texel_format::rgba32ui, input.data());
  for (std::size_t i = 0; i < textures.size(); ++i) {
    const bool is_float = i < inputs.floats.size();
    kernel.set((is_float ? "float_input" + std::to_string(i) : "uint_input" + std::to_string(i - inputs.floats.size())), static_cast<int>(i));
    textures[i].bind(static_cast<int>(i));
  }
  const std::vector<texture_2d> tables = bind_gl_resources(kernel, resources, static_cast<int>(textures.size()), true);
  std::vector<texel_format> formats(static_cast<std::size_t>(source.float_outputs), texel_format::rgba32f);
  formats.insert(formats.end(), static_cast<std::size_t>(source.uint_outputs), texel_format::rgba32ui);
  framebuffer target(inputs.width, inputs.height, formats, false);
  target.bind();
  gl_vertex_array empty(generate_vertex_array());
  glBindVertexArray(empty.get());
  kernel.use();
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_BLEND);
  glDrawArrays(GL_TRIANGLES, 0, 3);
  check_gl("running parity fragment kernel " + source.name);

  // glReadPixels for floats too: GLES has no glGetTexImage (a float colour buffer reads back as
  // RGBA / FLOAT, EXT_color_buffer_float, which Mesa's GLES has).
  kernel_outputs outputs;
  for (int i = 0; i < source.float_outputs + source.uint_outputs; ++i) {
    const bool is_float = i < source.float_outputs;
    target.bind_for_reading(static_cast<std::size_t>(i));
    glPixelStorei(GL_PACK_ALIGNMENT, 4);
    if (is_float) {
      std::vector<glm::vec4> values(inputs.size());
      glReadPixels(0, 0, inputs.width, inputs.height, GL_RGBA, GL_FLOAT, values.data());
      outputs.floats.push_back(std::move(values));
    } else {
      std::vector<glm::uvec4> values(inputs.size());
      glReadPixels(0, 0, inputs.width, inputs.height, GL_RGBA_INTEGER, GL_UNSIGNED_INT, values.data());
      outputs.uints.push_back(std::move(values));
    }
  }
  check_gl("reading back parity fragment kernel " + source.name);
  return outputs;
}

// A buffer's contents read back: GLES has no glGetBufferSubData; mapping works on both.
template <typename Value>
std::vector<Value> read_buffer(GLenum binding_point, std::size_t count) {
  std::vector<Value> values(count);
  const auto bytes = static_cast<GLsizeiptr>(count * sizeof(Value));
  if (const void* mapped = glMapBufferRange(binding_point, 0, bytes, GL_MAP_READ_BIT)) {
    std::memcpy(values.data(), mapped, static_cast<std::size_t>(bytes));
    glUnmapBuffer(binding_point);
  }
  return values;
}

kernel_outputs run_gl_vertex(const std::string& what, const kernel_source& source, const kernel_inputs& inputs, target where,
                             const kernel_resources& resources) {
  const shader_library& shaders = shaders_for(std::string(run_name(shader_stage::vertex)) + " of " + source.name);
  default_context_again restore;
  context_for(where, std::string(run_name(shader_stage::vertex)) + " of " + source.name);
  check_run(what, source, inputs, shader_stage::vertex, where, resources);
  std::vector<std::string> varyings;
  for (int i = 0; i < source.float_outputs; ++i) varyings.push_back("fout" + std::to_string(i));
  for (int i = 0; i < source.uint_outputs; ++i) varyings.push_back("uout" + std::to_string(i));
  // GLES needs a fragment shader in every program; nothing is rasterised, so it does nothing.
  std::vector<stage_source> stages = {
      {shader_stage::vertex, shaders.expand_text(vertex_source(source, inputs, where, resources), "<parity " + source.name + ">")}};
  if (where == target::gles3) stages.push_back({shader_stage::fragment, shaders.expand_text(glsl_preamble(where) + "void main() {}\n", "<parity no fragment>")});
  program kernel = link_program("parity vertex kernel " + source.name + " (" + target_name(where) + ")", stages, varyings);
  const std::vector<texture_2d> tables = bind_gl_resources(kernel, resources, 0, true);

  const auto count = static_cast<GLsizei>(inputs.size());
  gl_vertex_array vertex_array(generate_vertex_array());
  glBindVertexArray(vertex_array.get());
  std::vector<gl_buffer> attribute_buffers;
  GLuint location = 0;
  for (const auto& input : inputs.floats) {
    attribute_buffers.emplace_back(generate_buffer());
    glBindBuffer(GL_ARRAY_BUFFER, attribute_buffers.back().get());
    glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(input.size() * sizeof(glm::vec4)), input.data(), GL_STATIC_DRAW);
    glEnableVertexAttribArray(location);
    glVertexAttribPointer(location++, 4, GL_FLOAT, GL_FALSE, 0, nullptr);
  }
  for (const auto& input : inputs.uints) {
    attribute_buffers.emplace_back(generate_buffer());
    glBindBuffer(GL_ARRAY_BUFFER, attribute_buffers.back().get());
    glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(input.size() * sizeof(glm::uvec4)), input.data(), GL_STATIC_DRAW);
    glEnableVertexAttribArray(location);
    glVertexAttribIPointer(location++, 4, GL_UNSIGNED_INT, 0, nullptr);
  }
  std::vector<gl_buffer> captured;
  for (std::size_t i = 0; i < varyings.size(); ++i) {
    captured.emplace_back(generate_buffer());
    glBindBuffer(GL_TRANSFORM_FEEDBACK_BUFFER, captured.back().get());
    glBufferData(GL_TRANSFORM_FEEDBACK_BUFFER, static_cast<GLsizeiptr>(inputs.size() * 16), nullptr, GL_STATIC_READ);
    glBindBufferBase(GL_TRANSFORM_FEEDBACK_BUFFER, static_cast<GLuint>(i), captured.back().get());
  }
  // Nothing is rasterised, but a draw still needs a complete framebuffer, and a surfaceless EGL
  // context has no default one (GL_INVALID_FRAMEBUFFER_OPERATION).
  const framebuffer nothing_drawn(1, 1, {texel_format::rgba32f}, false);
  nothing_drawn.bind();
  kernel.use();
  glEnable(GL_RASTERIZER_DISCARD);
  glBeginTransformFeedback(GL_POINTS);
  glDrawArrays(GL_POINTS, 0, count);
  glEndTransformFeedback();
  glDisable(GL_RASTERIZER_DISCARD);
  check_gl("running parity vertex kernel " + source.name);

  // Unbound from the transform feedback points first: GLES refuses to map a buffer still bound
  // there.
  for (std::size_t i = 0; i < varyings.size(); ++i) glBindBufferBase(GL_TRANSFORM_FEEDBACK_BUFFER, static_cast<GLuint>(i), 0);
  kernel_outputs outputs;
  for (std::size_t i = 0; i < varyings.size(); ++i) {
    glBindBuffer(GL_COPY_READ_BUFFER, captured[i].get());
    if (static_cast<int>(i) < source.float_outputs) outputs.floats.push_back(read_buffer<glm::vec4>(GL_COPY_READ_BUFFER, inputs.size()));
    else outputs.uints.push_back(read_buffer<glm::uvec4>(GL_COPY_READ_BUFFER, inputs.size()));
  }
  glBindBuffer(GL_COPY_READ_BUFFER, 0);
  glBindVertexArray(0);
  check_gl("reading back transform feedback of " + source.name);
  return outputs;
}

kernel_outputs run_gl_compute(const std::string& what, const kernel_source& source, const kernel_inputs& inputs, const kernel_resources& resources) {
  const shader_library& shaders = shaders_for(std::string(run_name(shader_stage::compute)) + " of " + source.name);
  default_context_again restore;
  context_for(target::gl45, std::string(run_name(shader_stage::compute)) + " of " + source.name);
  check_run(what, source, inputs, shader_stage::compute, target::gl45, resources);
  program kernel = link_program("parity compute kernel " + source.name + " (gl45)",
                                {{shader_stage::compute, shaders.expand_text(compute_source(source, inputs, target::gl45, resources), "<parity " + source.name + ">")}});
  bind_gl_resources(kernel, resources, 0, false);
  std::vector<gl_buffer> buffers;
  const auto storage = [&](const void* data, std::size_t bytes) {
    buffers.emplace_back(generate_buffer());
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, buffers.back().get());
    glBufferData(GL_SHADER_STORAGE_BUFFER, static_cast<GLsizeiptr>(bytes), data, data ? GL_STATIC_DRAW : GL_STATIC_READ);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, static_cast<GLuint>(buffers.size() - 1), buffers.back().get());
  };
  for (const auto& input : inputs.floats) storage(input.data(), input.size() * sizeof(glm::vec4));
  for (const auto& input : inputs.uints) storage(input.data(), input.size() * sizeof(glm::uvec4));
  const std::size_t first_output = buffers.size();
  for (int i = 0; i < source.float_outputs + source.uint_outputs; ++i) storage(nullptr, inputs.size() * 16);
  for (const kernel_table& table : resources.tables) storage(table.texels.data(), table.texels.size() * sizeof(glm::vec4));
  for (const kernel_uint_table& table : resources.uint_tables) storage(table.texels.data(), table.texels.size() * sizeof(glm::uvec4));
  kernel.use();
  glDispatchCompute(static_cast<GLuint>((inputs.size() + 63) / 64), 1, 1);
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  check_gl("running parity compute kernel " + source.name);
  kernel_outputs outputs;
  for (int i = 0; i < source.float_outputs + source.uint_outputs; ++i) {
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, buffers[first_output + static_cast<std::size_t>(i)].get());
    if (i < source.float_outputs) outputs.floats.push_back(read_buffer<glm::vec4>(GL_SHADER_STORAGE_BUFFER, inputs.size()));
    else outputs.uints.push_back(read_buffer<glm::uvec4>(GL_SHADER_STORAGE_BUFFER, inputs.size()));
  }
  for (std::size_t i = 0; i < buffers.size(); ++i) glBindBufferBase(GL_SHADER_STORAGE_BUFFER, static_cast<GLuint>(i), 0);
  check_gl("reading back parity compute kernel " + source.name);
  return outputs;
}

kernel_outputs run_vulkan_compute(const std::string& what, const kernel_source& source, const kernel_inputs& inputs, const kernel_resources& resources) {
  const shader_library& shaders = shaders_for(std::string(run_name(shader_stage::compute)) + " of " + source.name);
  if (const std::string reason = detail::vulkan_unavailable(); !reason.empty()) throw error(what + "target vulkan is unavailable: " + reason);
  check_run(what, source, inputs, shader_stage::compute, target::vulkan, resources);
  const expanded_source expanded = shaders.expand_text(compute_source(source, inputs, target::vulkan, resources), "<parity " + source.name + ">");
  const std::vector<std::uint32_t> spirv = detail::compile_vulkan_compute(source.name, expanded);
  std::vector<detail::vulkan_binding> bindings;
  for (const auto& input : inputs.floats) bindings.push_back({false, bytes_of(input), false});
  for (const auto& input : inputs.uints) bindings.push_back({false, bytes_of(input), false});
  for (int i = 0; i < source.float_outputs + source.uint_outputs; ++i)
    bindings.push_back({false, std::vector<std::byte>(inputs.size() * 16), true});
  for (const kernel_table& table : resources.tables) bindings.push_back({false, bytes_of(table.texels), false});
  for (const kernel_uint_table& table : resources.uint_tables) bindings.push_back({false, bytes_of(table.texels), false});
  for (const kernel_block& block : resources.blocks) bindings.push_back({true, block.bytes, false});
  const std::vector<std::vector<std::byte>> read =
      detail::run_vulkan_compute(source.name, spirv, bindings, static_cast<std::uint32_t>((inputs.size() + 63) / 64));
  kernel_outputs outputs;
  for (int i = 0; i < source.float_outputs; ++i) outputs.floats.push_back(values_of<glm::vec4>(read[static_cast<std::size_t>(i)], inputs.size()));
  for (int i = 0; i < source.uint_outputs; ++i)
    outputs.uints.push_back(values_of<glm::uvec4>(read[static_cast<std::size_t>(source.float_outputs + i)], inputs.size()));
  return outputs;
}

kernel_outputs run_on(shader_stage stage, const kernel_source& source, const kernel_inputs& inputs, target where, const kernel_resources& resources) {
  // The default target unnamed, as before targets existed.
  const std::string what = std::string("parity ") + run_name(stage) + " " + source.name +
                           (where == target::gl33 ? std::string() : std::string(" on ") + target_name(where)) + ": ";
  check_target(what, stage, where, resources);
  if (stage == shader_stage::fragment) return run_gl_fragment(what, source, inputs, where, resources);
  if (stage == shader_stage::vertex) return run_gl_vertex(what, source, inputs, where, resources);
  return where == target::vulkan ? run_vulkan_compute(what, source, inputs, resources) : run_gl_compute(what, source, inputs, resources);
}

}  // namespace

kernel_outputs run_fragment(const kernel_source& source, const kernel_inputs& inputs, const uniform_setter& uniforms) {
  return run_on(shader_stage::fragment, source, inputs, target::gl33, {{}, {}, uniforms});
}

kernel_outputs run_vertex(const kernel_source& source, const kernel_inputs& inputs, const uniform_setter& uniforms) {
  return run_on(shader_stage::vertex, source, inputs, target::gl33, {{}, {}, uniforms});
}

kernel_outputs run_fragment(const kernel_source& source, const kernel_inputs& inputs, target where, const kernel_resources& resources) {
  return run_on(shader_stage::fragment, source, inputs, where, resources);
}

kernel_outputs run_vertex(const kernel_source& source, const kernel_inputs& inputs, target where, const kernel_resources& resources) {
  return run_on(shader_stage::vertex, source, inputs, where, resources);
}

kernel_outputs run_compute(const kernel_source& source, const kernel_inputs& inputs, target where, const kernel_resources& resources) {
  return run_on(shader_stage::compute, source, inputs, where, resources);
}

}  // namespace vplkit::parity
