// Fuzz target: the OBJ and MTL parser (frontend/scene/obj_loader.hpp). The input is OBJ text, then
// optionally a NUL byte and the text every `mtllib` line gets. A malformed input must end in
// vplkit::error; a mesh that loads must pass check_mesh (finite, in range, indices valid) and
// have unit normals.
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstdio>
#include <string>
#include <string_view>

#include "frontend/core/error.hpp"
#include "frontend/scene/obj_loader.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view input(reinterpret_cast<const char*>(data), size);
  const std::size_t split = input.find('\0');
  const std::string_view obj = input.substr(0, split);
  const bool has_library = split != std::string_view::npos;
  const std::string library_text = has_library ? std::string(input.substr(split + 1)) : std::string();
  vplkit::obj_limits limits;
  limits.max_triangles = 1 << 16;  // keeps each run fast; the limit's own check is exercised too
  try {
    const vplkit::mesh loaded = vplkit::parse_obj(
        obj, "fuzz.obj",
        [&](const std::string& name) -> std::string {
          if (!has_library) throw vplkit::error(name + ": no such MTL file");
          return library_text;
        },
        limits);
    vplkit::check_mesh(loaded, "fuzz.obj");
    for (const vplkit::vertex& v : loaded.vertices)
      if (!(std::fabs(glm::length(v.normal) - 1.0f) < 1e-3f)) {
        std::fprintf(stderr, "fuzz_obj: a loaded normal is not a unit vector\n");
        std::abort();
      }
  } catch (const vplkit::error&) {
    // The expected outcome for malformed input: a message, nothing loaded.
  }
  return 0;
}
