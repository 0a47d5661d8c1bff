// The manifest of the settings twins in docs/glsl-twins.md, made from the compile-time list
// (vplkit::glsl_twin_settings, include/vplkit/std140.hpp) and the source tree: for each struct the
// header that declares its C++ template, the lib file that declares its GLSL struct (each exactly
// one), its described fields, its std140 size and the parity test of its header. The table is
// printed, written to twin-manifest.md in the working folder, and must equal the page's copy, so a
// struct added to the list (or moved, or grown) shows on the page or fails here.
#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include <vplkit/std140.hpp>
#include "tests/gl_test_helpers.hpp"

namespace fs = std::filesystem;

namespace {

using vplkit::testing::source_dir;

std::string read_text(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  REQUIRE_MESSAGE(in, "cannot read " << path.string());
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// The one file of `folder` with extension `extension` whose text declares `struct <name> {`.
std::string declaring_file(const fs::path& folder, const std::string& extension, const std::string& name) {
  std::vector<std::string> found;
  for (const fs::directory_entry& entry : fs::directory_iterator(folder))
    if (entry.path().extension() == extension && read_text(entry.path()).find("struct " + name + " {") != std::string::npos)
      found.push_back(entry.path().filename().string());
  INFO("struct " << name << " in " << folder.string());
  CHECK(found.size() == 1);
  return found.empty() ? "(none)" : found.front();
}

}  // namespace

TEST_CASE("twin manifest: docs/glsl-twins.md lists every struct of glsl_twin_settings with its files and std140 size") {
  const fs::path root = source_dir();
  std::string table =
      "| C++ (`include/vplkit/`) | GLSL (`shaders/lib/`) | described fields | std140 bytes | parity test (`tests/parity/`) |\n"
      "|---|---|---|---|---|\n";
  std::size_t structs = 0;
  vplkit::for_each_glsl_twin_type([&](auto value) {
    using settings = decltype(value);
    const std::string name = vplkit::settings_description<settings>::name;
    const std::string header = declaring_file(root / "include" / "vplkit", ".hpp", name);
    const std::string lib = declaring_file(root / "shaders" / "lib", ".glsl", name);
    const std::string parity_test = "test_parity_" + fs::path(header).stem().string() + ".cpp";
    CHECK_MESSAGE(fs::exists(root / "tests" / "parity" / parity_test), name << ": its header " << header << " has no " << parity_test);
    CHECK_MESSAGE(fs::path(header).stem() == fs::path(lib).stem(), name << ": declared in " << header << " but " << lib);
    table += "| `" + name + "<float>` in `" + header + "` | `" + name + "` in `" + lib + "` | " +
             std::to_string(std::tuple_size_v<std::remove_cv_t<decltype(vplkit::settings_description<settings>::fields())>>) + " | " +
             std::to_string(vplkit::std140_size<settings>) + " | `" + parity_test + "` |\n";
    ++structs;
  });
  CHECK(structs == vplkit::glsl_twin_settings::size);
  std::cout << "the settings twins (" << structs << " structs of glsl_twin_settings):\n" << table;
  std::ofstream("twin-manifest.md") << table;
  const std::string docs = read_text(root / "docs" / "glsl-twins.md");
  const std::string begin = "<!-- twin-manifest: the test writes this table -->\n", end = "<!-- twin-manifest: end -->";
  const std::size_t from = docs.find(begin), to = docs.find(end);
  REQUIRE_MESSAGE((from != std::string::npos && to != std::string::npos && from < to),
                  "docs/glsl-twins.md has no manifest between '" << begin << "' and '" << end << "'");
  CHECK_MESSAGE(docs.substr(from + begin.size(), to - from - begin.size()) == table,
                "docs/glsl-twins.md's twin manifest is not the one glsl_twin_settings makes; it is in "
                    << fs::absolute("twin-manifest.md").string() << " (copy it between the markers)");
}
