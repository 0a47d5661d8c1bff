// vplkit::parity (vplkit/parity/parity.hpp): the runs on the headless context, the shader
// search path, and the comparison with its report. No test framework: the adapters in
// include/vplkit/parity/ turn a comparison into an assertion.
#include <vplkit/parity/parity.hpp>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <iomanip>
#include <limits>
#include <memory>
#include <optional>
#include <sstream>
#include <thread>

#include "frontend/core/error.hpp"
#include "frontend/gl/context.hpp"
#include "frontend/gl/debug_output.hpp"
#include "frontend/gl/gl_object.hpp"
#include "frontend/gl/render_target.hpp"
#include "frontend/parity/vulkan_compute.hpp"

namespace vplkit::parity {
namespace fs = std::filesystem;

namespace {

std::string environment_text(const char* name) {
  const char* value = std::getenv(name);
  return std::string(name) + (value && *value ? "=" + std::string(value) : " not set");
}

// The process's headless contexts, one per GL target, made on first use as the CLI makes them
// (VPLKIT_CONTEXT, VPLKIT_EGL_DEVICE); a failure is thrown again on the next use, which tries
// again. A context is current on one thread: the thread of the first parity call is kept so that
// a call from another one says so, instead of running GL calls without a context (they fail one
// by one and the first error a user sees is an empty "GLSL compile error").
struct parity_contexts {
  std::unique_ptr<gl_context> made[3];  // gl33, gl45, gles3
  const gl_context* current = nullptr;
  std::optional<std::thread::id> owner;
};

parity_contexts& contexts() {
  static parity_contexts state;
  return state;
}

std::string thread_name(std::thread::id thread) {
  std::ostringstream text;
  text << thread;
  return text.str();
}

// The first parity call's thread owns the contexts and the shader library; others are refused.
void check_owner_thread(const std::string& call) {
  parity_contexts& state = contexts();
  if (!state.owner) state.owner = std::this_thread::get_id();
  if (std::this_thread::get_id() == *state.owner) return;
  throw error("vplkit::parity: " + call + " was called on thread " + thread_name(std::this_thread::get_id()) +
              ", but the headless GL context is current on thread " + thread_name(*state.owner) +
              " (the thread of the first parity call, which made it): a GL context is current on one thread, so make every "
              "parity call on that one");
}

gl_profile profile_of(target where) {
  return where == target::gl45 ? gl_profile::core45 : where == target::gles3 ? gl_profile::es30 : gl_profile::core33;
}

// The context of a GL target, made if need be and current on return; `call` names the function
// for the error when this is not the owner thread.
const gl_context& context_for(target where, const std::string& call) {
  check_owner_thread(call);
  parity_contexts& state = contexts();
  std::unique_ptr<gl_context>& slot = state.made[static_cast<int>(where)];
  if (!slot) {
    headless_request request;
    request.profile = profile_of(where);
    try {
      slot = create_headless_context(request);
    } catch (const error& failure) {
      // Making a context may have left none current: the next use of another makes its own current.
      state.current = nullptr;
      const std::string what = where == target::gl33 ? std::string("GL context")
                                                     : std::string(gl_profile_name(request.profile)) + " context for target " + target_name(where);
      throw error("vplkit::parity needs a headless " + what + " and could not make one (" + environment_text("VPLKIT_CONTEXT") + ", " +
                  environment_text("VPLKIT_EGL_DEVICE") + "): " + failure.what());
    }
    state.current = slot.get();
  } else if (state.current != slot.get()) {
    slot->make_current();
    state.current = slot.get();
  }
  return *slot;
}

// A run on gl45 or gles3 makes the default (gl33) context current again when it ends, also by an
// exception: a test makes its textures in the default context between runs. Declared before the
// run's GL objects, so that they are deleted in the run's own context first.
struct default_context_again {
  ~default_context_again() {
    parity_contexts& state = contexts();
    const gl_context* default_context = state.made[0].get();
    if (!default_context || state.current == default_context) return;
    try {
      state.made[0]->make_current();
      state.current = default_context;
    } catch (const error&) {
      state.current = nullptr;  // the next run makes it current, or says why it cannot
    }
  }
};

// Where vplkit's shaders are when $VPLKIT_SHADER_DIR does not say: recorded by the header
// (VPLKIT_PARITY_SHADER_DIR of the CMake target) before main.
std::optional<fs::path>& recorded_vplkit_shader_dir() {
  static std::optional<fs::path> folder;
  return folder;
}

fs::path vplkit_shader_dir() {
  if (const char* from_environment = std::getenv("VPLKIT_SHADER_DIR"); from_environment && *from_environment) return from_environment;
  if (recorded_vplkit_shader_dir()) return *recorded_vplkit_shader_dir();
  throw error("vplkit::parity does not know where vplkit's shaders are: link the CMake target vplkit::parity (it records them), "
              "or set VPLKIT_SHADER_DIR to vplkit's shaders/ folder");
}

// The folders added before the library was made, and the library once made.
struct shader_search {
  std::vector<fs::path> pending_roots;
  std::unique_ptr<shader_library> library;
};

shader_search& search() {
  static shader_search state;
  return state;
}

}  // namespace

namespace detail {
bool record_vplkit_shader_dir(const char* folder) {
  recorded_vplkit_shader_dir() = fs::path(folder);
  return true;
}
}  // namespace detail

void add_shader_root(const fs::path& folder) {
  std::error_code ignored;
  if (!fs::is_directory(folder, ignored))
    throw error("vplkit::parity::add_shader_root: " + folder.string() + " is not a folder");
  shader_search& state = search();
  // Once made, the library is the context thread's (test_shaders hands it out there).
  if (state.library) {
    check_owner_thread("add_shader_root");
    state.library->add_root(folder);
  } else {
    state.pending_roots.push_back(folder);
  }
}

namespace {

const shader_library& shaders_for(const std::string& call) {
  check_owner_thread(call);
  shader_search& state = search();
  if (!state.library) {
    auto library = std::make_unique<shader_library>(vplkit_shader_dir());
    for (const fs::path& root : state.pending_roots) library->add_root(root);
    state.library = std::move(library);
    state.pending_roots.clear();
  }
  return *state.library;
}

}  // namespace

const shader_library& test_shaders() {
  context_for(target::gl33, "test_shaders");
  return shaders_for("test_shaders");
}

// The kind is a fact about the process, not a GL call: any thread may ask once it is made.
std::string test_context_kind() {
  if (const gl_context* made = contexts().made[0].get()) return made->kind();
  return context_for(target::gl33, "test_context_kind").kind();
}

const char* target_name(target where) {
  switch (where) {
    case target::gl33: return "gl33";
    case target::gl45: return "gl45";
    case target::gles3: return "gles3";
    case target::vulkan: return "vulkan";
  }
  return "unknown target";
}

const std::vector<target>& all_targets() {
  static const std::vector<target> targets = {target::gl33, target::gl45, target::gles3, target::vulkan};
  return targets;
}

std::string target_unavailable(target where) {
  if (where == target::vulkan) return detail::vulkan_unavailable();
  try {
    default_context_again restore;
    context_for(where, std::string("target_unavailable(") + target_name(where) + ")");
    return "";
  } catch (const error& failure) {
    return failure.what();
  }
}

std::string glsl_preamble(target where) {
  switch (where) {
    case target::gl33: return "#version 330 core\n";
    case target::gl45: return "#version 450 core\n";
    case target::gles3:
      return "#version 300 es\nprecision highp float;\nprecision highp int;\nprecision highp sampler2D;\nprecision highp usampler2D;\n";
    case target::vulkan: return "#version 450\n";
  }
  throw error("glsl_preamble: unknown target " + std::to_string(static_cast<int>(where)));
}

namespace {

std::string include_lines(const kernel_source& source) {
  std::string text;
  for (const auto& [name, value] : source.defines) text += "#define " + name + " " + value + "\n";
  for (const std::string& include : source.includes) text += "#include \"" + include + "\"\n";
  return text;
}

// The grid and every input's size, for the runs and for compare: a grid of 0 texels would
// compare nothing and pass, and an input shorter than the grid would be read past its end (by the
// upload, and by the report that lists a texel's inputs).
void check_grid(const std::string& what, const kernel_inputs& inputs) {
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
  for (std::size_t i = 0; i < resources.tables.size(); ++i) {
    const kernel_table& table = resources.tables[i];
    if (table.name.empty() || table.width < 1 || table.height < 1 ||
        table.texels.size() != static_cast<std::size_t>(table.width) * static_cast<std::size_t>(table.height))
      throw error(what + "table " + std::to_string(i) + " '" + table.name + "' is " + std::to_string(table.width) + "x" +
                  std::to_string(table.height) + " with " + std::to_string(table.texels.size()) +
                  " texels: it needs a name and width * height texels, at least 1x1");
  }
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
  const std::size_t tables = resources.tables.size();
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

// The declarations of a run's tables and uniform blocks, after the includes (a block's struct
// comes from a lib file) and before the kernel's own declarations (which read them). Textures in a
// fragment or vertex run, storage buffers from binding `first_buffer` in a compute run; the
// blocks' bindings follow the buffers on Vulkan (one set), and GL binds them by name.
std::string resource_declarations(const kernel_resources& resources, shader_stage stage, target where, int first_buffer) {
  std::ostringstream out;
  int binding = first_buffer;
  const std::string set = where == target::vulkan ? "set = 0, " : "";
  for (const kernel_table& table : resources.tables) {
    if (stage == shader_stage::compute) {
      out << "layout(std430, " << set << "binding = " << binding++ << ") readonly buffer " << table.name << "_table { vec4 " << table.name
          << "_texels[]; };\nvec4 " << table.name << "(ivec2 texel) { return " << table.name << "_texels[texel.y * " << table.width
          << " + texel.x]; }\n";
    } else {
      out << "uniform sampler2D " << table.name << "_table;\nvec4 " << table.name << "(ivec2 texel) { return texelFetch(" << table.name
          << "_table, texel, 0); }\n";
    }
  }
  for (const kernel_block& block : resources.blocks) {
    out << "layout(std140";
    if (where == target::vulkan) out << ", " << set << "binding = " << binding++;
    out << ") uniform " << block.member << "_block {\n  " << block.type << " " << block.member << ";\n};\n";
  }
  return out.str();
}

std::string fragment_source(const kernel_source& source, const kernel_inputs& inputs, target where, const kernel_resources& resources) {
  std::ostringstream out;
  out << glsl_preamble(where) << include_lines(source);
  for (std::size_t i = 0; i < inputs.floats.size(); ++i) out << "uniform sampler2D float_input" << i << ";\n";
  for (std::size_t i = 0; i < inputs.uints.size(); ++i) out << "uniform usampler2D uint_input" << i << ";\n";
  int location = 0;
  for (int i = 0; i < source.float_outputs; ++i) out << "layout(location = " << location++ << ") out vec4 float_output" << i << ";\n";
  for (int i = 0; i < source.uint_outputs; ++i) out << "layout(location = " << location++ << ") out uvec4 uint_output" << i << ";\n";
  out << resource_declarations(resources, shader_stage::fragment, where, 0);
  out << source.declarations << "\nvoid main() {\n  ivec2 texel = ivec2(gl_FragCoord.xy);\n";
  for (std::size_t i = 0; i < inputs.floats.size(); ++i) out << "  vec4 fin" << i << " = texelFetch(float_input" << i << ", texel, 0);\n";
  for (std::size_t i = 0; i < inputs.uints.size(); ++i) out << "  uvec4 uin" << i << " = texelFetch(uint_input" << i << ", texel, 0);\n";
  for (int i = 0; i < source.float_outputs; ++i) out << "  vec4 fout" << i << " = vec4(0.0);\n";
  for (int i = 0; i < source.uint_outputs; ++i) out << "  uvec4 uout" << i << " = uvec4(0u);\n";
  out << "  {\n" << source.body << "\n  }\n";
  for (int i = 0; i < source.float_outputs; ++i) out << "  float_output" << i << " = fout" << i << ";\n";
  for (int i = 0; i < source.uint_outputs; ++i) out << "  uint_output" << i << " = uout" << i << ";\n";
  out << "}\n";
  return out.str();
}

std::string vertex_source(const kernel_source& source, const kernel_inputs& inputs, target where, const kernel_resources& resources) {
  std::ostringstream out;
  out << glsl_preamble(where) << include_lines(source);
  int location = 0;
  for (std::size_t i = 0; i < inputs.floats.size(); ++i) out << "layout(location = " << location++ << ") in vec4 fin" << i << ";\n";
  for (std::size_t i = 0; i < inputs.uints.size(); ++i) out << "layout(location = " << location++ << ") in uvec4 uin" << i << ";\n";
  for (int i = 0; i < source.float_outputs; ++i) out << "out vec4 fout" << i << ";\n";
  for (int i = 0; i < source.uint_outputs; ++i) out << "flat out uvec4 uout" << i << ";\n";
  out << resource_declarations(resources, shader_stage::vertex, where, 0);
  out << source.declarations << "\nvoid main() {\n  ivec2 texel = ivec2(gl_VertexID % " << inputs.width << ", gl_VertexID / " << inputs.width << ");\n";
  for (int i = 0; i < source.float_outputs; ++i) out << "  fout" << i << " = vec4(0.0);\n";
  for (int i = 0; i < source.uint_outputs; ++i) out << "  uout" << i << " = uvec4(0u);\n";
  out << "  {\n" << source.body << "\n  }\n  gl_Position = vec4(0.0, 0.0, 0.0, 1.0);\n}\n";
  return out.str();
}

// One invocation per texel in work groups of 64; storage buffers in binding order: the float
// inputs, the uint inputs, the float outputs, the uint outputs, then the tables (and on Vulkan
// the uniform blocks).
std::string compute_source(const kernel_source& source, const kernel_inputs& inputs, target where, const kernel_resources& resources) {
  std::ostringstream out;
  const std::string set = where == target::vulkan ? "set = 0, " : "";
  out << glsl_preamble(where) << "layout(local_size_x = 64) in;\n" << include_lines(source);
  int binding = 0;
  for (std::size_t i = 0; i < inputs.floats.size(); ++i)
    out << "layout(std430, " << set << "binding = " << binding++ << ") readonly buffer float_input" << i << " { vec4 float_input" << i << "_values[]; };\n";
  for (std::size_t i = 0; i < inputs.uints.size(); ++i)
    out << "layout(std430, " << set << "binding = " << binding++ << ") readonly buffer uint_input" << i << " { uvec4 uint_input" << i << "_values[]; };\n";
  for (int i = 0; i < source.float_outputs; ++i)
    out << "layout(std430, " << set << "binding = " << binding++ << ") writeonly buffer float_output" << i << " { vec4 float_output" << i << "_values[]; };\n";
  for (int i = 0; i < source.uint_outputs; ++i)
    out << "layout(std430, " << set << "binding = " << binding++ << ") writeonly buffer uint_output" << i << " { uvec4 uint_output" << i << "_values[]; };\n";
  out << resource_declarations(resources, shader_stage::compute, where, binding);
  out << source.declarations << "\nvoid main() {\n  uint index = gl_GlobalInvocationID.x;\n  if (index >= " << inputs.size()
      << "u) return;\n  ivec2 texel = ivec2(int(index % " << inputs.width << "u), int(index / " << inputs.width << "u));\n";
  for (std::size_t i = 0; i < inputs.floats.size(); ++i) out << "  vec4 fin" << i << " = float_input" << i << "_values[index];\n";
  for (std::size_t i = 0; i < inputs.uints.size(); ++i) out << "  uvec4 uin" << i << " = uint_input" << i << "_values[index];\n";
  for (int i = 0; i < source.float_outputs; ++i) out << "  vec4 fout" << i << " = vec4(0.0);\n";
  for (int i = 0; i < source.uint_outputs; ++i) out << "  uvec4 uout" << i << " = uvec4(0u);\n";
  out << "  {\n" << source.body << "\n  }\n";
  for (int i = 0; i < source.float_outputs; ++i) out << "  float_output" << i << "_values[index] = fout" << i << ";\n";
  for (int i = 0; i < source.uint_outputs; ++i) out << "  uint_output" << i << "_values[index] = uout" << i << ";\n";
  out << "}\n";
  return out.str();
}

// The GL side of tables and blocks: each table a texture on the units after the inputs', each
// block a buffer the program fills (program::set_uniform_block); then the user's setter.
std::vector<texture_2d> bind_gl_resources(const program& kernel, const kernel_resources& resources, int first_unit, bool textures) {
  std::vector<texture_2d> made;
  if (textures) {
    made.reserve(resources.tables.size());
    for (std::size_t i = 0; i < resources.tables.size(); ++i) {
      const kernel_table& table = resources.tables[i];
      made.emplace_back(table.width, table.height, texel_format::rgba32f, table.texels.data());
      made.back().bind(first_unit + static_cast<int>(i));
      kernel.set(table.name + "_table", first_unit + static_cast<int>(i));
    }
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

std::int64_t ulp_distance(float a, float b) {
  auto ordered = [](float value) {
    std::int32_t bits;
    std::memcpy(&bits, &value, sizeof bits);
    // Map the sign-magnitude float order onto two's-complement order (-0 and +0 both to 0).
    return bits < 0 ? static_cast<std::int64_t>(std::int32_t{INT32_MIN}) - bits : static_cast<std::int64_t>(bits);
  };
  return std::llabs(ordered(a) - ordered(b));
}

namespace {

std::string describe_inputs(const kernel_inputs& inputs, std::size_t index) {
  std::ostringstream out;
  out << std::setprecision(9);
  for (std::size_t i = 0; i < inputs.floats.size(); ++i) {
    const glm::vec4& v = inputs.floats[i][index];
    out << " fin" << i << "=(" << v.x << ", " << v.y << ", " << v.z << ", " << v.w << ")";
  }
  for (std::size_t i = 0; i < inputs.uints.size(); ++i) {
    const glm::uvec4& v = inputs.uints[i][index];
    out << " uin" << i << "=(" << v.x << ", " << v.y << ", " << v.z << ", " << v.w << ")";
  }
  return out.str();
}

std::string texel_name(const kernel_inputs& inputs, std::size_t index, int channel) {
  const char* channels = "xyzw";
  return "texel (" + std::to_string(index % static_cast<std::size_t>(inputs.width)) + ", " +
         std::to_string(index / static_cast<std::size_t>(inputs.width)) + ")." + channels[channel];
}

std::string number_text(double value) {
  std::ostringstream text;
  text << std::setprecision(9) << value;
  return text.str();
}

// What every comparison needs before it counts anything. Each misuse here made compare() pass,
// or read out of bounds, rather than fail: a NaN, negative or above-1 allowed fraction (cast to a
// huge or arbitrary count of allowed mismatches), 0 or negative channels (nothing compared), 5 or
// more channels (past w), an empty grid, outputs or inputs shorter than the grid.
void check_comparison(const std::string& kernel, std::size_t gpu, std::size_t cpu, const kernel_inputs& inputs, int channels,
                      double allowed_mismatch_fraction) {
  const std::string what = "parity compare " + kernel + ": ";
  if (channels < 1 || channels > 4)
    throw error(what + "channels is " + std::to_string(channels) + "; it must be 1 to 4 (x, xy, xyz or xyzw)");
  if (!(allowed_mismatch_fraction >= 0.0 && allowed_mismatch_fraction <= 1.0))
    throw error(what + "allowed_mismatch_fraction is " + number_text(allowed_mismatch_fraction) + "; it must be in [0, 1]");
  check_grid(what, inputs);
  if (gpu != inputs.size() || cpu != inputs.size())
    throw error(what + "the outputs have gpu " + std::to_string(gpu) + " and cpu " + std::to_string(cpu) + " values for a " +
                std::to_string(inputs.width) + "x" + std::to_string(inputs.height) + " grid (" + std::to_string(inputs.size()) + " texels)");
}

// A tolerance that is NaN, infinite or negative passes everything, nothing, or depends on the
// comparison's direction; it is refused with the field that holds it.
void check_tolerance(const std::string& kernel, const tolerance& bounds, const kernel_inputs& inputs) {
  const std::string what = "parity compare " + kernel + ": the tolerance's ";
  const std::string rule = "; bounds must be finite and non-negative";
  if (!(std::isfinite(bounds.max_abs) && bounds.max_abs >= 0.0f)) throw error(what + "max_abs is " + number_text(bounds.max_abs) + rule);
  if (!(std::isfinite(bounds.max_rel) && bounds.max_rel >= 0.0f)) throw error(what + "max_rel is " + number_text(bounds.max_rel) + rule);
  if (bounds.max_ulp < 0) throw error(what + "max_ulp is " + std::to_string(bounds.max_ulp) + rule);
  if (bounds.abs_scale.empty()) return;
  if (bounds.abs_scale.size() != inputs.size())
    throw error(what + "abs_scale has " + std::to_string(bounds.abs_scale.size()) + " values for " + std::to_string(inputs.size()) + " texels");
  for (std::size_t index = 0; index < bounds.abs_scale.size(); ++index)
    for (int c = 0; c < 4; ++c)
      if (const float scale = bounds.abs_scale[index][c]; !(std::isfinite(scale) && scale >= 0.0f))
        throw error(what + "abs_scale of " + texel_name(inputs, index, c) + " is " + number_text(scale) + rule);
}

std::size_t allowed(std::size_t values, double fraction) {
  return static_cast<std::size_t>(std::floor(fraction * static_cast<double>(values)));
}

}  // namespace

comparison compare(const std::string& kernel, const std::vector<glm::vec4>& gpu, const std::vector<glm::vec4>& cpu,
                   const kernel_inputs& inputs, const tolerance& bounds, int channels) {
  check_comparison(kernel, gpu.size(), cpu.size(), inputs, channels, bounds.allowed_mismatch_fraction);
  check_tolerance(kernel, bounds, inputs);
  comparison result;
  result.kernel = kernel;
  result.bounds = bounds;
  const bool scaled = !bounds.abs_scale.empty();
  double worst_score = -1.0;
  std::size_t listed = 0;
  std::ostringstream list;
  list << std::setprecision(9);
  for (std::size_t index = 0; index < gpu.size(); ++index) {
    for (int c = 0; c < channels; ++c) {
      const float g = gpu[index][c], r = cpu[index][c];
      ++result.values;
      const bool finite = std::isfinite(g) && std::isfinite(r);
      const double abs_error = finite ? std::fabs(static_cast<double>(g) - static_cast<double>(r)) : INFINITY;
      const double magnitude = std::max(std::fabs(static_cast<double>(g)), std::fabs(static_cast<double>(r)));
      const double rel_error = finite ? (magnitude > 0.0 ? abs_error / magnitude : 0.0) : INFINITY;
      const std::int64_t ulps = finite ? ulp_distance(g, r) : INT64_MAX;
      const double abs_bound = static_cast<double>(bounds.max_abs) * (scaled ? static_cast<double>(bounds.abs_scale[index][c]) : 1.0);
      if (finite) {
        result.max_abs = std::max(result.max_abs, abs_error);
        result.max_rel = std::max(result.max_rel, rel_error);
        result.max_ulp = std::max(result.max_ulp, ulps);
        if (abs_bound > 0.0) result.max_abs_over_bound = std::max(result.max_abs_over_bound, abs_error / abs_bound);
      }
      const bool within = finite && (abs_error <= abs_bound || rel_error <= bounds.max_rel || ulps <= bounds.max_ulp);
      // The worst texel: non-finite first, then by the error measure relative to its bound.
      const double score = !finite ? INFINITY
                                   : std::min({abs_bound > 0 ? abs_error / abs_bound : abs_error * 1e30,
                                               bounds.max_rel > 0 ? rel_error / bounds.max_rel : rel_error * 1e30,
                                               bounds.max_ulp > 0 ? static_cast<double>(ulps) / static_cast<double>(bounds.max_ulp)
                                                                  : static_cast<double>(ulps) * 1e30});
      const auto detail = [&] {
        std::ostringstream text;
        text << std::setprecision(9) << texel_name(inputs, index, c) << ": gpu=" << g << " cpu=" << r << " (abs " << abs_error;
        if (scaled) text << " of " << abs_bound << " allowed";
        text << ", rel " << rel_error << ", ulp " << ulps << ");" << describe_inputs(inputs, index);
        return text.str();
      };
      if (score > worst_score) {
        worst_score = score;
        result.worst = detail();
      }
      if (!within) {
        ++result.mismatches;
        if (listed++ < 8) list << "\n    " << detail();
      }
    }
  }
  result.allowed_mismatches = allowed(result.values, bounds.allowed_mismatch_fraction);
  result.mismatch_list = list.str();
  return result;
}

comparison compare_exact(const std::string& kernel, const std::vector<glm::uvec4>& gpu, const std::vector<glm::uvec4>& cpu,
                         const kernel_inputs& inputs, double allowed_mismatch_fraction, int channels) {
  check_comparison(kernel, gpu.size(), cpu.size(), inputs, channels, allowed_mismatch_fraction);
  comparison result;
  result.kernel = kernel;
  result.bounds = {0.0f, 0.0f, 0, allowed_mismatch_fraction, "integers: exact"};
  std::size_t listed = 0;
  std::ostringstream list;
  for (std::size_t index = 0; index < gpu.size(); ++index) {
    for (int c = 0; c < channels; ++c) {
      ++result.values;
      if (gpu[index][c] == cpu[index][c]) continue;
      ++result.mismatches;
      const std::string detail = texel_name(inputs, index, c) + ": gpu=" + std::to_string(gpu[index][c]) +
                                 " cpu=" + std::to_string(cpu[index][c]) + ";" + describe_inputs(inputs, index);
      if (result.worst.empty()) result.worst = detail;
      if (listed++ < 8) list << "\n    " << detail;
    }
  }
  result.allowed_mismatches = allowed(result.values, allowed_mismatch_fraction);
  result.mismatch_list = list.str();
  return result;
}

std::string comparison::summary() const {
  std::ostringstream out;
  out << std::setprecision(3) << "parity " << kernel << ": " << values << " values, " << mismatches
      << " outside tolerance (allowed " << allowed_mismatches << "), max abs " << max_abs << ", max rel " << max_rel
      << ", max ulp " << max_ulp;
  if (!bounds.abs_scale.empty()) out << ", max abs / its bound " << max_abs_over_bound;
  out << "\n  worst " << worst;
  if (!passed())
    out << "\n  tolerance: abs <= " << bounds.max_abs << (bounds.abs_scale.empty() ? "" : " x the texel's abs_scale") << " or rel <= "
        << bounds.max_rel << " or ulp <= " << bounds.max_ulp << ", allowed fraction " << bounds.allowed_mismatch_fraction
        << (bounds.reason.empty() ? "" : " (" + bounds.reason + ")");
  return out.str();
}

}  // namespace vplkit::parity
