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

namespace vplkit::parity {
namespace fs = std::filesystem;

namespace {

std::string environment_text(const char* name) {
  const char* value = std::getenv(name);
  return std::string(name) + (value && *value ? "=" + std::string(value) : " not set");
}

// The process's headless context, made on first use as the CLI makes it (VPLKIT_CONTEXT,
// VPLKIT_EGL_DEVICE); a failure is thrown again on the next use, which tries again. A context is
// current on one thread, the one that made it: the thread is kept so that a call from another
// one says so, instead of running GL calls without a context (they fail one by one and the first
// error a user sees is an empty "GLSL compile error").
struct owned_context {
  std::unique_ptr<gl_context> context;
  std::thread::id thread;
};

const owned_context& made_context() {
  static const owned_context made = [] {
    try {
      return owned_context{create_headless_context(), std::this_thread::get_id()};
    } catch (const error& failure) {
      throw error("vplkit::parity needs a headless GL context and could not make one (" + environment_text("VPLKIT_CONTEXT") + ", " +
                  environment_text("VPLKIT_EGL_DEVICE") + "): " + failure.what());
    }
  }();
  return made;
}

std::string thread_name(std::thread::id thread) {
  std::ostringstream text;
  text << thread;
  return text.str();
}

void check_owner_thread(const owned_context& made, const std::string& call) {
  if (std::this_thread::get_id() == made.thread) return;
  throw error("vplkit::parity: " + call + " was called on thread " + thread_name(std::this_thread::get_id()) +
              ", but the headless GL context is current on thread " + thread_name(made.thread) +
              " (the thread of the first parity call, which made it): a GL context is current on one thread, so make every "
              "parity call on that one");
}

// The context, current on this thread; `call` names the function for the error when it is not.
const gl_context& test_context(const std::string& call) {
  const owned_context& made = made_context();
  check_owner_thread(made, call);
  return *made.context;
}

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
    check_owner_thread(made_context(), "add_shader_root");
    state.library->add_root(folder);
  } else {
    state.pending_roots.push_back(folder);
  }
}

namespace {

const shader_library& shaders_for(const std::string& call) {
  test_context(call);
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

const shader_library& test_shaders() { return shaders_for("test_shaders"); }

// The kind is a fact about the process, not a GL call: any thread may ask.
std::string test_context_kind() { return made_context().context->kind(); }

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

// What a run asks of its stage, checked against this context's limits before anything is made,
// so that too many inputs or outputs are named as such rather than surfacing as a list of GL
// errors from the texture uploads or the link. GL 3.3 guarantees 16 texture units per stage, 16
// vertex attributes, 8 draw buffers and 4 separate transform feedback outputs.
void check_run(const kernel_source& source, const kernel_inputs& inputs, shader_stage stage) {
  const bool fragment = stage == shader_stage::fragment;
  const std::string what = std::string("parity ") + (fragment ? "run_fragment " : "run_vertex ") + source.name + ": ";
  check_grid(what, inputs);
  if (source.float_outputs < 0 || source.uint_outputs < 0)
    throw error(what + "float_outputs " + std::to_string(source.float_outputs) + " and uint_outputs " + std::to_string(source.uint_outputs) +
                ": an output count cannot be negative");
  if (source.float_outputs + source.uint_outputs == 0) throw error(what + "the kernel has no outputs: set float_outputs or uint_outputs");
  const auto check_limit = [&](std::size_t count, const std::string& things, GLenum limit_name, const char* limit_text, const std::string& advice) {
    const GLint limit = gl_limit(limit_name);
    if (count > static_cast<std::size_t>(std::max(limit, 0)))
      throw error(what + std::to_string(count) + " " + things + ", but " + (fragment ? "a fragment" : "a vertex") + " shader has at most " +
                  std::to_string(limit) + " (" + limit_text + " of this context): " + advice);
  };
  const std::size_t input_count = inputs.floats.size() + inputs.uints.size();
  const std::string inputs_text = "inputs (" + std::to_string(inputs.floats.size()) + " float, " + std::to_string(inputs.uints.size()) + " uint)";
  const std::size_t output_count = static_cast<std::size_t>(source.float_outputs) + static_cast<std::size_t>(source.uint_outputs);
  const std::string outputs_text = "outputs (" + std::to_string(source.float_outputs) + " float, " + std::to_string(source.uint_outputs) + " uint)";
  const std::string split = "split the kernel into runs with fewer, or pack more values into each vec4";
  if (fragment) {
    check_limit(input_count, inputs_text + ", each a texture", GL_MAX_TEXTURE_IMAGE_UNITS, "GL_MAX_TEXTURE_IMAGE_UNITS", split);
    check_limit(output_count, outputs_text + ", each a render target", GL_MAX_DRAW_BUFFERS, "GL_MAX_DRAW_BUFFERS", split);
  } else {
    check_limit(input_count, inputs_text + ", each a vertex attribute", GL_MAX_VERTEX_ATTRIBS, "GL_MAX_VERTEX_ATTRIBS", split);
    check_limit(output_count, outputs_text + ", each captured by transform feedback", GL_MAX_TRANSFORM_FEEDBACK_SEPARATE_ATTRIBS,
                "GL_MAX_TRANSFORM_FEEDBACK_SEPARATE_ATTRIBS", split);
    // One vertex per texel, drawn with a GLsizei count.
    if (inputs.size() > static_cast<std::size_t>(std::numeric_limits<GLsizei>::max()))
      throw error(what + "a " + std::to_string(inputs.width) + "x" + std::to_string(inputs.height) + " grid is more vertices than one draw takes (" +
                  std::to_string(std::numeric_limits<GLsizei>::max()) + ")");
  }
}

std::string fragment_source(const kernel_source& source, const kernel_inputs& inputs) {
  std::ostringstream out;
  out << "#version 330 core\n" << include_lines(source);
  for (std::size_t i = 0; i < inputs.floats.size(); ++i) out << "uniform sampler2D float_input" << i << ";\n";
  for (std::size_t i = 0; i < inputs.uints.size(); ++i) out << "uniform usampler2D uint_input" << i << ";\n";
  int location = 0;
  for (int i = 0; i < source.float_outputs; ++i) out << "layout(location = " << location++ << ") out vec4 float_output" << i << ";\n";
  for (int i = 0; i < source.uint_outputs; ++i) out << "layout(location = " << location++ << ") out uvec4 uint_output" << i << ";\n";
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

std::string vertex_source(const kernel_source& source, const kernel_inputs& inputs) {
  std::ostringstream out;
  out << "#version 330 core\n" << include_lines(source);
  int location = 0;
  for (std::size_t i = 0; i < inputs.floats.size(); ++i) out << "layout(location = " << location++ << ") in vec4 fin" << i << ";\n";
  for (std::size_t i = 0; i < inputs.uints.size(); ++i) out << "layout(location = " << location++ << ") in uvec4 uin" << i << ";\n";
  for (int i = 0; i < source.float_outputs; ++i) out << "out vec4 fout" << i << ";\n";
  for (int i = 0; i < source.uint_outputs; ++i) out << "flat out uvec4 uout" << i << ";\n";
  out << source.declarations << "\nvoid main() {\n";
  for (int i = 0; i < source.float_outputs; ++i) out << "  fout" << i << " = vec4(0.0);\n";
  for (int i = 0; i < source.uint_outputs; ++i) out << "  uout" << i << " = uvec4(0u);\n";
  out << "  {\n" << source.body << "\n  }\n  gl_Position = vec4(0.0, 0.0, 0.0, 1.0);\n}\n";
  return out.str();
}

}  // namespace

kernel_outputs run_fragment(const kernel_source& source, const kernel_inputs& inputs, const uniform_setter& uniforms) {
  const shader_library& shaders = shaders_for("run_fragment of " + source.name);
  check_run(source, inputs, shader_stage::fragment);
  static const char* const full_screen_triangle =
      "#version 330 core\nvoid main() {\n  vec2 corner = vec2(float((gl_VertexID << 1) & 2), float(gl_VertexID & 2));\n"
      "  gl_Position = vec4(corner * 4.0 - 1.0, 0.0, 1.0);\n}\n";
  program kernel = link_program("parity fragment kernel " + source.name,
                                {{shader_stage::vertex, shaders.expand_text(full_screen_triangle, "<parity full-screen triangle>")},
                                 {shader_stage::fragment, shaders.expand_text(fragment_source(source, inputs), "<parity " + source.name + ">")}});
  std::vector<texture_2d> textures;
  for (const auto& input : inputs.floats) textures.emplace_back(inputs.width, inputs.height, texel_format::rgba32f, input.data());
  for (const auto& input : inputs.uints) textures.emplace_back(inputs.width, inputs.height, texel_format::rgba32ui, input.data());
  for (std::size_t i = 0; i < textures.size(); ++i) {
    const bool is_float = i < inputs.floats.size();
    kernel.set((is_float ? "float_input" + std::to_string(i) : "uint_input" + std::to_string(i - inputs.floats.size())), static_cast<int>(i));
    textures[i].bind(static_cast<int>(i));
  }
  if (uniforms) uniforms(kernel);
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

  kernel_outputs outputs;
  for (int i = 0; i < source.float_outputs; ++i) {
    outputs.floats.push_back(target.read_image(static_cast<std::size_t>(i)).texels);
  }
  for (int i = 0; i < source.uint_outputs; ++i) {
    const std::vector<std::uint32_t> texels = target.read_uint(static_cast<std::size_t>(source.float_outputs + i));
    std::vector<glm::uvec4> values(inputs.size());
    std::memcpy(values.data(), texels.data(), texels.size() * sizeof(std::uint32_t));
    outputs.uints.push_back(std::move(values));
  }
  return outputs;
}

kernel_outputs run_vertex(const kernel_source& source, const kernel_inputs& inputs, const uniform_setter& uniforms) {
  const shader_library& shaders = shaders_for("run_vertex of " + source.name);
  check_run(source, inputs, shader_stage::vertex);
  std::vector<std::string> varyings;
  for (int i = 0; i < source.float_outputs; ++i) varyings.push_back("fout" + std::to_string(i));
  for (int i = 0; i < source.uint_outputs; ++i) varyings.push_back("uout" + std::to_string(i));
  program kernel = link_program("parity vertex kernel " + source.name,
                                {{shader_stage::vertex, shaders.expand_text(vertex_source(source, inputs), "<parity " + source.name + ">")}},
                                varyings);
  if (uniforms) uniforms(kernel);

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
  kernel.use();
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

  kernel_outputs outputs;
  for (std::size_t i = 0; i < varyings.size(); ++i) {
    glBindBuffer(GL_TRANSFORM_FEEDBACK_BUFFER, captured[i].get());
    if (static_cast<int>(i) < source.float_outputs) {
      std::vector<glm::vec4> values(inputs.size());
      glGetBufferSubData(GL_TRANSFORM_FEEDBACK_BUFFER, 0, static_cast<GLsizeiptr>(values.size() * sizeof(glm::vec4)), values.data());
      outputs.floats.push_back(std::move(values));
    } else {
      std::vector<glm::uvec4> values(inputs.size());
      glGetBufferSubData(GL_TRANSFORM_FEEDBACK_BUFFER, 0, static_cast<GLsizeiptr>(values.size() * sizeof(glm::uvec4)), values.data());
      outputs.uints.push_back(std::move(values));
    }
  }
  for (std::size_t i = 0; i < varyings.size(); ++i) glBindBufferBase(GL_TRANSFORM_FEEDBACK_BUFFER, static_cast<GLuint>(i), 0);
  glBindVertexArray(0);
  check_gl("reading back transform feedback of " + source.name);
  return outputs;
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
