// OBJ meshes with the MTL diffuse colour (Kd) times its texture (map_Kd) as the albedo, read by
// vplkit's own parser: the validation and the loading are one pass over the text, so no face
// reaches the mesh that was not checked (indices in range, every number finite as a float and
// within max_mesh_coordinate).
//
// Supported: v (x y z, optional w or r g b), vn, vt (u v; v is flipped to glTF's convention,
// frontend/scene/material.hpp), f with v, v/vt, v//vn and v/vt/vn corners (negative indices count
// from the end), mtllib, usemtl; o, g, s, l, p and other statements are skipped. In MTL files:
// newmtl, Kd and map_Kd (PNG or JPEG, next to the OBJ; -o and -s offset and scale its
// coordinates, -clamp on clamps them, the other options are skipped); a face without vt corners
// takes Kd alone. Convex polygons are fans; others are triangulated by GLU's tessellator in their
// best-fit plane (frontend/scene/polygon.hpp), and one whose edges cross is an error. Lines end
// in LF or CRLF; any other control character is an error, so what the parser sees is what an
// editor shows.
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <string_view>

#include "frontend/image/texture_decode.hpp"
#include "frontend/scene/scene.hpp"

namespace vplkit {

/// What an OBJ file may make vplkit allocate.
struct obj_limits {
  std::uintmax_t max_obj_bytes = std::uintmax_t{1} << 30;  ///< 1 GiB
  std::uintmax_t max_mtl_bytes = std::uintmax_t{1} << 24;  ///< 16 MiB per material library
  std::size_t max_triangles = std::size_t{1} << 24;        ///< after triangulation
  std::uintmax_t max_texture_file_bytes = std::uintmax_t{1} << 28;  ///< 256 MiB per map_Kd file
  texture_limits textures;  ///< each map_Kd image; max_scene_bytes: all of them with mipmaps
};

/// Returns the text of the material library an `mtllib` line names (or throws vplkit::error).
using material_library_reader = std::function<std::string(const std::string& library)>;
/// Returns the bytes of the texture file a `map_Kd` line names (or throws vplkit::error).
using texture_file_reader = std::function<std::string(const std::string& file)>;

/// Loads triangles with per-vertex normals (the OBJ's, or the area-weighted mean of the adjacent
/// face normals where it has none), albedo from the material's Kd (0.73 grey without one) and its
/// map_Kd texture (decoded only when a face uses the material). Material libraries and textures
/// are found next to the OBJ file; each must be a regular file. Throws vplkit::error naming
/// file:line for malformed input, and the file for one too large or a texture that does not
/// decode.
mesh load_obj(const std::filesystem::path& path, const obj_limits& limits = {});

/// The same from text in memory; `name` starts every message ("<name>:<line>: ..."). Without
/// `read_texture`, a used material with a map_Kd is an error.
mesh parse_obj(std::string_view text, const std::string& name, const material_library_reader& read_library, const obj_limits& limits = {},
               const texture_file_reader& read_texture = {});

}  // namespace vplkit
