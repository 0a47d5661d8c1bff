// Fuzz target: the shader #include expander (frontend/gl/program.hpp, shader_library), fed with
// include trees that a generator (fuzz_input) builds from the bytes: up to 40 files, or a chain up
// to 300 deep, whose lines are includes of each other (in every spelling the directive scanner
// meets: spaces, comments, trailing words, missing or empty names, a name longer than a path),
// #version lines in and out of place, CR line ends, code, and text of the input itself (never an
// '@', which marks the code lines). The files
// are written to a scratch folder (the expander reads files) and expanded from main.frag. The folder
// is on tmpfs (/dev/shm) when there is one, and the files stay from one input to the next: each
// input rewrites the files it has in place and removes the ones it has not, because creating and
// deleting hundreds of files an input made the file system, not the expander, the fuzzer's cost.
// A bad tree must end in vplkit::error naming a file; an expansion must name each file once, start
// with main.frag, hold each file's code once, and stay within the depth and size limits.
#include <unistd.h>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <set>
#include <string>
#include <vector>

#include "frontend/core/error.hpp"
#include <vplkit/gl/program.hpp>
#include "tests/fuzz/fuzz_input.hpp"

namespace fs = std::filesystem;
using vplkit::fuzzing::fuzz_input;

namespace {

void require(bool condition, const char* what) {
  if (!condition) {
    std::fprintf(stderr, "fuzz_shader_includes: %s\n", what);
    std::abort();
  }
}

const fs::path& scratch() {
  static const fs::path folder = [] {
    std::error_code ignored;
    const fs::path parent = fs::is_directory("/dev/shm", ignored) && ::access("/dev/shm", W_OK) == 0 ? fs::path("/dev/shm") : fs::temp_directory_path();
    const fs::path root = parent / ("vplkit-fuzz-includes-" + std::to_string(::getpid()));
    fs::remove_all(root, ignored);
    fs::create_directories(root / "lib" / "deep");
    static fs::path removed_at_exit = root;
    std::atexit([] {
      std::error_code failed;
      fs::remove_all(removed_at_exit, failed);
    });
    return root;
  }();
  return folder;
}

// How many files (main.frag, lib/f1.glsl, ...) the previous input left in the scratch folder.
std::uint32_t files_on_disk = 0;

std::string file_name(std::uint32_t index) { return index == 0 ? "main.frag" : (index % 5 == 0 ? "lib/deep/f" : "lib/f") + std::to_string(index) + ".glsl"; }

std::string include_line(fuzz_input& in, std::uint32_t target) {
  const std::string name = file_name(target);
  switch (in.below(12)) {
    case 0: return "  #  include \"" + name + "\"";
    case 1: return "#include \"" + name + "\" // a comment";
    case 2: return "#include \"" + name + "\" trailing";  // refused, naming the line: text after the name
    case 3: return "#include <" + name + ">";
    case 4: return "#include \"missing.glsl\"";
    case 5: return "#include \"\"";
    case 6: return "#include \"" + std::string(4100, 'x') + "\"";
    case 7: return "#includes \"" + name + "\"";
    case 8: return "#include \"" + name;
    default: return "#include \"" + name + "\"";
  }
}

// Raw bytes of the input, except that '@' becomes '_': the code lines below carry '@', so the random
// text can never spell one of them and "a file's code appears twice" can only mean a file read twice
// (an input once spelled "float code_0() { return 1.0; }" in its random text, which the expander
// rightly kept, and the property fired on valid behaviour).
std::string random_text(fuzz_input& in, std::uint32_t count) {
  std::string text = in.take(count);
  std::replace(text.begin(), text.end(), '@', '_');
  return text;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  fuzz_input in(data, size);
  const bool chain = in.below(4) == 0;
  const std::uint32_t files = chain ? 2 + in.below(300) : 1 + in.below(40);
  std::vector<std::string> code_of(files);  // each file's one code line, to find in the expansion
  for (std::uint32_t f = 0; f < files; ++f) {
    std::string text;
    if (f == 0 && in.below(8) != 0) text += "#version 330 core\n";
    code_of[f] = "float code_" + std::to_string(f) + "() { return 1.0; }  // @" + std::to_string(f) + "@";
    const std::uint32_t lines = chain ? 2 : in.below(8);
    bool code_written = false;
    for (std::uint32_t l = 0; l < lines; ++l) {
      const char* end = in.below(16) == 0 ? "\r\n" : "\n";
      if (chain) {
        text += (l == 0 ? code_of[f] : (f + 1 < files ? include_line(in, f + 1) : std::string("// end"))) + end;
        continue;
      }
      switch (in.below(6)) {
        case 0:
        case 1:
        case 2: text += include_line(in, in.below(files + 1)) + end; break;
        case 3:
          text += (code_written ? std::string("// code") : code_of[f]) + end;
          code_written = true;
          break;
        case 4: text += std::string(in.below(4) == 0 ? "#version 330 core" : "// text ") + end; break;
        default: text += random_text(in, in.below(32)) + end; break;
      }
    }
    std::ofstream(scratch() / file_name(f), std::ios::binary | std::ios::trunc) << text;
  }
  for (std::uint32_t f = files; f < files_on_disk; ++f) fs::remove(scratch() / file_name(f));
  files_on_disk = files;
  try {
    const vplkit::shader_library library(scratch());
    const vplkit::expanded_source source = library.expand_file("main.frag");
    require(!source.file_names.empty() && source.file_names.front() == "main.frag", "the expansion does not start with main.frag");
    require(std::set<std::string>(source.file_names.begin(), source.file_names.end()).size() == source.file_names.size(), "a file is named twice");
    require(source.file_names.size() <= files, "more files than exist");
    require(source.text.size() <= vplkit::max_expanded_bytes + 64 * source.file_names.size() + 4096, "the expansion exceeds its limit");
    // Each expanded file's code line is in the text once at most (each file is read once).
    for (std::uint32_t f = 0; f < files; ++f) {
      const std::size_t first = source.text.find(code_of[f] + "\n");
      if (first != std::string::npos) require(source.text.find(code_of[f] + "\n", first + 1) == std::string::npos, "a file's code appears twice");
    }
    if (chain) require(source.file_names.size() <= static_cast<std::size_t>(vplkit::max_include_depth) + 1, "an include chain deeper than the limit");
  } catch (const vplkit::error& failure) {
    require(failure.what()[0] != '\0', "an error without a message");
  }
  return 0;
}
