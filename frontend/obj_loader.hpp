// OBJ meshes (tinyobjloader), with the MTL diffuse colour (Kd) as the albedo. Before tinyobj
// parses a file, a validation pass reads it line by line so that bad input is reported as
// file:line: face indices out of range, NaN or Inf coordinates, lines that do not parse; then
// a file without faces, or one that cannot be opened, is reported by name.
#pragma once

#include <filesystem>

#include "frontend/scene.hpp"

namespace vplkit {

/// Loads triangles (polygons are fan-triangulated) with per-vertex normals (the OBJ's, or the
/// area-weighted mean of the adjacent face normals where it has none) and albedo from the material's Kd (0.73 grey without one).
/// Throws vplkit::error naming file:line for malformed input.
mesh load_obj(const std::filesystem::path& path);

}  // namespace vplkit
