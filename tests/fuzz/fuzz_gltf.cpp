// Fuzz target: the glTF 2.0 reader (frontend/scene/gltf_scene.hpp over tinygltf). The input is a
// .gltf text or, when it starts with the GLB magic, a .glb; external buffers are refused (no
// folder). A malformed input must end in vplkit::error; a scene that loads must pass check_scene.
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "frontend/core/error.hpp"
#include "frontend/scene/gltf_scene.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string bytes(reinterpret_cast<const char*>(data), size);
  const bool binary = bytes.compare(0, 4, "glTF") == 0;
  vplkit::gltf_limits limits;
  limits.max_triangles = 1 << 16;  // keeps each run fast; the limit's own check is exercised too
  try {
    const vplkit::scene loaded = vplkit::parse_gltf(bytes, binary, "fuzz.gltf", {}, limits);
    vplkit::check_scene(loaded);
  } catch (const vplkit::error&) {
  }
  return 0;
}
