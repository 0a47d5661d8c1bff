// vplkit shader expand: a GLSL file with every `#include "..."` expanded into one self-contained
// source, for one's own pipelines that use vplkit's GLSL twins. Includes are looked up in the
// --root folders in the order given, then in vplkit's shaders (--shader-dir), with the expander
// the frontend and vplkit::parity use (vplkit/gl/program.hpp): each file once, `#line` directives
// back to every file, --define lines right after #version. The CMake function vplkit_expand_glsl
// (cmake/vplkitExpandGlsl.cmake) runs it at build time, with --depfile.
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include <vplkit/gl/program.hpp>

#include "frontend/cli/commands.hpp"
#include "frontend/core/error.hpp"
#include "frontend/core/files.hpp"

namespace vplkit::cli {

namespace {

namespace fs = std::filesystem;

struct expand_state {
  std::string file, out, depfile, shader_dir;
  std::vector<std::string> roots, defines;
};

bool is_identifier(const std::string& name) {
  if (name.empty() || (name[0] >= '0' && name[0] <= '9')) return false;
  for (char c : name)
    if (!((c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_')) return false;
  return true;
}

// "NAME=VALUE" or "NAME" (defined empty).
std::pair<std::string, std::string> parse_define(const std::string& text) {
  const std::size_t equals = text.find('=');
  const std::string name = text.substr(0, equals);
  const std::string value = equals == std::string::npos ? "" : text.substr(equals + 1);
  if (!is_identifier(name)) throw usage_error("--define " + shown(text) + ": expected NAME=VALUE with NAME a GLSL identifier");
  if (value.find_first_of("\r\n") != std::string::npos) throw usage_error("--define " + shown(text) + ": the value is one line");
  return {name, value};
}

// A path in a Makefile rule: spaces, '#' and '$' escaped.
std::string make_escaped(const fs::path& path) {
  std::string escaped;
  for (char c : fs::absolute(path).lexically_normal().string()) {
    if (c == ' ' || c == '#') escaped += '\\';
    if (c == '$') escaped += '$';
    escaped += c;
  }
  return escaped;
}

std::vector<std::uint8_t> bytes_of(const std::string& text) { return {text.begin(), text.end()}; }

// -o - and -o /dev/stdout: the command's own standard output, the stream whose writes main()
// checks, rather than a path opened again (which, when standard output is a regular file, would
// replace that file behind the shell's back).
bool is_standard_output(const std::string& out) { return out == "-" || out == "/dev/stdout"; }

int run_expand(const session& io, const expand_state& s) {
  shader_defines defines;
  for (const std::string& define : s.defines) defines.push_back(parse_define(define));
  const bool to_standard_output = s.out.empty() || is_standard_output(s.out);
  if (!to_standard_output && same_file(s.out, s.file)) throw usage_error("-o " + s.out + " is the input " + s.file + "; name a new file");
  if (!s.depfile.empty() && to_standard_output) throw usage_error("--depfile names the dependencies of -o OUT; give -o with a file");
  if (io.dry_run) return 0;
  shader_library library(s.shader_dir.empty() ? default_shader_dir() : fs::path(s.shader_dir));
  for (const std::string& root : s.roots) library.add_root(root);
  const expanded_source source = library.expand_path(s.file, defines);
  if (!defines.empty() && source.text.rfind("#version", 0) != 0)
    throw error(s.file + " has no #version line first: --define puts its lines right after it");
  std::string text = source.text;
  text += "// vplkit shader expand: the source-string numbers of the #line directives:";
  for (std::size_t i = 0; i < source.file_names.size(); ++i) text += (i ? ", " : " ") + std::to_string(i) + " " + source.file_names[i];
  text += "\n";
  if (to_standard_output) {
    io.out << text;
    return 0;
  }
  std::vector<output_file> files = {{s.out, [&text] { return bytes_of(text); }}};
  std::string rule = make_escaped(s.out) + ":";
  for (const fs::path& read : source.files_read) rule += " " + make_escaped(read);
  rule += "\n";
  if (!s.depfile.empty()) files.push_back({s.depfile, [&rule] { return bytes_of(rule); }});
  write_all_or_nothing(files);
  for (const output_file& file : files) io.out << "wrote " << fs::absolute(file.path).lexically_normal().string() << "\n";
  return 0;
}

}  // namespace

command add_shader_command(CLI::App& app) {
  auto state = std::make_shared<expand_state>();
  CLI::App* shader = app.add_subcommand("shader", "tools for one's own GLSL that uses vplkit's GLSL twins");
  shader->require_subcommand(1);
  CLI::App* expand = shader->add_subcommand(
      "expand", "write FILE with every #include \"...\" expanded (the --root folders in order, then vplkit's shaders): one self-contained source");
  expand->add_option("file", state->file, "the GLSL file")->required();
  expand->add_option("--root", state->roots, "a folder searched for included files, before vplkit's shaders (repeat: searched in order)")
      ->check(CLI::ExistingDirectory);
  expand->add_option("-o,--out", state->out, "output file (default, or - or /dev/stdout: standard output)");
  expand->add_option("-D,--define", state->defines, "NAME=VALUE: a #define line right after #version (repeat for several)");
  expand->add_option("--depfile", state->depfile, "also write a Makefile rule: OUT depends on FILE and every file it included");
  expand->add_option("--shader-dir", state->shader_dir, "folder with the vplkit shaders (default: $VPLKIT_SHADER_DIR, else the source tree's for a build tree's vplkit, else the installed ones beside it)");
  const command block = add_shader_block_command(*shader);
  return {shader, [state, block](const session& io) { return block.app->parsed() ? block.run(io) : run_expand(io, *state); },
          [reset = restorer(state), block] {
            reset();
            block.reset();
          }};
}

}  // namespace vplkit::cli
