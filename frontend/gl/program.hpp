// GLSL program loading: files from a shader directory, `#include "lib/....glsl"` resolved
// (each file once, recursively), and compile/link errors reported against the original
// file:line, not the expanded source. The expansion emits `#line <line> <file number>` around
// every include; the driver's log then names (file number, line), which map back to file names.
#pragma once

#include <cstddef>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

#include "frontend/gl/gl.hpp"
#include "frontend/gl/gl_object.hpp"
#include "frontend/gl/uniform_declarations.hpp"

namespace vplkit {

/// The deepest chain of #include a shader may make (vplkit's own nest 3 deep).
inline constexpr int max_include_depth = 32;
/// The most text a shader with all its includes may expand to (each file is read once).
inline constexpr std::size_t max_expanded_bytes = std::size_t{16} << 20;

/// One shader stage's source after #include expansion.
struct expanded_source {
  std::string text;
  /// GLSL source-string number (the second argument of #line) -> file name for messages.
  std::vector<std::string> file_names;
};

/// The shader directory: --shader-dir when given, else $VPLKIT_SHADER_DIR, else the source
/// tree's shaders/ when it exists, else the installed share/vplkit/shaders.
std::filesystem::path default_shader_dir();

/// Preprocessor definitions placed right after #version: the GLSL side of a kernel's variant
/// template parameters (e.g. {"VPLKIT_VISIBILITY", "6"}).
using shader_defines = std::vector<std::pair<std::string, std::string>>;

class shader_library {
 public:
  explicit shader_library(std::filesystem::path root);
  const std::filesystem::path& root() const { return root_; }
  /// Expands a file under root (e.g. "direct.frag"). Throws vplkit::error naming a missing or
  /// unreadable file, and the including file:line for a missing include, an include nested more
  /// than max_include_depth deep, or an expansion beyond max_expanded_bytes.
  expanded_source expand_file(const std::string& relative_path, const shader_defines& defines = {}) const;
  /// Expands in-memory text (generated shaders), shown in messages as `display_name`.
  expanded_source expand_text(const std::string& text, const std::string& display_name,
                              const shader_defines& defines = {}) const;

 private:
  std::filesystem::path root_;
};

enum class shader_stage { vertex, fragment };

/// A linked program with uniform setters (each binds the program: GL 3.3 has no glProgramUniform).
/// Setting a uniform that the source declares but the linker removed (a variant that does not
/// read it) is a no-op, as in GL; setting a name the source does not declare (a typo, a renamed
/// field) throws vplkit::error naming the program and the uniform.
class program {
 public:
  program() = default;
  program(gl_program name, std::string program_name, uniform_declarations declarations)
      : name_(std::move(name)), program_name_(std::move(program_name)), declarations_(std::move(declarations)) {}
  GLuint id() const { return name_.get(); }
  void use() const { glUseProgram(name_.get()); }
  /// The uniform's location, -1 for a declared uniform the linker removed; throws for an
  /// undeclared name.
  GLint location(const std::string& uniform) const;
  void set(const std::string& uniform, int value) const;
  void set(const std::string& uniform, unsigned value) const;
  void set(const std::string& uniform, float value) const;
  void set(const std::string& uniform, const glm::vec2& value) const;
  void set(const std::string& uniform, const glm::vec3& value) const;
  void set(const std::string& uniform, const glm::vec4& value) const;
  void set(const std::string& uniform, const glm::ivec2& value) const;
  void set(const std::string& uniform, const glm::mat4& value) const;

 private:
  gl_program name_;
  std::string program_name_;
  uniform_declarations declarations_;
};

struct stage_source {
  shader_stage stage;
  expanded_source source;
};

/// Compiles and links. Errors name the program, the stage, and original file:line per message.
/// `transform_feedback_varyings`, when not empty, are captured interleaved-separately
/// (GL_SEPARATE_ATTRIBS), one buffer each.
program link_program(const std::string& program_name, const std::vector<stage_source>& stages,
                     const std::vector<std::string>& transform_feedback_varyings = {});

/// Loads a vertex and a fragment shader file from the library and links them; `defines` go
/// into both stages.
program load_program(const shader_library& library, const std::string& vertex_file,
                     const std::string& fragment_file, const shader_defines& defines = {});

/// Rewrites a driver log so that each "<source>:<line>(<column>)" (Mesa), "<source>(<line>)"
/// (NVIDIA) or "ERROR: <source>:<line>:" (AMD) reference names the original file and line.
std::string map_log_to_files(const std::string& log, const std::vector<std::string>& file_names);

}  // namespace vplkit
