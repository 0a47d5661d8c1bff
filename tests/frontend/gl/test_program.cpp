// The program loader: #include expansion, file:line in errors, and the failure messages for
// missing files and bad GLSL (include/vplkit/gl/program.hpp): several folders searched in order too.
#include <doctest/doctest.h>

#include <array>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>

#include <vplkit/gl/program.hpp>
#include <vplkit/parity/parity.hpp>

#include "frontend/gl/debug_output.hpp"
#include "frontend/gl/gl.hpp"
#include "frontend/core/error.hpp"
#include "tests/gl_test_helpers.hpp"

namespace fs = std::filesystem;
using namespace vplkit;

namespace {

// A temporary shader folder with the given files, removed at the end of the test.
struct scratch_shaders {
  fs::path root;
  using file_list = std::vector<std::pair<std::string, std::string>>;
  explicit scratch_shaders(const file_list& files) {
    root = fs::temp_directory_path() / ("vplkit-shaders-" + std::to_string(std::random_device{}()));
    for (const auto& [name, text] : files) {
      fs::create_directories((root / name).parent_path());
      std::ofstream(root / name) << text;
    }
  }
  ~scratch_shaders() { fs::remove_all(root); }
};

using vplkit::testing::message_of;

}  // namespace

TEST_CASE("#include is expanded once per file, with #line directives back to each file") {
  scratch_shaders files({{"main.frag", "#version 330 core\n#include \"lib/a.glsl\"\n#include \"lib/b.glsl\"\nvoid main() {}\n"},
                         {"lib/a.glsl", "#include \"lib/b.glsl\"\nfloat a() { return b(); }\n"},
                         {"lib/b.glsl", "float b() { return 1.0; }\n"}});
  const shader_library library(files.root);
  const expanded_source source = library.expand_file("main.frag");
  CHECK(source.file_names == std::vector<std::string>{"main.frag", "lib/a.glsl", "lib/b.glsl"});
  CHECK(source.text.find("#version 330 core\n") == 0);
  // The top-level file counts as included: a file that includes it does not expand it again
  // (the include fuzzer found main.frag named twice).
  scratch_shaders cycle({{"main.frag", "#include \"lib/a.glsl\"\nfloat m() { return 1.0; }\n"}, {"lib/a.glsl", "#include \"main.frag\"\nfloat a();\n"}});
  const expanded_source once = shader_library(cycle.root).expand_file("main.frag");
  CHECK(once.file_names == std::vector<std::string>{"main.frag", "lib/a.glsl"});
  // b is defined once, although it is included twice.
  const auto first = source.text.find("float b()");
  CHECK(first != std::string::npos);
  CHECK(source.text.find("float b()", first + 1) == std::string::npos);
  // After the includes, main.frag's own lines resume with their original numbers.
  CHECK(source.text.find("#line 4 0\nvoid main()") != std::string::npos);
}

TEST_CASE("a missing shader file, folder or include is named in the error") {
  scratch_shaders files(scratch_shaders::file_list{{"main.frag", "#version 330 core\n\n#include \"lib/missing.glsl\"\nvoid main() {}\n"}});
  const shader_library library(files.root);
  CHECK(message_of([&] { library.expand_file("nowhere.frag"); }).find("shader file not found: " + (files.root / "nowhere.frag").string()) == 0);
  const std::string include_error = message_of([&] { library.expand_file("main.frag"); });
  CHECK(include_error.find("main.frag:3: included file \"lib/missing.glsl\" not found") == 0);
  CHECK(message_of([&] { shader_library(files.root / "absent"); }).find("shader directory not found") == 0);
  scratch_shaders nested(scratch_shaders::file_list{{"main.frag", "#version 330 core\n#include \"lib/v.glsl\"\n"}, {"lib/v.glsl", "#version 330 core\n"}});
  CHECK(message_of([&] { shader_library(nested.root).expand_file("main.frag"); }).find("lib/v.glsl:1: #version must be") == 0);
}

TEST_CASE("an #include line that is not expanded is refused with its file and line; CR, LF and CRLF lines all expand") {
  // Each spelling GLSL would otherwise meet as an unknown directive, far from its cause, in a
  // "self-contained" expansion.
  const std::vector<std::pair<std::string, std::string>> refused = {
      {"#include <lib/b.glsl>", "main.frag:3: #include <...> is not expanded"},
      {"#include \"lib/b.glsl\" junk", "main.frag:3: text after the file name: 'junk' (only a // comment may follow)"},
      {"#include \"lib/b.glsl", "main.frag:3: the file name has no closing quote"},
      {"#include \"\"", "main.frag:3: the file name is empty"},
      {"  #  include", "main.frag:3: no file name after #include"},
      {"#include lib/b.glsl", "main.frag:3: expected #include \"path\", not 'lib/b.glsl'"},
  };
  for (const auto& refusal : refused) {
    // Named copies: clang 14 cannot capture structured bindings in CAPTURE's lambda.
    const std::string& line = refusal.first;
    const std::string& message = refusal.second;
    CAPTURE(line);
    scratch_shaders files({{"main.frag", "#version 330 core\n// a comment\n" + line + "\nvoid main() {}\n"}, {"lib/b.glsl", "float b() { return 1.0; }\n"}});
    CHECK(message_of([&] { shader_library(files.root).expand_file("main.frag"); }).find(message) == 0);
  }
  // In an included file, the message names that file and its line.
  scratch_shaders nested({{"main.frag", "#version 330 core\n#include \"lib/a.glsl\"\n"}, {"lib/a.glsl", "float a();\n#include <x.glsl>\n"}});
  CHECK(message_of([&] { shader_library(nested.root).expand_file("main.frag"); }).find("lib/a.glsl:2: #include <...> is not expanded") == 0);
  // A // comment after the name, and a directive that only starts like include, stay allowed.
  scratch_shaders fine({{"main.frag", "#version 330 core\n#include \"lib/b.glsl\" // why\n#includes_not\nvoid main() {}\n"},
                        {"lib/b.glsl", "float b() { return 1.0; }\n"}});
  CHECK(shader_library(fine.root).expand_file("main.frag").text.find("float b()") != std::string::npos);

  // The same file with LF, CRLF and lone-CR line ends expands to the same text: a CR-only file's
  // include was one long line before, never expanded.
  const auto with_ends = [](const std::string& end) {
    return "#version 330 core" + end + "#include \"lib/b.glsl\"" + end + "void main() {}" + end;
  };
  scratch_shaders lf({{"main.frag", with_ends("\n")}, {"lib/b.glsl", "float b() { return 1.0; }\n"}});
  scratch_shaders crlf({{"main.frag", with_ends("\r\n")}, {"lib/b.glsl", "float b() { return 1.0; }\r\n"}});
  scratch_shaders cr({{"main.frag", with_ends("\r")}, {"lib/b.glsl", "float b() { return 1.0; }\r"}});
  const std::string expected = shader_library(lf.root).expand_file("main.frag").text;
  CHECK(expected.find("float b()") != std::string::npos);
  CHECK(expected.find("#line 3 0\nvoid main() {}\n") != std::string::npos);
  CHECK(shader_library(crlf.root).expand_file("main.frag").text == expected);
  CHECK(shader_library(cr.root).expand_file("main.frag").text == expected);
  CHECK(expected.find('\r') == std::string::npos);
}

TEST_CASE("a NUL byte in a shader is refused with its file, line and byte offset") {
  // glShaderSource would read the text only up to it: the rest would vanish without a word.
  scratch_shaders files({{"main.frag", std::string("#version 330 core\nvoid main() {}\nfloat x") + std::string(1, '\0') + " = 1.0;\n"},
                         {"lib/a.glsl", std::string("float a()\r\r{") + std::string(1, '\0') + "}\n"},
                         {"top.frag", "#include \"lib/a.glsl\"\n"}});
  CHECK(message_of([&] { shader_library(files.root).expand_file("main.frag"); }) ==
        "main.frag:3: a NUL byte (byte offset 40 of the file); a shader is text");
  // Lone CRs count as line ends here too: the NUL is on line 3 of the included file.
  CHECK(message_of([&] { shader_library(files.root).expand_file("top.frag"); }) ==
        "lib/a.glsl:3: a NUL byte (byte offset 12 of the file); a shader is text");
}

TEST_CASE("include chains are bounded: 32 deep expands, 10,000 deep is refused at depth 33, the expanded text has a limit") {
  const auto chain = [](int length) {
    scratch_shaders::file_list files{{"main.frag", "#version 330 core\n#include \"lib/c0.glsl\"\nvoid main() {}\n"}};
    for (int i = 0; i < length; ++i)
      files.push_back({"lib/c" + std::to_string(i) + ".glsl",
                       i + 1 < length ? "#include \"lib/c" + std::to_string(i + 1) + ".glsl\"\n" : std::string("float deepest() { return 1.0; }\n")});
    return files;
  };
  const scratch_shaders fits(chain(max_include_depth));
  const expanded_source source = shader_library(fits.root).expand_file("main.frag");
  CHECK(source.file_names.size() == static_cast<std::size_t>(max_include_depth) + 1);
  CHECK(source.text.find("float deepest()") != std::string::npos);
  // 10,000 distinct files in a chain overflowed the stack; now the 33rd level is refused.
  const scratch_shaders deep(chain(10000));
  CHECK(message_of([&] { shader_library(deep.root).expand_file("main.frag"); }) ==
        "lib/c31.glsl:1: including \"lib/c32.glsl\" nests includes more than 32 deep");
  // A wide tree of large files: the sum is bounded, each file is once.
  scratch_shaders::file_list wide{{"main.frag", "#version 330 core\n"}};
  for (int i = 0; i < 5; ++i) {
    wide.front().second += "#include \"lib/w" + std::to_string(i) + ".glsl\"\n";
    wide.push_back({"lib/w" + std::to_string(i) + ".glsl", "// " + std::string(std::size_t{4} << 20, 'x') + "\n"});
  }
  const scratch_shaders large(wide);
  CHECK(message_of([&] { shader_library(large.root).expand_file("main.frag"); }).find("exceeds 16 MiB") != std::string::npos);
}

TEST_CASE("folders added to a library are searched in order, before its base folder") {
  scratch_shaders base({{"lib/a.glsl", "float a() { return 0.0; }\n"}, {"lib/b.glsl", "float b() { return 0.0; }\n"}});
  scratch_shaders first({{"lib/a.glsl", "float a() { return 1.0; }\n"}, {"my/top.glsl", "#include \"lib/a.glsl\"\n#include \"lib/b.glsl\"\n"}});
  scratch_shaders second({{"lib/a.glsl", "float a() { return 2.0; }\n"}, {"lib/b.glsl", "float b() { return 2.0; }\n"}});
  shader_library library(base.root);
  library.add_root(first.root);
  library.add_root(second.root);
  library.add_root(first.root);  // already searched: no effect
  CHECK(library.roots() == std::vector<fs::path>{first.root, second.root, base.root});
  CHECK(library.locate("lib/a.glsl") == first.root / "lib/a.glsl");
  CHECK(library.locate("lib/b.glsl") == second.root / "lib/b.glsl");
  const expanded_source source = library.expand_file("my/top.glsl");
  CHECK(source.text.find("return 1.0") != std::string::npos);
  CHECK(source.text.find("return 2.0") != std::string::npos);
  CHECK(source.text.find("return 0.0") == std::string::npos);
  CHECK(source.files_read == std::vector<fs::path>{first.root / "my/top.glsl", first.root / "lib/a.glsl", second.root / "lib/b.glsl"});
  // A file anywhere, its includes from the folders.
  const expanded_source elsewhere = library.expand_path(first.root / "my/top.glsl");
  CHECK(elsewhere.text == source.text);  // #line directives number the files; names are for messages
  CHECK(elsewhere.file_names.front() == (first.root / "my/top.glsl").string());
  CHECK(elsewhere.files_read == source.files_read);
  // Not found: every folder is named.
  const std::string missing = message_of([&] { library.locate("lib/c.glsl"); });
  CHECK(missing.find("shader file not found: " + (first.root / "lib/c.glsl").string() + ", " + (second.root / "lib/c.glsl").string() + ", " +
                     (base.root / "lib/c.glsl").string()) == 0);
  scratch_shaders includer(scratch_shaders::file_list{{"main.frag", "#version 330 core\n#include \"lib/c.glsl\"\n"}});
  library.add_root(includer.root);
  CHECK(message_of([&] { library.expand_file("main.frag"); }) ==
        "main.frag:2: included file \"lib/c.glsl\" not found (looked in " + first.root.string() + ", " + second.root.string() + ", " +
            includer.root.string() + ", " + base.root.string() + ")");
  CHECK(message_of([&] { library.add_root(base.root / "absent"); }) == "shader folder not found: " + (base.root / "absent").string() + " is not a folder");
}

TEST_CASE("a GLSL syntax error in an included file is reported at that file's line") {
  parity::test_shaders();  // the headless context
  scratch_shaders files({{"main.frag", "#version 330 core\n#include \"lib/broken.glsl\"\nout vec4 colour;\nvoid main() { colour = vec4(f()); }\n"},
                         {"lib/broken.glsl", "// a comment\nfloat f() {\n  return 1.0 +;\n}\n"},
                         {"main.vert", "#version 330 core\nvoid main() { gl_Position = vec4(0.0); }\n"}});
  const shader_library library(files.root);
  const std::string message = message_of([&] { load_program(library, "main.vert", "main.frag"); });
  CAPTURE(message);
  CHECK(message.find("GLSL compile error in fragment shader main.frag") == 0);
  CHECK(message.find("lib/broken.glsl:3:") != std::string::npos);
}

TEST_CASE("a GLSL error in the top-level file keeps its own line numbers after includes") {
  parity::test_shaders();
  scratch_shaders files({{"main.frag", "#version 330 core\n#include \"lib/ok.glsl\"\nout vec4 colour;\nvoid main() { colour = undefined_name; }\n"},
                         {"lib/ok.glsl", "float g() { return 2.0; }\n\n\n"},
                         {"main.vert", "#version 330 core\nvoid main() { gl_Position = vec4(0.0); }\n"}});
  const std::string message = message_of([&] { load_program(shader_library(files.root), "main.vert", "main.frag"); });
  CAPTURE(message);
  CHECK(message.find("main.frag:4:") != std::string::npos);
}

TEST_CASE("an undeclared name in an included user file is reported at that file's line, not the top-level file's") {
  parity::test_shaders();
  // Mesa reports a semantic error such as an undeclared name with source number 0 whatever file
  // it is in; line 3 of main.frag is a blank line, so a message naming main.frag:3 is wrong.
  scratch_shaders files({{"main.frag", "#version 330 core\n#include \"lib/consts.glsl\"\n\n#include \"mine/shade.glsl\"\n"
                                       "out vec4 colour;\nvoid main() { colour = vec4(shade()); }\n"},
                         {"lib/consts.glsl", "const float k_one = 1.0;\n"},
                         {"mine/shade.glsl", "// my shading\nfloat shade() {\n  return k_one * not_declared_anywhere;\n}\n"},
                         {"main.vert", "#version 330 core\nvoid main() { gl_Position = vec4(0.0); }\n"}});
  const std::string message = message_of([&] { load_program(shader_library(files.root), "main.vert", "main.frag"); });
  CAPTURE(message);
  CHECK(message.find("GLSL compile error in fragment shader main.frag") == 0);
  CHECK(message.find("mine/shade.glsl:3:") != std::string::npos);
  CHECK(message.find("not_declared_anywhere") != std::string::npos);  // the driver's own text is kept
  CHECK(message.find("main.frag:3:") == std::string::npos);
}

TEST_CASE("compiled_text numbers each line by its place; map_compile_log maps Mesa and NVIDIA logs to file and line") {
  // No GL here: the renumbering and the mapping are plain text.
  scratch_shaders files({{"main.frag", "#version 330 core\n#include \"lib/a.glsl\"\nvoid main() {}\n"},
                         {"lib/a.glsl", "// a\n#include \"lib/b.glsl\"\nfloat a() { return b(); }\n"},
                         {"lib/b.glsl", "float b() {\n  return 1.0;\n}\n"}});
  const expanded_source source = shader_library(files.root).expand_file("main.frag", {{"K", "1"}});
  const std::string compiled = compiled_text(source.text);
  const auto lines_of = [](const std::string& text) {
    std::vector<std::string> lines;
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);) lines.push_back(line);
    return lines;
  };
  const std::vector<std::string> original_lines = lines_of(source.text), compiled_lines = lines_of(compiled);
  // The same lines but for the numbers of the #line directives, each now the place of the line after it.
  REQUIRE(compiled_lines.size() == original_lines.size());
  int directives = 0;
  for (std::size_t i = 0; i < compiled_lines.size(); ++i) {
    CAPTURE(i);
    if (original_lines[i].rfind("#line ", 0) == 0) {
      ++directives;
      REQUIRE(compiled_lines[i].rfind("#line ", 0) == 0);
      CHECK(std::stoul(compiled_lines[i].substr(6)) == i + 2);
      CHECK(compiled_lines[i].substr(compiled_lines[i].rfind(' ')) == original_lines[i].substr(original_lines[i].rfind(' ')));  // the source number
    } else {
      CHECK(compiled_lines[i] == original_lines[i]);
    }
  }
  CHECK(directives == 5);  // one at the start of each file, one after each include
  // The 1-based place of a line of text in the expansion.
  const auto place_of = [&](const std::string& text) {
    for (std::size_t i = 0; i < compiled_lines.size(); ++i)
      if (compiled_lines[i] == text) return i + 1;
    FAIL("no line " << text);
    return std::size_t{0};
  };
  const std::string b_return = std::to_string(place_of("  return 1.0;"));
  const std::string a_line = std::to_string(place_of("float a() { return b(); }"));
  const std::string main_line = std::to_string(place_of("void main() {}"));
  // Mesa with the source number dropped to 0, and with the right one: the file and line either way.
  CHECK(map_compile_log("0:" + b_return + "(10): error: `x' undeclared\n", source) == "  lib/b.glsl:2:10: error: `x' undeclared\n");
  CHECK(map_compile_log("2:" + b_return + "(10): error: `x' undeclared\n", source) == "  lib/b.glsl:2:10: error: `x' undeclared\n");
  CHECK(map_compile_log("0:" + a_line + "(1): error: syntax error\n0:" + main_line + "(6): error: y\n", source) ==
        "  lib/a.glsl:3:1: error: syntax error\n  main.frag:3:6: error: y\n");
  // NVIDIA, and AMD.
  CHECK(map_compile_log("0(" + b_return + ") : error C1008: undefined variable \"x\"\n", source) ==
        "  lib/b.glsl:2 : error C1008: undefined variable \"x\"\n");
  CHECK(map_compile_log("ERROR: 0:" + a_line + ": 'b' : no matching overloaded function\n", source) ==
        "  lib/a.glsl:3: ERROR 'b' : no matching overloaded function\n");
  // A line beyond the text keeps the driver's numbers; other lines are kept as they are.
  CHECK(map_compile_log("1:9999(1): error: z\nsome note\n", source) == "  lib/a.glsl:9999:1: error: z\n  some note\n");
  // A #line that is a macro is not evaluated: the text is compiled as it is and mapped by source number.
  const std::string with_macro = "#version 330 core\n#define L 7\n#line L 1\nfloat f;\n";
  CHECK(compiled_text(with_macro) == with_macro);
  CHECK(map_compile_log("1:7(1): error: w\n", expanded_source{with_macro, {"main.frag", "lib/x.glsl"}, {}}) == "  lib/x.glsl:7:1: error: w\n");
}

TEST_CASE("a link error names the program's files") {
  parity::test_shaders();
  scratch_shaders files({{"main.frag", "#version 330 core\nin vec3 never_written;\nout vec4 colour;\nvoid main() { colour = vec4(never_written, 1.0); }\n"},
                         {"main.vert", "#version 330 core\nout vec2 never_written;\nvoid main() { never_written = vec2(0.0); gl_Position = vec4(0.0); }\n"}});
  const std::string message = message_of([&] { load_program(shader_library(files.root), "main.vert", "main.frag"); });
  CAPTURE(message);
  CHECK(message.find("GLSL link error in program main.vert + main.frag") == 0);
}

TEST_CASE("uniforms by name: a declared uniform the linker removed is a no-op, an undeclared name or field is an error") {
  parity::test_shaders();
  scratch_shaders files({{"lib/light.glsl", "struct light_settings {\n  vec3 position; // where\n  float cutoff[2];\n};\n"},
                         {"main.vert", "#version 330 core\nvoid main() { gl_Position = vec4(0.0); }\n"},
                         {"main.frag", "#version 330 core\n#include \"lib/light.glsl\"\nuniform light_settings light;\n"
                                       "uniform float unused_scale; /* declared, never read */\nuniform mat4 matrices[3];\nout vec4 colour;\n"
                                       "void main() { colour = vec4(light.position * light.cutoff[1], 1.0) * matrices[2][0].x; }\n"}});
  const program linked = load_program(shader_library(files.root), "main.vert", "main.frag");
  CHECK(linked.location("light.position") >= 0);
  CHECK(linked.location("light.cutoff[1]") >= 0);
  CHECK(linked.location("matrices[2]") >= 0);
  CHECK(linked.location("unused_scale") == -1);  // optimised away: allowed, setting it does nothing
  linked.set("unused_scale", 2.0f);
  CHECK(message_of([&] { linked.set("light.positon", glm::vec3(1.0f)); }) ==
        "program main.vert + main.frag declares no uniform 'light.positon' (its uniforms: light, matrices, unused_scale)");
  CHECK(message_of([&] { linked.set("lights.position", glm::vec3(1.0f)); }).find("declares no uniform 'lights.position'") != std::string::npos);
  check_gl("setting uniforms");
}

TEST_CASE("uniform blocks: set_uniform_block fills one, a removed block is a no-op, an unknown one or too few bytes is an error") {
  const shader_library& library = parity::test_shaders();
  const auto build = [&](const std::string& body) {
    return link_program("blocks", {{shader_stage::vertex, library.expand_text("#version 330 core\nvoid main() { gl_Position = vec4(0.0); }\n", "v.vert")},
                                   {shader_stage::fragment, library.expand_text("#version 330 core\nlayout(std140) uniform used { vec4 a; float b; };\n"
                                                                                "layout(std140) uniform unused { vec4 c; };\nout vec4 colour;\n"
                                                                                "void main() { " + body + " }\n", "f.frag")}});
  };
  const program linked = build("colour = a + vec4(b);");
  std::array<std::byte, 32> bytes{};
  const float b = 2.5f;
  std::memcpy(bytes.data() + 16, &b, sizeof b);
  linked.set_uniform_block("used", bytes);
  GLint bound = 0;
  glGetIntegeri_v(GL_UNIFORM_BUFFER_BINDING, glGetUniformBlockIndex(linked.id(), "used"), &bound);
  REQUIRE(bound != 0);
  float read_back = 0.0f;
  glBindBuffer(GL_UNIFORM_BUFFER, static_cast<GLuint>(bound));
  glGetBufferSubData(GL_UNIFORM_BUFFER, 16, sizeof read_back, &read_back);
  glBindBuffer(GL_UNIFORM_BUFFER, 0);
  CHECK(read_back == b);
  // Declared, not read: no error, whether the linker kept it (std140 blocks may stay active) or not.
  CHECK_NOTHROW(linked.set_uniform_block("unused", bytes));
  const std::string unknown = message_of([&] { linked.set_uniform_block("usde", bytes); });
  CHECK(unknown.find("program blocks declares no uniform block 'usde' (its blocks: unused, used)") != std::string::npos);
  const std::string short_by_one = message_of([&] { linked.set_uniform_block("used", bytes.data(), 31); });
  CHECK(short_by_one.find("uniform block 'used' holds 32 bytes, given 31") != std::string::npos);
  // A member of a block is not a default-block uniform: setting it by name is an error, not a no-op.
  CHECK(message_of([&] { linked.set("b", 1.0f); }).find("declares no uniform 'b'") != std::string::npos);
}

TEST_CASE("driver logs of Mesa, NVIDIA and AMD are mapped to file:line") {
  const std::vector<std::string> names = {"main.frag", "lib/x.glsl"};
  CHECK(map_log_to_files("1:12(5): error: syntax error\n", names) == "  lib/x.glsl:12:5: error: syntax error\n");
  CHECK(map_log_to_files("0(7) : error C0000: syntax error\n", names) == "  main.frag:7 : error C0000: syntax error\n");
  CHECK(map_log_to_files("ERROR: 1:3: 'f' : no matching overloaded function\n", names) ==
        "  lib/x.glsl:3: ERROR 'f' : no matching overloaded function\n");
  CHECK(map_log_to_files("7:1(1): error: x\n", names) == "  <source 7>:1:1: error: x\n");
}

TEST_CASE("every shipped pass program compiles and links") {
  const shader_library& library = parity::test_shaders();
  for (const std::pair<std::string, std::string>& stages : std::vector<std::pair<std::string, std::string>>{
           {"fullscreen.vert", "present.frag"}, {"fullscreen.vert", "blur_x.frag"}, {"scene.vert", "gbuffer.frag"},
           {"fullscreen.vert", "rsm_coarse.frag"}, {"fullscreen.vert", "temporal.frag"}}) {
    const std::string& vertex = stages.first;
    const std::string& fragment = stages.second;
    CAPTURE(fragment);
    CHECK_NOTHROW(load_program(library, vertex, fragment));
  }
  // The separable filter's x pass packing the y pass's taps (rgba16f buffers).
  CHECK_NOTHROW(load_program(library, "fullscreen.vert", "blur_x.frag", {{"VPLKIT_PACKED_BLUR", "1"}}));
  // The y pass for 2 x 2 pixels at once (indirect divisor 2), on packed or float taps.
  for (const char* packed : {"0", "1"}) CHECK_NOTHROW(load_program(library, "fullscreen.vert", "blur_y.frag", {{"VPLKIT_PACKED_BLUR", packed}}));
  // The variant programs, every define combination the pipeline uses.
  for (const char* light : {"0", "1"}) {
    CHECK_NOTHROW(load_program(library, "scene.vert", "rsm.frag", {{"VPLKIT_LIGHT_DIRECTIONAL", light}}));
    for (const char* indirect : {"0", "1"})
      for (const char* separable : {"0", "1"})
        CHECK_NOTHROW(load_program(library, "fullscreen.vert", "post.frag",
                                   {{"VPLKIT_INDIRECT", indirect}, {"VPLKIT_SEPARABLE", separable}, {"VPLKIT_LIGHT_DIRECTIONAL", light}}));
    CHECK_NOTHROW(load_program(library, "fullscreen.vert", "post.frag",
                               {{"VPLKIT_INDIRECT", "1"}, {"VPLKIT_SEPARABLE", "1"}, {"VPLKIT_PACKED_BLUR", "1"}, {"VPLKIT_LIGHT_DIRECTIONAL", light}}));
    for (const char* packed : {"0", "1"})
      CHECK_NOTHROW(load_program(library, "fullscreen.vert", "post.frag",
                                 {{"VPLKIT_INDIRECT", "1"}, {"VPLKIT_SEPARABLE", "1"}, {"VPLKIT_PACKED_BLUR", packed}, {"VPLKIT_QUAD_BLUR", "1"}, {"VPLKIT_LIGHT_DIRECTIONAL", light}}));
  }
  for (const char* coverage : {"0", "1"}) {
    for (const char* visibility : {"0", "2", "3", "6", "7", "8"})
      CHECK_NOTHROW(load_program(library, "fullscreen.vert", "gather.frag",
                                 {{"VPLKIT_RSM_PATTERN", "0"}, {"VPLKIT_VISIBILITY", visibility}, {"VPLKIT_RSM_COVERAGE", coverage}}));
    CHECK_NOTHROW(load_program(library, "fullscreen.vert", "gather.frag",
                               {{"VPLKIT_RSM_PATTERN", "1"}, {"VPLKIT_VISIBILITY", "0"}, {"VPLKIT_RSM_COVERAGE", coverage}}));
  }
  // The disk pattern has no paths: asking it for visibility is a compile error that says so.
  CHECK_THROWS_WITH_AS(load_program(library, "fullscreen.vert", "gather.frag", {{"VPLKIT_RSM_PATTERN", "1"}, {"VPLKIT_VISIBILITY", "6"}}),
                       doctest::Contains("the disk pattern has no paths"), vplkit::error);
}

TEST_CASE("GL errors reach the error path with the operation's name") {
  parity::test_shaders();
  REQUIRE(GLAD_GL_KHR_debug);  // Mesa has it on every context; the count below relies on it
  const std::size_t before = unchecked_gl_error_count();
  glBindTexture(GL_TEXTURE_2D + 1, 0);  // not a texture target: GL_INVALID_ENUM
  // Counted as soon as the driver reports it, until a check point turns it into an exception.
  CHECK(unchecked_gl_error_count() == before + 1);
  const std::string message = message_of([] { check_gl("binding a texture on purpose"); });
  CHECK(unchecked_gl_error_count() == before);
  CAPTURE(message);
  CHECK(message.find("GL error during binding a texture on purpose") == 0);
  CHECK(message.find("GL_INVALID_ENUM") != std::string::npos);
  CHECK_NOTHROW(check_gl("nothing"));  // cleared
}
