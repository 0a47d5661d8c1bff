// GLSL program loading: files from one or more shader folders, `#include "lib/....glsl"`
// resolved (each file once, recursively), and compile/link errors reported against the original
// file:line, not the expanded source. The expansion emits `#line <line> <file number>` around
// every include; the driver compiles that text renumbered by place (compiled_text), so the line in
// its log maps back to the file and line even where it prints the wrong file number.
//
// Installed with vplkit::parity (the program a uniform setter receives, the shader library of
// the parity runs), so it names no GL header: the GL names are plain unsigned and int here.
#pragma once

#include <cstdint>
#include <array>
#include <cstddef>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

#include <vplkit/gl/uniform_declarations.hpp>

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
  /// Every file the expansion read, the top-level file first (for build-system dependencies).
  std::vector<std::filesystem::path> files_read;
};

/// The shader directory: $VPLKIT_SHADER_DIR when set (the command line's --shader-dir comes
/// before it), else, for an executable inside vplkit's build tree, the source tree's shaders/,
/// else the share/vplkit/shaders installed beside the executable, else the configured prefix's.
std::filesystem::path default_shader_dir();

/// Preprocessor definitions placed right after #version: the GLSL side of a kernel's variant
/// template parameters (e.g. {"VPLKIT_VISIBILITY", "6"}).
using shader_defines = std::vector<std::pair<std::string, std::string>>;

/// Shader folders searched in order: the folders added with add_root, in the order added, then
/// the base folder (vplkit's shaders/). A file name (`#include "lib/irradiance.glsl"`, or the
/// file given to expand_file) is looked up relative to each folder, and the first that has it
/// wins, so one's own folder can shadow a vplkit file by giving its own copy.
class shader_library {
 public:
  /// Throws vplkit::error when `base` is not a folder.
  explicit shader_library(std::filesystem::path base);
  /// Adds a folder searched before the base folder and after the folders added earlier; a folder
  /// already searched is not added again. Throws vplkit::error when it is not a folder.
  void add_root(const std::filesystem::path& folder);
  /// The folders in search order; the base folder is last.
  const std::vector<std::filesystem::path>& roots() const { return roots_; }
  /// The file `relative_path` names: in the first folder that has it. Throws vplkit::error naming
  /// every folder looked in when none has it.
  std::filesystem::path locate(const std::string& relative_path) const;
  /// Expands a file found in the folders (e.g. "direct.frag"). Lines may end in LF, CRLF or a
  /// lone CR; the expansion's end in LF. Throws vplkit::error naming a missing or unreadable
  /// file, and the file:line for a missing include, an include nested more than
  /// max_include_depth deep, an expansion beyond max_expanded_bytes, a NUL byte (with its byte
  /// offset), or an #include line that is not `#include "path"` with at most a // comment after
  /// it (`#include <x>`, trailing text, a missing closing quote, an empty name): GLSL has no
  /// #include, so such a line is never left for the driver to fail on.
  expanded_source expand_file(const std::string& relative_path, const shader_defines& defines = {}) const;
  /// Expands in-memory text (generated shaders), shown in messages as `display_name`.
  expanded_source expand_text(const std::string& text, const std::string& display_name,
                              const shader_defines& defines = {}) const;
  /// Expands the file at `path` (anywhere; its includes are looked up in the folders), shown in
  /// messages as `path`.
  expanded_source expand_path(const std::filesystem::path& path, const shader_defines& defines = {}) const;

 private:
  std::vector<std::filesystem::path> roots_;
};

/// compute needs a GL 4.3+ context (vplkit::parity's gl45 target).
enum class shader_stage { vertex, fragment, compute };

/// A linked program with uniform setters (each binds the program: GL 3.3 has no glProgramUniform).
/// Setting a uniform that the source declares but the linker removed (a variant that does not
/// read it) is a no-op, as in GL; setting a name the source does not declare (a typo, a renamed
/// field) throws vplkit::error naming the program and the uniform.
class program {
 public:
  program() = default;
  /// Takes ownership of the linked GL program `name` (link_program makes them).
  program(unsigned name, std::string program_name, uniform_declarations declarations)
      : name_(name), program_name_(std::move(program_name)), declarations_(std::move(declarations)) {}
  ~program();
  program(program&& other) noexcept;
  program& operator=(program&& other) noexcept;
  program(const program&) = delete;
  program& operator=(const program&) = delete;
  /// The GL program name (a GLuint).
  unsigned id() const { return name_; }
  /// Binds the program (glUseProgram) and the buffers of its uniform blocks (set_uniform_block)
  /// to their binding points.
  void use() const;
  /// The uniform's location, -1 for a declared uniform the linker removed; throws for an
  /// undeclared name.
  int location(const std::string& uniform) const;
  void set(const std::string& uniform, int value) const;
  void set(const std::string& uniform, unsigned value) const;
  void set(const std::string& uniform, float value) const;
  void set(const std::string& uniform, const glm::vec2& value) const;
  void set(const std::string& uniform, const glm::vec3& value) const;
  void set(const std::string& uniform, const glm::vec4& value) const;
  void set(const std::string& uniform, const glm::ivec2& value) const;
  void set(const std::string& uniform, const glm::ivec3& value) const;
  void set(const std::string& uniform, const glm::mat4& value) const;
  /// Fills the uniform block `block` from `size` bytes (e.g. vplkit::std140_bytes(settings), for
  /// a `layout(std140) uniform block { twin member; };` that vplkit::std140_block writes): into a
  /// buffer the program owns, bound at binding point = the block's index whenever the program is
  /// used. A declared block the linker removed is a no-op, as for a uniform; an undeclared one,
  /// or fewer bytes than GL_UNIFORM_BLOCK_DATA_SIZE (the shader would read past them), throws
  /// vplkit::error naming the program and the block.
  void set_uniform_block(const std::string& block, const void* bytes, std::size_t size) const;
  template <std::size_t N>
  void set_uniform_block(const std::string& block, const std::array<std::byte, N>& bytes) const {
    set_uniform_block(block, bytes.data(), N);
  }

 private:
  unsigned name_ = 0;  // owned: deleted with the program, on the context current then
  std::string program_name_;
  uniform_declarations declarations_;
  // (binding point = block index, buffer name), owned like name_; filled by set_uniform_block.
  mutable std::vector<std::pair<unsigned, unsigned>> block_buffers_;
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

/// How many programs link_program has linked in this process (from any thread): what a change
/// costs in programs, e.g. that a setting applied in place (pipeline::apply_settings) links none.
std::uint64_t linked_program_count();

/// Loads a vertex and a fragment shader file from the library and links them; `defines` go
/// into both stages.
program load_program(const shader_library& library, const std::string& vertex_file,
                     const std::string& fragment_file, const shader_defines& defines = {});

/// Rewrites a driver log so that each "<source>:<line>(<column>)" (Mesa), "<source>(<line>)"
/// (NVIDIA) or "ERROR: <source>:<line>:" (AMD) reference names the original file and line.
std::string map_log_to_files(const std::string& log, const std::vector<std::string>& file_names);

/// The text link_program gives the driver for an expanded source: `text` with each `#line L S`
/// renumbered to the place of the line after it (`#line P S`, S kept), so the line any driver
/// reports is the line's place in `text`, from which map_compile_log finds the file and line
/// even when the driver prints the wrong source number (Mesa prints 0 for semantic errors such
/// as an undeclared name in an included file). `text` unchanged when a #line in it is not
/// plain numbers (a macro), which is not evaluated.
std::string compiled_text(const std::string& text);

/// Rewrites the log of a driver that compiled compiled_text(source.text), in any format
/// map_log_to_files reads, so that each reference names the file and line the reported line of
/// the expanded text came from (by its #line directives), whatever source number the driver
/// printed; the rest of each line is the driver's own text. Falls back to map_log_to_files
/// where compiled_text left the text unchanged or the line is beyond the text.
std::string map_compile_log(const std::string& log, const expanded_source& source);

}  // namespace vplkit
