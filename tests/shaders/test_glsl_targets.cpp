// Every lib file (shaders/lib/*.glsl) compiles on every target an engine may embed it in: GLSL
// 3.30, 4.50 and 4.60 core, GLSL ES 3.00 (WebGL2) and Vulkan GLSL 4.50 compiled to SPIR-V that
// spirv-val accepts. Each file is included, with each define variant its row of the table in
// docs/glsl-twins.md lists, by a minimal fragment shader that calls every function the file
// defines from main() with values from a uniform block (Vulkan has no uniforms outside blocks),
// so that every function body is compiled and, for Vulkan, emitted and validated. The functions
// the file declares and leaves to the including shader (rsm_fetch, ...) are defined by the
// minimal shader the same way.
//
// The per-file defines come from the docs table, the one table users read: every macro a lib
// file tests in #if/#ifdef/#ifndef (its include guard aside) must be in its row, and every
// function it leaves to the including shader must be named in the row's "including shader
// defines" cell. Every function a lib file defines has a C++ function of the same name in the
// header the file is the twin of (its first line names it), or a comment above it that says what
// its C++ twin is. The measured matrix (file x target) is printed, written to glsl-targets.md in
// the working folder, and must equal the one in docs/glsl-twins.md.
//
// glslang (glslangValidator, Debian glslang-tools) and spirv-val (spirv-tools) are found by
// CMake; scripts/setup.sh installs both. The GL and ES shaders of every variant compile in one
// glslang run and the preprocessing in another; Vulkan takes one run per variant (a SPIR-V module
// has one fragment entry point), spread over the cores: glslang's start-up (its built-in symbol
// tables) is most of the cost.
#include <doctest/doctest.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include "frontend/core/files.hpp"
#include <vplkit/gl/program.hpp>
#include "tests/gl_test_helpers.hpp"

namespace fs = std::filesystem;
using namespace vplkit;

namespace {

struct glsl_target {
  const char* name;
  const char* header;  // the including shader's first lines
  bool vulkan;
};

const std::vector<glsl_target>& targets() {
  static const std::vector<glsl_target> all = {
      {"GLSL 3.30 core", "#version 330 core\n", false},
      {"GLSL 4.50 core", "#version 450 core\n", false},
      {"GLSL 4.60 core", "#version 460 core\n", false},
      // ES has no default float precision in fragment shaders; highp for both, as WebGL2 engines do.
      {"GLSL ES 3.00", "#version 300 es\nprecision highp float;\nprecision highp int;\n", false},
      {"Vulkan GLSL 4.50 (SPIR-V)", "#version 450\n", true},
  };
  return all;
}

// One define of a lib file as its docs row states it: `NAME` (values...) or `NAME` (optional: ...).
struct define_row {
  std::string name;
  bool optional = false;
  std::vector<std::string> values;  // empty: a flag, defined or not
};

struct lib_row {
  std::string file;             // "lib/rsm_gather.glsl"
  std::vector<define_row> defines;
  std::string includer_cell;    // the "including shader defines" cell
};

std::string trim(const std::string& text) {
  const std::size_t first = text.find_first_not_of(" \t");
  if (first == std::string::npos) return "";
  return text.substr(first, text.find_last_not_of(" \t") - first + 1);
}

std::vector<std::string> split(const std::string& text, char separator) {
  std::vector<std::string> parts;
  std::string part;
  std::istringstream in(text);
  while (std::getline(in, part, separator)) parts.push_back(part);
  return parts;
}

// The defines cell: each `VPLKIT_...` name followed by a parenthesised description. A description
// that starts with "optional" makes the define optional; the values are the integers that begin
// the description's comma-separated items before the first ';' ("0 radial, 1 disk" -> 0, 1).
std::vector<define_row> parse_defines(const std::string& cell, const std::string& file) {
  std::vector<define_row> defines;
  std::size_t at = 0;
  while ((at = cell.find("`VPLKIT_", at)) != std::string::npos) {
    const std::size_t end = cell.find('`', at + 1);
    REQUIRE_MESSAGE(end != std::string::npos, "docs/glsl-twins.md, row " << file << ": an unclosed ` in the defines cell");
    define_row define;
    define.name = cell.substr(at + 1, end - at - 1);
    std::size_t open = end + 1;
    while (open < cell.size() && cell[open] == ' ') ++open;
    REQUIRE_MESSAGE((open < cell.size() && cell[open] == '('), "docs/glsl-twins.md, row " << file << ": " << define.name
                                                                  << " needs its values in parentheses after it");
    int depth = 0;
    std::size_t close = open;
    for (; close < cell.size(); ++close) {
      if (cell[close] == '(') ++depth;
      if (cell[close] == ')' && --depth == 0) break;
    }
    std::string description = cell.substr(open + 1, close - open - 1);
    if (description.rfind("optional", 0) == 0) {
      define.optional = true;
      const std::size_t colon = description.find(':');
      description = colon == std::string::npos ? "" : description.substr(colon + 1);
    }
    description = description.substr(0, description.find(';'));
    for (const std::string& item : split(description, ',')) {
      const std::string word = trim(item);
      std::size_t digits = 0;
      while (digits < word.size() && std::isdigit(static_cast<unsigned char>(word[digits]))) ++digits;
      if (digits > 0 && (digits == word.size() || word[digits] == ' ')) define.values.push_back(word.substr(0, digits));
    }
    REQUIRE_MESSAGE((define.optional || !define.values.empty()),
                    "docs/glsl-twins.md, row " << file << ": the required " << define.name << " lists no values");
    defines.push_back(define);
    at = close;
  }
  return defines;
}

using vplkit::testing::source_dir;

// The rows of docs/glsl-twins.md's lib-file table, by file.
std::map<std::string, lib_row> docs_rows() {
  std::map<std::string, lib_row> rows;
  std::ifstream in(source_dir() / "docs" / "glsl-twins.md");
  REQUIRE(in);
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind("| `lib/", 0) != 0) continue;
    const std::vector<std::string> cells = split(line, '|');
    REQUIRE_MESSAGE(cells.size() >= 7, "docs/glsl-twins.md: a lib-file row with fewer than 6 cells: " << line);
    lib_row row;
    row.file = trim(cells[1]);
    row.file = row.file.substr(1, row.file.size() - 2);  // without the backticks
    row.defines = parse_defines(cells[3], row.file);
    row.includer_cell = cells[4];
    rows[row.file] = row;
  }
  return rows;
}

struct run_result {
  int status = 0;
  std::string output;  // standard output and error together
};

// Runs a tool with its output into `log`, without a shell (paths may hold any character) and
// without fork's copy of this process (posix_spawn).
run_result run_tool(const std::vector<std::string>& command, const fs::path& log) {
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 1, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_adddup2(&actions, 1, 2);
  std::vector<char*> argv;
  for (const std::string& word : command) argv.push_back(const_cast<char*>(word.c_str()));
  argv.push_back(nullptr);
  pid_t child = 0;
  const int spawned = posix_spawn(&child, argv[0], &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (spawned != 0) return {127, "could not run " + command.front() + ": " + std::strerror(spawned)};
  int status = 0;
  while (waitpid(child, &status, 0) < 0 && errno == EINTR) {
  }
  const int code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  return {code, read_file(log, std::uintmax_t{1} << 24, "tool output")};
}

// The macros a lib file tests in its conditional directives, its include guard (..._GLSL) aside.
std::set<std::string> tested_macros(const std::string& text) {
  std::set<std::string> names;
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line)) {
    const std::string directive = trim(line);
    if (directive.rfind("#if", 0) != 0 && directive.rfind("#elif", 0) != 0) continue;
    for (std::size_t at = directive.find("VPLKIT_"); at != std::string::npos; at = directive.find("VPLKIT_", at + 1)) {
      std::size_t end = at;
      while (end < directive.size() && (std::isalnum(static_cast<unsigned char>(directive[end])) || directive[end] == '_')) ++end;
      const std::string name = directive.substr(at, end - at);
      if (name.size() < 5 || name.compare(name.size() - 5, 5, "_GLSL") != 0) names.insert(name);
      at = end - 1;
    }
  }
  return names;
}

// A function of the preprocessed source: its return type, name, parameters, and whether it has a body.
struct parameter {
  std::string qualifier;  // "", "in", "out", "inout"
  std::string type;
  std::string array;      // "[4]" or ""
};
struct function {
  std::string return_type, name;
  std::vector<parameter> parameters;
  bool defined = false;
};

std::vector<std::string> tokens_of(const std::string& preprocessed) {
  std::vector<std::string> tokens;
  std::istringstream in(preprocessed);
  std::string line;
  while (std::getline(in, line)) {
    if (trim(line).rfind("#", 0) == 0) continue;  // #version, #line, #extension
    for (std::size_t i = 0; i < line.size();) {
      const unsigned char c = static_cast<unsigned char>(line[i]);
      if (std::isspace(c)) {
        ++i;
      } else if (std::isalnum(c) || c == '_' || c == '.') {
        std::size_t end = i;
        while (end < line.size() && (std::isalnum(static_cast<unsigned char>(line[end])) || line[end] == '_' || line[end] == '.')) ++end;
        tokens.push_back(line.substr(i, end - i));
        i = end;
      } else {
        tokens.push_back(std::string(1, line[i]));
        ++i;
      }
    }
  }
  return tokens;
}

bool is_identifier(const std::string& token) {
  return !token.empty() && (std::isalpha(static_cast<unsigned char>(token[0])) || token[0] == '_');
}

// Top-level `type name(parameters) {` or `;`: what glslang -E leaves of a lib file.
std::vector<function> functions_of(const std::string& preprocessed) {
  const std::vector<std::string> tokens = tokens_of(preprocessed);
  std::vector<function> functions;
  int depth = 0;
  std::size_t statement = 0;  // the first token of the current top-level statement
  for (std::size_t i = 0; i < tokens.size(); ++i) {
    const std::string& token = tokens[i];
    if (token == "{") ++depth;
    if (token == "}" && --depth == 0) statement = i + 1;
    if (depth == 0 && token == ";") statement = i + 1;
    if (depth != 0 || token != "(" || i != statement + 2 || !is_identifier(tokens[i - 1]) || !is_identifier(tokens[i - 2])) continue;
    function f;
    f.return_type = tokens[i - 2];
    f.name = tokens[i - 1];
    std::size_t close = i + 1;
    std::vector<std::string> words;
    auto flush = [&] {
      if (words.empty() || (words.size() == 1 && words[0] == "void")) return;
      parameter p;
      std::size_t w = 0;
      for (; w < words.size() && (words[w] == "in" || words[w] == "out" || words[w] == "inout" || words[w] == "const"); ++w)
        if (words[w] != "const") p.qualifier = words[w];
      REQUIRE_MESSAGE(w + 2 <= words.size(), "cannot read a parameter of " << f.name);
      p.type = words[w];
      for (std::size_t k = w + 2; k < words.size(); ++k) p.array += words[k];
      f.parameters.push_back(p);
      words.clear();
    };
    for (; close < tokens.size() && tokens[close] != ")"; ++close) {
      if (tokens[close] == ",") flush();
      else words.push_back(tokens[close]);
    }
    flush();
    REQUIRE(close + 1 < tokens.size());
    f.defined = tokens[close + 1] == "{";
    functions.push_back(f);
    i = close;
    if (!f.defined) statement = close + 2;
  }
  return functions;
}

// The minimal including shader: the defines, the include, a uniform block with one member per
// value the calls need, the functions the file leaves to its includer, and main() calling every
// function the file defines.
std::string including_shader(const glsl_target& on, const std::string& file, const std::vector<std::pair<std::string, std::string>>& defines,
                             const std::vector<function>& functions) {
  std::string text = on.header;
  for (const auto& [name, value] : defines) text += "#define " + name + " " + value + "\n";
  text += "#include \"" + file + "\"\n";
  std::string members, fetchers, calls;
  int member = 0;
  auto add_member = [&](const std::string& type, const std::string& array) {
    const std::string name = "vplkit_a" + std::to_string(member++);
    members += "  " + type + " " + name + array + ";\n";
    return "vplkit_in." + name;
  };
  std::set<std::string> defined;
  for (const function& f : functions)
    if (f.defined) defined.insert(f.name);
  std::set<std::string> fetched;
  for (const function& f : functions) {
    if (f.defined || defined.count(f.name) || !fetched.insert(f.name).second) continue;
    fetchers += f.return_type + " " + f.name + "(";
    for (std::size_t k = 0; k < f.parameters.size(); ++k)
      fetchers += (k ? ", " : "") + f.parameters[k].qualifier + (f.parameters[k].qualifier.empty() ? "" : " ") + f.parameters[k].type + " p" +
                  std::to_string(k) + f.parameters[k].array;
    fetchers += ") { ";
    for (std::size_t k = 0; k < f.parameters.size(); ++k)
      if (f.parameters[k].qualifier == "out" || f.parameters[k].qualifier == "inout")
        fetchers += "p" + std::to_string(k) + " = " + add_member(f.parameters[k].type, f.parameters[k].array) + "; ";
    if (f.return_type != "void") fetchers += "return " + add_member(f.return_type, "") + "; ";
    fetchers += "}\n";
  }
  int local = 0;
  for (const function& f : functions) {
    if (!f.defined) continue;
    std::string arguments;
    for (const parameter& p : f.parameters) {
      std::string argument;
      if (p.qualifier == "out" || p.qualifier == "inout") {
        argument = "vplkit_t" + std::to_string(local++);
        calls += "  " + p.type + " " + argument + p.array + (p.qualifier == "inout" ? " = " + add_member(p.type, p.array) : "") + ";\n";
      } else {
        argument = add_member(p.type, p.array);
      }
      arguments += (arguments.empty() ? "" : ", ") + argument;
    }
    calls += "  " + f.name + "(" + arguments + ");\n";
  }
  if (member > 0)
    text += std::string(on.vulkan ? "layout(std140, set = 0, binding = 0)" : "layout(std140)") + " uniform vplkit_inputs {\n" + members +
            "} vplkit_in;\n";
  text += fetchers;
  text += "void main() {\n" + calls + "}\n";
  return text;
}

// "ok", or the first error line, for the docs table (no '|', no scratch paths).
std::string first_error(const std::string& log) {
  for (const std::string& line : split(log, '\n'))
    if (line.find("ERROR") != std::string::npos || line.find("error") != std::string::npos) {
      std::string shown = trim(line);
      std::replace(shown.begin(), shown.end(), '|', '/');
      return shown;
    }
  return trim(log.substr(0, log.find('\n')));
}

using vplkit::testing::scratch_folder;


// The C++ header a lib file is the twin of: its first line names it ("GLSL twin of
// include/vplkit/irradiance.hpp: ...").
std::string twin_header_of(const std::string& text) {
  const std::string first = text.substr(0, text.find('\n'));
  const std::size_t at = first.find("include/vplkit/");
  if (at == std::string::npos) return "";
  std::size_t end = at + 15;
  while (end < first.size() && (std::isalnum(static_cast<unsigned char>(first[end])) || first[end] == '_' || first[end] == '.')) ++end;
  return first.substr(at, end - at);
}

// Whether `name` is defined at the top of `text` ("type name(" starting a line, this project's
// style) with "C++ twin is" in the comment right above it: a GLSL function whose C++ twin has
// another form (a lambda), which the comment names.
bool names_its_cpp_twin(const std::string& text, const std::string& name) {
  std::vector<std::string> lines = split(text, '\n');
  for (std::size_t i = 0; i < lines.size(); ++i) {
    const std::size_t at = lines[i].find(" " + name + "(");
    if (at == std::string::npos || lines[i].empty() || !std::isalpha(static_cast<unsigned char>(lines[i][0])) ||
        lines[i].find(' ') != at)
      continue;
    for (std::size_t k = i; k > 0 && trim(lines[k - 1]).rfind("//", 0) == 0; --k)
      if (lines[k - 1].find("C++ twin is") != std::string::npos) return true;
  }
  return false;
}

using define_list = std::vector<std::pair<std::string, std::string>>;

// One lib file with one set of defines, and what became of it.
struct define_variant {
  std::string file;
  define_list defines;
  std::string shown;                     // " NAME=VALUE ..."
  std::vector<function> functions;
  std::vector<expanded_source> sources;  // per target
  std::vector<fs::path> paths;           // per target
  std::vector<std::string> errors;       // per target, "" when it compiled
};

// The variants of a file: every required define at its first value, no optional one; then each
// define at each other value it takes (a flag: defined as 1), one at a time.
std::vector<define_list> variants_of(const lib_row& row) {
  define_list base;
  for (const define_row& define : row.defines)
    if (!define.optional) base.push_back({define.name, define.values.front()});
  std::vector<define_list> variants = {base};
  for (const define_row& define : row.defines) {
    std::vector<std::string> others = define.values;
    if (!define.optional) others.erase(others.begin());
    if (define.optional && others.empty()) others = {"1"};
    for (const std::string& value : others) {
      define_list changed = base;
      changed.erase(std::remove_if(changed.begin(), changed.end(), [&](const auto& d) { return d.first == define.name; }), changed.end());
      changed.push_back({define.name, value});
      variants.push_back(changed);
    }
  }
  return variants;
}

// glslang's output for several files, by file: each file's messages follow a line with its path.
std::map<std::string, std::string> logs_by_file(const std::string& output, const std::set<std::string>& paths) {
  std::map<std::string, std::string> logs;
  std::string current;
  for (const std::string& line : split(output, '\n')) {
    if (paths.count(line)) current = line;
    else if (!current.empty()) logs[current] += line + "\n";
  }
  return logs;
}

}  // namespace

TEST_CASE("every lib file compiles for GLSL 3.30, 4.50 and 4.60 core, GLSL ES 3.00 and Vulkan SPIR-V, with every define its docs row lists") {
  const std::string glslang = VPLKIT_GLSLANG_VALIDATOR, spirv_val = VPLKIT_SPIRV_VAL;
  REQUIRE_MESSAGE(!glslang.empty(), "glslangValidator was not found when CMake ran: install glslang-tools (scripts/setup.sh does) and reconfigure");
  REQUIRE_MESSAGE(!spirv_val.empty(), "spirv-val was not found when CMake ran: install spirv-tools (scripts/setup.sh does) and reconfigure");
  const fs::path shaders = source_dir() / "shaders";
  const shader_library library(shaders);
  const std::map<std::string, lib_row> rows = docs_rows();
  const scratch_folder scratch("glsl-targets");

  std::vector<std::string> files;
  for (const fs::directory_entry& entry : fs::directory_iterator(shaders / "lib"))
    if (entry.path().extension() == ".glsl") files.push_back("lib/" + entry.path().filename().string());
  std::sort(files.begin(), files.end());
  REQUIRE(files.size() >= 18u);
  for (const auto& listed_row : rows)
    CHECK_MESSAGE(std::count(files.begin(), files.end(), listed_row.first) == 1,
                  "docs/glsl-twins.md has a row for " << listed_row.first << ", which shaders/lib lacks");

  // The variants, each preprocessed alone (the file, its defines, an empty main) to find the
  // functions it defines and the ones it leaves to the includer; all in one glslang run.
  std::vector<define_variant> variants;
  std::vector<std::string> preprocess = {glslang, "-E"};
  std::vector<expanded_source> alone;
  for (const std::string& file : files) {
    CAPTURE(file);
    const auto found = rows.find(file);
    REQUIRE_MESSAGE(found != rows.end(), "docs/glsl-twins.md's lib-file table has no row for " << file);
    const lib_row& row = found->second;
    std::set<std::string> listed;
    for (const define_row& define : row.defines) listed.insert(define.name);
    for (const std::string& macro : tested_macros(read_file(shaders / file, std::uintmax_t{1} << 20, "shader file")))
      CHECK_MESSAGE(listed.count(macro) == 1, file << " tests " << macro << ", which its row in docs/glsl-twins.md does not list");
    for (const define_list& defines : variants_of(row)) {
      define_variant v;
      v.file = file;
      v.defines = defines;
      for (const auto& [name, value] : defines) v.shown += " " + name + "=" + value;
      alone.push_back(library.expand_text(including_shader(targets().front(), file, defines, {}), "main.frag"));
      const fs::path path = scratch.path / ("alone" + std::to_string(variants.size()) + ".frag");
      std::ofstream(path) << alone.back().text;
      preprocess.push_back(path.string());
      variants.push_back(v);
    }
  }
  const run_result preprocessed = run_tool(preprocess, scratch.path / "alone.log");
  std::vector<std::string> texts;
  if (preprocessed.status == 0) {
    for (const std::string& line : split(preprocessed.output, '\n')) {
      if (line.rfind("#version", 0) == 0) texts.emplace_back();
      if (!texts.empty()) texts.back() += line + "\n";
    }
    REQUIRE(texts.size() == variants.size());
  } else {  // one variant or more stopped (an #error): run each alone to say which
    for (std::size_t k = 0; k < variants.size(); ++k) {
      const run_result one = run_tool({glslang, "-E", preprocess[k + 2]}, scratch.path / "alone.log");
      texts.push_back(one.status == 0 ? one.output : "");
      if (one.status != 0) {
        variants[k].errors.assign(targets().size(), first_error(map_log_to_files(one.output, alone[k].file_names)));
        FAIL_CHECK(variants[k].file << variants[k].shown << ": glslang's preprocessor: " << map_log_to_files(one.output, alone[k].file_names));
      }
    }
  }

  // Every variant's including shader for every target; the GL and ES ones compiled in one run.
  std::vector<std::string> compile_gl = {glslang};
  std::set<std::string> gl_paths;
  std::map<std::string, int> paired;  // "lib file: function" paired with its C++ twin
  for (std::size_t k = 0; k < variants.size(); ++k) {
    define_variant& v = variants[k];
    if (!v.errors.empty()) continue;
    for (const function& f : functions_of(texts[k]))
      if (f.name != "main") v.functions.push_back(f);
    std::set<std::string> defined;
    for (const function& f : v.functions)
      if (f.defined) defined.insert(f.name);
    for (const function& f : v.functions)
      if (!f.defined && !defined.count(f.name))
        CHECK_MESSAGE(rows.at(v.file).includer_cell.find(f.name + "(") != std::string::npos,
                      v.file << v.shown << " leaves " << f.name << " to the including shader; its row in docs/glsl-twins.md does not say so");
    // The mirror rule by name: every function the file itself defines (not its includes') has a
    // C++ function of the same name in the header it is the twin of, or says in a comment what
    // its C++ twin is.
    const std::string own_text = read_file(shaders / v.file, std::uintmax_t{1} << 20, "shader file");
    const std::string header = twin_header_of(own_text);
    REQUIRE_MESSAGE(!header.empty(), v.file << ": its first line names no include/vplkit/ header it is the twin of");
    const std::string header_text = read_file(source_dir() / header, std::uintmax_t{1} << 20, "C++ header");
    for (const std::string& name : defined) {
      const std::string definition = " " + name + "(";
      bool own = false;
      for (const std::string& line : split(own_text, '\n'))
        own = own || (!line.empty() && std::isalpha(static_cast<unsigned char>(line[0])) && line.find(' ') == line.find(definition) &&
                      line.find(definition) != std::string::npos && trim(line).back() != ';');  // not a prototype
      if (!own || paired[v.file + ": " + name]++ > 0) continue;  // once per function, not per variant
      bool in_header = false;
      for (std::size_t at = header_text.find(name + "("); at != std::string::npos && !in_header; at = header_text.find(name + "(", at + 1))
        in_header = at == 0 || !(std::isalnum(static_cast<unsigned char>(header_text[at - 1])) || header_text[at - 1] == '_');
      CHECK_MESSAGE((in_header || names_its_cpp_twin(own_text, name)),
                    v.file << " defines " << name << ", which " << header << " does not (and no comment above it names its C++ twin)");
    }
    v.errors.assign(targets().size(), "");
    for (std::size_t t = 0; t < targets().size(); ++t) {
      v.sources.push_back(library.expand_text(including_shader(targets()[t], v.file, v.defines, v.functions), "main.frag"));
      v.paths.push_back(scratch.path / ("variant" + std::to_string(k) + "-target" + std::to_string(t) + ".frag"));
      std::ofstream(v.paths.back()) << v.sources.back().text;
      if (!targets()[t].vulkan) {
        compile_gl.push_back(v.paths.back().string());
        gl_paths.insert(v.paths.back().string());
      }
    }
  }
  const run_result gl = run_tool(compile_gl, scratch.path / "gl.log");
  const std::map<std::string, std::string> gl_logs = logs_by_file(gl.output, gl_paths);
  std::size_t compiled = gl_paths.size();
  for (define_variant& v : variants)
    for (std::size_t t = 0; t < v.paths.size(); ++t) {
      const auto log = gl_logs.find(v.paths[t].string());
      if (!targets()[t].vulkan && log != gl_logs.end() && log->second.find("ERROR") != std::string::npos)
        v.errors[t] = map_log_to_files(log->second, v.sources[t].file_names);
    }
  CHECK_MESSAGE((gl.status == 0) == std::all_of(variants.begin(), variants.end(), [](const define_variant& v) {
                  return std::all_of(v.errors.begin(), v.errors.end(), [](const std::string& e) { return e.empty(); });
                }),
                "glslang's exit status and its messages disagree:\n" << gl.output);

  // Vulkan: one glslang -V (a SPIR-V module has one entry point per stage) and one spirv-val per
  // variant, on as many threads as there are cores.
  const std::size_t vulkan = static_cast<std::size_t>(std::find_if(targets().begin(), targets().end(), [](const glsl_target& t) { return t.vulkan; }) -
                                                      targets().begin());
  const unsigned workers = std::max(1u, std::min(4u, std::thread::hardware_concurrency()));
  std::vector<std::thread> threads;
  for (unsigned w = 0; w < workers; ++w)
    threads.emplace_back([&, w] {
      for (std::size_t k = w; k < variants.size(); k += workers) {
        define_variant& v = variants[k];
        if (v.paths.empty()) continue;
        const fs::path spirv = scratch.path / ("variant" + std::to_string(k) + ".spv");
        const fs::path log = scratch.path / ("variant" + std::to_string(k) + ".log");
        run_result result = run_tool({glslang, "-V", "--target-env", "vulkan1.0", "-o", spirv.string(), v.paths[vulkan].string()}, log);
        if (result.status == 0) result = run_tool({spirv_val, "--target-env", "vulkan1.0", spirv.string()}, log);
        if (result.status != 0) v.errors[vulkan] = map_log_to_files(result.output, v.sources[vulkan].file_names);
      }
    });
  for (std::thread& thread : threads) thread.join();
  for (const define_variant& v : variants) compiled += v.paths.empty() ? 0 : 1;

  // matrix[file][target]: "ok", or the first error of the first variant that failed there.
  std::map<std::string, std::vector<std::string>> matrix;
  std::map<std::string, std::size_t> variant_counts;
  for (const define_variant& v : variants) {
    std::vector<std::string>& cells = matrix[v.file];
    if (cells.empty()) cells.assign(targets().size(), "ok");
    ++variant_counts[v.file];
    for (std::size_t t = 0; t < targets().size(); ++t) {
      if (v.errors[t].empty()) continue;
      if (cells[t] == "ok") cells[t] = first_error(v.errors[t]) + (v.shown.empty() ? "" : " (" + trim(v.shown) + ")");
      FAIL_CHECK(v.file << v.shown << " on " << targets()[t].name << ":\n" << v.errors[t] << "\nthe including shader:\n" << (v.sources.empty() ? "" : v.sources[t].text));
    }
  }

  // The matrix as docs/glsl-twins.md shows it.
  std::string table = "| lib file | variants |";
  for (const glsl_target& on : targets()) table += std::string(" ") + on.name + " |";
  table += "\n|---|---|";
  for (std::size_t t = 0; t < targets().size(); ++t) table += "---|";
  table += "\n";
  for (const auto& [file, cells] : matrix) {
    table += "| `" + file + "` | " + std::to_string(variant_counts[file]) + " |";
    for (const std::string& cell : cells) table += " " + cell + " |";
    table += "\n";
  }
  // Every function definition in a lib file's text ("type name(" starting a line, not a
  // prototype) was seen by the parse of some variant, so main() called it on every target: a
  // function the parse missed would have escaped both the pairing and the compilation.
  for (const std::string& file : files)
    for (const std::string& line : split(read_file(shaders / file, std::uintmax_t{1} << 20, "shader file"), '\n')) {
      const std::size_t space = line.find(' '), open = line.find('(');
      if (line.empty() || !std::isalpha(static_cast<unsigned char>(line[0])) || space == std::string::npos || open == std::string::npos ||
          open < space || trim(line).back() == ';' || line.rfind("struct", 0) == 0)
        continue;
      const std::string name = line.substr(space + 1, open - space - 1);
      if (is_identifier(name) && name.find(' ') == std::string::npos)
        CHECK_MESSAGE(paired.count(file + ": " + name) == 1, file << " defines " << name << ", which no variant's main() called");
    }
  std::cout << paired.size() << " GLSL functions paired with their C++ twins by name\n";
  std::cout << "compiled " << compiled << " shaders (" << variants.size() << " variants of " << files.size()
            << " lib files); the matrix (file x target):\n" << table;
  std::ofstream("glsl-targets.md") << table;

  const std::string docs = read_file(source_dir() / "docs" / "glsl-twins.md", std::uintmax_t{1} << 20, "docs/glsl-twins.md");
  const std::string begin = "<!-- glsl-targets: the test writes this table -->\n", end = "<!-- glsl-targets: end -->";
  const std::size_t from = docs.find(begin), to = docs.find(end);
  REQUIRE_MESSAGE((from != std::string::npos && to != std::string::npos && from < to),
                  "docs/glsl-twins.md has no matrix between '" << trim(begin) << "' and '" << end << "'");
  CHECK_MESSAGE(docs.substr(from + begin.size(), to - from - begin.size()) == table,
                "docs/glsl-twins.md's target matrix is not the one measured; the measured one is in "
                    << fs::absolute("glsl-targets.md").string() << " (copy it between the markers)");
}
