#include <vplkit/gl/program.hpp>

#include <algorithm>
#include <atomic>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <optional>
#include <string_view>
#include <set>
#include <sstream>
#include <type_traits>

#include <glm/gtc/type_ptr.hpp>

#include "frontend/gl/debug_output.hpp"
#include "frontend/gl/gl.hpp"
#include "frontend/gl/gl_object.hpp"
#include <vplkit/gl/settings_uniforms.hpp>
#include "frontend/core/error.hpp"
#include "frontend/core/files.hpp"

namespace vplkit {
namespace fs = std::filesystem;

namespace {

// Whether `inner` is `outer` or lies below it (both canonical).
bool is_within(const fs::path& inner, const fs::path& outer) {
  return std::mismatch(outer.begin(), outer.end(), inner.begin(), inner.end()).first == outer.end();
}

}  // namespace

// Decided by where the running executable is, not by which folders exist: an installed vplkit
// once read the source tree's shaders whenever that tree was still on the machine, so editing a
// checkout changed what an installed binary drew. An executable inside the build tree (vplkit's
// own tools and tests) reads the source tree; an installed one reads the shaders installed beside
// it (found relative to the executable, so a moved prefix still finds its own); any other the
// prefix the build was configured for.
fs::path default_shader_dir() {
  if (const char* from_environment = std::getenv("VPLKIT_SHADER_DIR"); from_environment && *from_environment)
    return from_environment;
  std::error_code failed;
  const fs::path executable = fs::canonical("/proc/self/exe", failed);
  if (!failed) {
    // Beside it first: a prefix may itself lie inside the build tree (the tests install there).
    const fs::path beside = (executable.parent_path() / VPLKIT_INSTALLED_SHADER_DIR_FROM_BIN).lexically_normal();
    if (fs::is_directory(beside / "lib", failed)) return beside;
    const fs::path build_tree = fs::weakly_canonical(VPLKIT_BUILD_DIR, failed);
    if (!failed && is_within(executable, build_tree)) return VPLKIT_SOURCE_SHADER_DIR;
  }
  return VPLKIT_INSTALLED_SHADER_DIR;
}

namespace {
std::atomic<std::uint64_t>& linked_programs() {
  static std::atomic<std::uint64_t> count{0};
  return count;
}
}  // namespace

std::uint64_t linked_program_count() { return linked_programs().load(std::memory_order_relaxed); }

// The public header names GL's integer types by their C++ types.
static_assert(std::is_same_v<GLuint, unsigned> && std::is_same_v<GLint, int>, "GLuint and GLint are unsigned and int");

namespace {

// The first of `roots` that has `relative`, or nothing.
std::optional<fs::path> find_in(const std::vector<fs::path>& roots, const std::string& relative) {
  std::error_code ignored;
  for (const fs::path& root : roots)
    if (fs::exists(root / relative, ignored)) return root / relative;
  return std::nullopt;
}

std::string folder_list(const std::vector<fs::path>& roots) {
  std::string list;
  for (const fs::path& root : roots) list += (list.empty() ? "" : ", ") + root.string();
  return list;
}

// A shader's text. The not-found message says where shaders are looked for; read_file does the
// rest (a regular file, at most 16 MiB: no shader is near that).
std::string read_text_file(const fs::path& path, const std::string& what_for) {
  std::error_code ignored;
  if (!fs::exists(path, ignored)) throw error("shader file not found: " + path.string() + what_for);
  return read_file(path, std::uintmax_t{1} << 24, "shader file");
}

bool is_blank(char c) { return c == ' ' || c == '\t'; }

std::string_view skip_blanks(std::string_view text) {
  while (!text.empty() && is_blank(text.front())) text.remove_prefix(1);
  return text;
}

// For a preprocessor line "# name ...", the text after the name; nothing for any other line.
// Scanned by hand: a std::regex recurses per character and overflows the stack on long lines.
std::optional<std::string_view> directive(std::string_view line, std::string_view name) {
  line = skip_blanks(line);
  if (line.empty() || line.front() != '#') return std::nullopt;
  line = skip_blanks(line.substr(1));
  if (line.substr(0, name.size()) != name) return std::nullopt;
  line.remove_prefix(name.size());
  if (!line.empty()) {
    const char next = line.front();
    if ((next >= 'a' && next <= 'z') || (next >= 'A' && next <= 'Z') || (next >= '0' && next <= '9') || next == '_') return std::nullopt;
  }
  return line;
}

// An `#include` line: the path it names, or why it is not one vplkit expands.
struct include_line {
  std::string path;
  std::string refusal;  ///< empty when `path` is the include
};

// `#include "path"`, optionally followed by a // comment: the path. Any other spelling of an
// #include line is refused with the reason: GLSL has no #include, so a line left in the
// "self-contained" text would only fail later, as a driver's compile error far from its cause.
// Nothing for a line that is not an #include.
std::optional<include_line> include_of(std::string_view line) {
  std::optional<std::string_view> rest = directive(line, "include");
  if (!rest) return std::nullopt;
  const std::string_view text = skip_blanks(*rest);
  const auto refused = [](std::string why) { return include_line{{}, std::move(why)}; };
  if (text.empty()) return refused("no file name after #include");
  if (text.front() == '<') return refused("#include <...> is not expanded: vplkit expands #include \"path\", looked up in the shader folders");
  if (text.front() != '"') return refused("expected #include \"path\", not '" + excerpt(text, 60) + "'");
  const std::size_t close = text.find('"', 1);
  if (close == std::string_view::npos) return refused("the file name has no closing quote");
  if (close == 1) return refused("the file name is empty");
  const std::string_view after = skip_blanks(text.substr(close + 1));
  if (!after.empty() && after.substr(0, 2) != "//")
    return refused("text after the file name: '" + excerpt(after, 60) + "' (only a // comment may follow)");
  return include_line{std::string(text.substr(1, close - 1)), {}};
}

// The next line of `text` from `at`, without its end: LF, CRLF or a lone CR (old Mac files), so
// that an #include in a CR-only file is seen as a line of its own. `at` moves past the end.
std::string_view next_line(std::string_view text, std::size_t& at) {
  const std::size_t end = text.find_first_of("\r\n", at);
  const std::string_view line = text.substr(at, end == std::string_view::npos ? std::string_view::npos : end - at);
  if (end == std::string_view::npos) at = text.size();
  else at = end + (text[end] == '\r' && end + 1 < text.size() && text[end + 1] == '\n' ? 2 : 1);
  return line;
}

// The includes form a tree walked depth first: recursion is fine because its depth is bounded
// (max_include_depth; a chain of 10,000 includes overflowed the stack), and so is the text it
// makes (max_expanded_bytes: each file once, but a wide tree of large files adds up).
class expander {
 public:
  expander(const std::vector<fs::path>& roots, const shader_defines& defines) : roots_(roots), defines_(defines) {}

  /// `top_file`: where `text` was read from, when it was (for files_read).
  expanded_source run(const std::string& text, const std::string& display_name, const std::optional<fs::path>& top_file = {}) {
    if (top_file) {
      files_read_.push_back(*top_file);
      included_.insert(fs::weakly_canonical(*top_file).string());
    }
    expand(text, display_name, /*top_level=*/true, 0);
    return {out_.str(), file_names_, files_read_};
  }

 private:
  void expand(const std::string& text, const std::string& display_name, bool top_level, int depth) {
    expanded_bytes_ += text.size();
    if (expanded_bytes_ > max_expanded_bytes)
      throw error(excerpt_path(display_name) + ": the shader with its includes exceeds " + std::to_string(max_expanded_bytes >> 20) + " MiB");
    const int file_number = static_cast<int>(file_names_.size());
    file_names_.push_back(display_name);
    int line_number = 0;
    bool wrote_line_directive = false;
    for (std::size_t at = 0; at < text.size();) {
      const std::size_t line_start = at;
      const std::string_view line = next_line(text, at);
      ++line_number;
      const auto where = [&] { return excerpt_path(display_name) + ":" + std::to_string(line_number); };
      // glShaderSource reads the text up to its first NUL: the rest would vanish without a word.
      if (const std::size_t nul = line.find('\0'); nul != std::string_view::npos)
        throw error(where() + ": a NUL byte (byte offset " + std::to_string(line_start + nul) + " of the file); a shader is text");
      if (directive(line, "version")) {
        if (!top_level || line_number != 1)
          throw error(where() + ": #version must be the first line of the top-level shader, not in an included file");
        out_ << line << "\n";
        for (const auto& [name, value] : defines_) out_ << "#define " << name << " " << value << "\n";
        continue;
      }
      if (!wrote_line_directive) {
        out_ << "#line " << line_number << " " << file_number << "\n";
        wrote_line_directive = true;
      }
      if (const std::optional<include_line> included = include_of(line)) {
        if (!included->refusal.empty()) throw error(where() + ": " + included->refusal);
        const std::string& relative = included->path;
        // Longer than any path a file system takes (PATH_MAX is 4096 on Linux).
        if (relative.size() > 4096)
          throw error(where() + ": the included file name has " + std::to_string(relative.size()) +
                      " characters, more than a path can have");
        const std::optional<fs::path> path = find_in(roots_, relative);
        if (!path)
          throw error(where() + ": included file \"" + excerpt_path(relative) +
                      "\" not found (looked in " + folder_list(roots_) + ")");
        if (included_.insert(fs::weakly_canonical(*path).string()).second) {
          if (depth + 1 > max_include_depth)
            throw error(where() + ": including \"" + excerpt_path(relative) +
                        "\" nests includes more than " + std::to_string(max_include_depth) + " deep");
          files_read_.push_back(*path);
          expand(read_text_file(*path, ""), relative, /*top_level=*/false, depth + 1);
        }
        out_ << "#line " << (line_number + 1) << " " << file_number << "\n";
        continue;
      }
      out_ << line << "\n";
    }
  }

  const std::vector<fs::path>& roots_;
  const shader_defines& defines_;
  std::ostringstream out_;
  std::vector<std::string> file_names_;
  std::vector<fs::path> files_read_;
  std::set<std::string> included_;
  std::size_t expanded_bytes_ = 0;
};

const char* stage_name(shader_stage stage) {
  return stage == shader_stage::vertex ? "vertex" : stage == shader_stage::fragment ? "fragment" : "compute";
}

}  // namespace

shader_library::shader_library(fs::path base) {
  std::error_code ignored;
  if (!fs::is_directory(base, ignored))
    throw error("shader directory not found: " + base.string() +
                " (set --shader-dir or VPLKIT_SHADER_DIR to the vplkit shaders/ folder)");
  roots_.push_back(std::move(base));
}

void shader_library::add_root(const fs::path& folder) {
  std::error_code ignored;
  if (!fs::is_directory(folder, ignored)) throw error("shader folder not found: " + folder.string() + " is not a folder");
  for (const fs::path& root : roots_)
    if (fs::equivalent(root, folder, ignored)) return;
  roots_.insert(roots_.end() - 1, folder);
}

fs::path shader_library::locate(const std::string& relative_path) const {
  if (const std::optional<fs::path> found = find_in(roots_, relative_path)) return *found;
  std::string candidates;
  for (const fs::path& root : roots_) candidates += (candidates.empty() ? "" : ", ") + (root / relative_path).string();
  throw error("shader file not found: " + candidates + " (shader " + (roots_.size() == 1 ? "directory " : "folders ") +
              folder_list(roots_) + "; set --shader-dir or VPLKIT_SHADER_DIR for vplkit's own)");
}

expanded_source shader_library::expand_file(const std::string& relative_path, const shader_defines& defines) const {
  const fs::path path = locate(relative_path);
  return expander(roots_, defines).run(read_text_file(path, ""), relative_path, path);
}

expanded_source shader_library::expand_text(const std::string& text, const std::string& display_name,
                                            const shader_defines& defines) const {
  return expander(roots_, defines).run(text, display_name);
}

expanded_source shader_library::expand_path(const fs::path& path, const shader_defines& defines) const {
  return expander(roots_, defines).run(read_text_file(path, ""), path.string(), path);
}

namespace {

// Digits at the start of `text`, which then starts after them; nothing if there are none.
std::optional<std::string> take_digits(std::string_view& text) {
  std::size_t count = 0;
  while (count < text.size() && count < 9 && text[count] >= '0' && text[count] <= '9') ++count;
  if (count == 0) return std::nullopt;
  std::string digits(text.substr(0, count));
  text.remove_prefix(count);
  return digits;
}

bool take(std::string_view& text, std::string_view expected) {
  if (text.substr(0, expected.size()) != expected) return false;
  text.remove_prefix(expected.size());
  return true;
}

}  // namespace

namespace {

// Where a log line points: the source-string number the driver printed and its line.
using locate_fn = std::function<std::string(const std::string& source, const std::string& line)>;

// Rewrites each log line in a driver's format so that its "source, line" prefix reads as
// `locate` names it, keeping the rest of the driver's text; other lines are kept as they are.
std::string rewrite_log(const std::string& log, const locate_fn& locate) {
  // Mesa: "0:12(5): error: ...".
  const auto mesa = [&](std::string_view rest) -> std::optional<std::string> {
    const auto file = take_digits(rest);
    if (!file || !take(rest, ":")) return std::nullopt;
    const auto row = take_digits(rest);
    if (!row || !take(rest, "(")) return std::nullopt;
    const auto column = take_digits(rest);
    if (!column || !take(rest, ")")) return std::nullopt;
    return locate(*file, *row) + ":" + *column + std::string(rest);
  };
  // NVIDIA: "0(12) : error C0000: ...".
  const auto nvidia = [&](std::string_view rest) -> std::optional<std::string> {
    const auto file = take_digits(rest);
    if (!file || !take(rest, "(")) return std::nullopt;
    const auto row = take_digits(rest);
    if (!row || !take(rest, ")")) return std::nullopt;
    return locate(*file, *row) + std::string(rest);
  };
  // AMD: "ERROR: 0:12: ..." (or WARNING).
  const auto amd = [&](std::string_view rest) -> std::optional<std::string> {
    const std::string severity = take(rest, "ERROR: ") ? "ERROR" : take(rest, "WARNING: ") ? "WARNING" : "";
    if (severity.empty()) return std::nullopt;
    const auto file = take_digits(rest);
    if (!file || !take(rest, ":")) return std::nullopt;
    const auto row = take_digits(rest);
    if (!row || !take(rest, ":")) return std::nullopt;
    return locate(*file, *row) + ": " + severity + std::string(rest);
  };
  std::istringstream lines(log);
  std::ostringstream out;
  std::string line;
  while (std::getline(lines, line)) {
    if (auto mapped = mesa(line)) line = *mapped;
    else if (auto from_nvidia = nvidia(line)) line = *from_nvidia;
    else if (auto from_amd = amd(line)) line = *from_amd;
    if (!line.empty()) out << "  " << line << "\n";
  }
  return out.str();
}

std::string file_name(const std::vector<std::string>& file_names, const std::string& number) {
  const std::size_t index = std::stoul(number);
  return index < file_names.size() ? file_names[index] : "<source " + number + ">";
}

// A line's origin: the source-string number and the line within it.
struct line_origin {
  unsigned long source = 0;
  unsigned long line = 1;
};

// The origin of each line of `text` (index 0 is its first line), read from its #line directives
// as the GLSL preprocessor reads them: `#line L S` makes the next line line L of source S, and
// the first line is line 1 of source 0. Nothing when a #line is not plain numbers (a macro),
// which is not evaluated here.
std::optional<std::vector<line_origin>> origins_of(std::string_view text) {
  std::vector<line_origin> origins;
  line_origin next;
  for (std::size_t at = 0; at < text.size();) {
    const std::string_view line = next_line(text, at);
    origins.push_back(next);
    std::optional<std::string_view> rest = directive(line, "line");
    if (!rest) {
      ++next.line;
      continue;
    }
    std::string_view numbers = skip_blanks(*rest);
    const auto row = take_digits(numbers);
    if (!row) return std::nullopt;
    numbers = skip_blanks(numbers);
    const auto source = take_digits(numbers);
    numbers = skip_blanks(numbers);
    if (!numbers.empty() && numbers.substr(0, 2) != "//") return std::nullopt;
    next.line = std::stoul(*row);
    if (source) next.source = std::stoul(*source);
  }
  return origins;
}

}  // namespace

std::string map_log_to_files(const std::string& log, const std::vector<std::string>& file_names) {
  return rewrite_log(log, [&](const std::string& source, const std::string& line) { return file_name(file_names, source) + ":" + line; });
}

std::string compiled_text(const std::string& text) {
  if (!origins_of(text)) return text;
  std::string out;
  out.reserve(text.size());
  std::size_t number = 0;
  for (std::size_t at = 0; at < text.size();) {
    const std::size_t start = at;
    const std::string_view line = next_line(text, at);
    ++number;
    if (const std::optional<std::string_view> rest = directive(line, "line")) {
      // Keep the source number (__FILE__ stays the file's); the line becomes the next line's place.
      std::string_view numbers = skip_blanks(*rest);
      take_digits(numbers);
      numbers = skip_blanks(numbers);
      const auto source = take_digits(numbers);
      out += "#line " + std::to_string(number + 1) + (source ? " " + *source : std::string()) + "\n";
    } else {
      out += text.substr(start, at - start);
    }
  }
  return out;
}

std::string map_compile_log(const std::string& log, const expanded_source& source) {
  const std::optional<std::vector<line_origin>> origins = origins_of(source.text);
  if (!origins) return map_log_to_files(log, source.file_names);
  return rewrite_log(log, [&](const std::string& number, const std::string& line) {
    const std::size_t place = std::stoul(line);
    if (place == 0 || place > origins->size()) return file_name(source.file_names, number) + ":" + line;
    const line_origin& origin = (*origins)[place - 1];
    return file_name(source.file_names, std::to_string(origin.source)) + ":" + std::to_string(origin.line);
  });
}

program link_program(const std::string& program_name, const std::vector<stage_source>& stages,
                     const std::vector<std::string>& transform_feedback_varyings) {
  check_gl("before building program " + program_name);
  gl_program linked(glCreateProgram());
  std::vector<gl_shader> shaders;
  for (const stage_source& stage : stages) {
    gl_shader shader(glCreateShader(stage.stage == shader_stage::vertex     ? GL_VERTEX_SHADER
                                    : stage.stage == shader_stage::fragment ? GL_FRAGMENT_SHADER
                                                                            : GL_COMPUTE_SHADER));
    // The driver gets the text numbered by place, so the line it reports locates the file and
    // line even where it drops the source number (Mesa does for an undeclared name).
    const std::string numbered = compiled_text(stage.source.text);
    const char* text = numbered.c_str();
    glShaderSource(shader.get(), 1, &text, nullptr);
    glCompileShader(shader.get());
    GLint compiled = GL_FALSE;
    glGetShaderiv(shader.get(), GL_COMPILE_STATUS, &compiled);
    if (!compiled) {
      GLint length = 0;
      glGetShaderiv(shader.get(), GL_INFO_LOG_LENGTH, &length);
      std::string log(static_cast<std::size_t>(std::max(length, 1)), '\0');
      glGetShaderInfoLog(shader.get(), length, nullptr, log.data());
      log.resize(std::char_traits<char>::length(log.c_str()));
      // Compile failures are reported here; drop the driver's duplicate KHR_debug copy.
      discard_pending_gl_messages();
      throw error("GLSL compile error in " + std::string(stage_name(stage.stage)) + " shader " +
                  stage.source.file_names.front() + " (program " + program_name + "):\n" +
                  map_compile_log(log, stage.source));
    }
    glAttachShader(linked.get(), shader.get());
    shaders.push_back(std::move(shader));
  }
  if (!transform_feedback_varyings.empty()) {
    std::vector<const char*> names;
    for (const std::string& name : transform_feedback_varyings) names.push_back(name.c_str());
    glTransformFeedbackVaryings(linked.get(), static_cast<GLsizei>(names.size()), names.data(), GL_SEPARATE_ATTRIBS);
  }
  glLinkProgram(linked.get());
  linked_programs().fetch_add(1, std::memory_order_relaxed);
  GLint link_ok = GL_FALSE;
  glGetProgramiv(linked.get(), GL_LINK_STATUS, &link_ok);
  if (!link_ok) {
    GLint length = 0;
    glGetProgramiv(linked.get(), GL_INFO_LOG_LENGTH, &length);
    std::string log(static_cast<std::size_t>(std::max(length, 1)), '\0');
    glGetProgramInfoLog(linked.get(), length, nullptr, log.data());
    log.resize(std::char_traits<char>::length(log.c_str()));
    discard_pending_gl_messages();
    std::vector<std::string> all_files;
    for (const stage_source& stage : stages) all_files.push_back(stage.source.file_names.front());
    std::string files;
    for (const std::string& name : all_files) files += (files.empty() ? "" : ", ") + name;
    throw error("GLSL link error in program " + program_name + " (" + files + "):\n  " + log);
  }
  for (const gl_shader& shader : shaders) glDetachShader(linked.get(), shader.get());
  check_gl("building program " + program_name);
  uniform_declarations declarations;
  for (const stage_source& stage : stages) declarations.scan(stage.source.text);
  // Every uniform struct that twins a kernel settings struct has exactly the described fields.
  check_glsl_twins(declarations, program_name);
  return program(linked.release(), program_name, std::move(declarations));
}

program load_program(const shader_library& library, const std::string& vertex_file,
                     const std::string& fragment_file, const shader_defines& defines) {
  std::string name = vertex_file + " + " + fragment_file;
  for (const auto& [define, value] : defines) name += " " + define + "=" + value;
  return link_program(name, {{shader_stage::vertex, library.expand_file(vertex_file, defines)},
                             {shader_stage::fragment, library.expand_file(fragment_file, defines)}});
}

namespace {

void delete_block_buffers(std::vector<std::pair<unsigned, unsigned>>& buffers) {
  for (const auto& [binding, buffer] : buffers) glDeleteBuffers(1, &buffer);
  buffers.clear();
}

}  // namespace

program::~program() {
  if (name_ != 0) glDeleteProgram(name_);
  delete_block_buffers(block_buffers_);
}

program::program(program&& other) noexcept
    : name_(std::exchange(other.name_, 0u)), program_name_(std::move(other.program_name_)), declarations_(std::move(other.declarations_)),
      block_buffers_(std::exchange(other.block_buffers_, {})) {}

program& program::operator=(program&& other) noexcept {
  if (this != &other) {
    if (name_ != 0) glDeleteProgram(name_);
    delete_block_buffers(block_buffers_);
    name_ = std::exchange(other.name_, 0u);
    program_name_ = std::move(other.program_name_);
    declarations_ = std::move(other.declarations_);
    block_buffers_ = std::exchange(other.block_buffers_, {});
  }
  return *this;
}

// Binding points are the context's, not the program's: another program's blocks may have taken
// them since set_uniform_block, so every use binds this program's buffers again.
void program::use() const {
  glUseProgram(name_);
  for (const auto& [binding, buffer] : block_buffers_) glBindBufferBase(GL_UNIFORM_BUFFER, binding, buffer);
}

void program::set_uniform_block(const std::string& block, const void* bytes, std::size_t size) const {
  const GLuint index = glGetUniformBlockIndex(name_, block.c_str());
  if (index == GL_INVALID_INDEX) {
    if (declarations_.declares_block(block)) return;  // the variant does not read it
    throw error("program " + program_name_ + " declares no uniform block '" + block + "' (its blocks: " +
                (declarations_.block_names().empty() ? std::string("none") : declarations_.block_names()) + ")");
  }
  GLint needed = 0;
  glGetActiveUniformBlockiv(name_, index, GL_UNIFORM_BLOCK_DATA_SIZE, &needed);
  if (size < static_cast<std::size_t>(needed))
    throw error("program " + program_name_ + ": uniform block '" + block + "' holds " + std::to_string(needed) + " bytes, given " +
                std::to_string(size) + ": the shader would read past them");
  GLint bindings = 0;
  glGetIntegerv(GL_MAX_UNIFORM_BUFFER_BINDINGS, &bindings);
  if (index >= static_cast<GLuint>(bindings))
    throw error("program " + program_name_ + ": uniform block '" + block + "' has index " + std::to_string(index) + ", beyond the " +
                std::to_string(bindings) + " binding points (GL_MAX_UNIFORM_BUFFER_BINDINGS)");
  glUniformBlockBinding(name_, index, index);
  GLuint buffer = 0;
  for (const auto& [binding, owned] : block_buffers_)
    if (binding == index) buffer = owned;
  if (buffer == 0) {
    glGenBuffers(1, &buffer);
    block_buffers_.emplace_back(index, buffer);
  }
  glBindBuffer(GL_UNIFORM_BUFFER, buffer);
  glBufferData(GL_UNIFORM_BUFFER, static_cast<GLsizeiptr>(size), bytes, GL_DYNAMIC_DRAW);
  glBindBuffer(GL_UNIFORM_BUFFER, 0);
  use();
}

// GL 3.3 has no glProgramUniform (that is 4.1), so a setter binds the program first.
GLint program::location(const std::string& uniform) const {
  const GLint found = glGetUniformLocation(name_, uniform.c_str());
  if (found < 0 && !declarations_.declares(uniform))
    throw error("program " + program_name_ + " declares no uniform '" + uniform + "' (its uniforms: " + declarations_.names() + ")");
  return found;
}

void program::set(const std::string& uniform, int value) const { use(); glUniform1i(location(uniform), value); }
void program::set(const std::string& uniform, unsigned value) const { use(); glUniform1ui(location(uniform), value); }
void program::set(const std::string& uniform, float value) const { use(); glUniform1f(location(uniform), value); }
void program::set(const std::string& uniform, const glm::vec2& value) const { use(); glUniform2fv(location(uniform), 1, glm::value_ptr(value)); }
void program::set(const std::string& uniform, const glm::vec3& value) const { use(); glUniform3fv(location(uniform), 1, glm::value_ptr(value)); }
void program::set(const std::string& uniform, const glm::vec4& value) const { use(); glUniform4fv(location(uniform), 1, glm::value_ptr(value)); }
void program::set(const std::string& uniform, const glm::ivec2& value) const { use(); glUniform2iv(location(uniform), 1, glm::value_ptr(value)); }
void program::set(const std::string& uniform, const glm::ivec3& value) const { use(); glUniform3iv(location(uniform), 1, glm::value_ptr(value)); }
void program::set(const std::string& uniform, const glm::mat4& value) const { use(); glUniformMatrix4fv(location(uniform), 1, GL_FALSE, glm::value_ptr(value)); }

}  // namespace vplkit
