// glTF 2.0 scenes (.gltf with embedded or external buffers, .glb), read and written with
// tinygltf (Debian's libtinygltf-dev). What a scene carries in vplkit and how it maps:
//
//   geometry  every TRIANGLES, TRIANGLE_STRIP and TRIANGLE_FAN primitive of the scene's node
//             tree (the default scene, else the first, else every root node), indexed or not,
//             strips and fans numbered as the spec does (every triangle wound as the first), in
//             world space through the node transforms (matrix or TRS; a mirroring transform keeps
//             the front faces front). Points and lines are skipped. Without NORMAL a primitive
//             gets flat normals, as the glTF spec asks. KHR_draco_mesh_compression primitives
//             are decoded by libdraco (frontend/scene/draco.hpp). glTF 1.0 files are refused as
//             such (by asset.version, or a GLB container of version 1).
//   albedo    the material's baseColorFactor (linear RGB) times its baseColorTexture (PNG or
//             JPEG, frontend/image/texture_decode.hpp; sRGB decoded; the sampler's wrap modes
//             and filters, mipmapped; KHR_texture_transform's offset, rotation, scale and
//             texCoord) at TEXCOORD_n (float, or normalized unsigned bytes or shorts); alphaMode
//             MASK with alphaCutoff cuts out (frontend/scene/material.hpp); BLEND is drawn opaque.
//             No material: the spec's default, white (1, 1, 1). A primitive whose textured
//             material lacks its TEXCOORD set takes the factor alone.
//   camera    the first perspective camera node met (depth first): it looks down its -Z with
//             +Y up, yfov is the vertical field of view, znear/zfar the planes (zfar absent:
//             1000 x znear). Orthographic cameras are not read.
//   lights    every KHR_lights_punctual light node (spot, directional, point), in the order met
//             depth first; spots and suns shine down their node's -Z. glTF states intensity
//             photometrically (cd for a spot or point light, lux for a sun); vplkit's lights are
//             radiometric and unit-free, so intensity x color is read as the radiant intensity
//             (W/sr) of a spot or point light and the sun's irradiance (W/m^2), one to one
//             (write_gltf writes the same numbers back). Cone angles become cos_inner/cos_outer.
//             `range` is not read (inverse-square falloff without a cut-off). A file with more
//             than max_scene_lights lights reads; check_scene refuses it until some are chosen.
// A file without a light or a camera gets them from frame_mesh (a room is lit and seen from
// inside; an object or open scene gets a three-quarter view, a spot light and a floor, the floor
// only when the light is placed too); what was placed is a note of the scene.
// What the file has and vplkit does not read is named once per feature in the scene's notes:
// other texture slots (normal, occlusion, metallic-roughness), alphaMode BLEND, vertex colours,
// morph targets, skins, animations, light ranges, orthographic cameras, points and lines,
// material extensions, and every extension the file uses or requires other than
// KHR_lights_punctual, KHR_texture_transform, KHR_draco_mesh_compression and
// KHR_materials_emissive_strength. Emissive materials (emissiveFactor x emissiveStrength x
// emissiveTexture) are read and drawn as seen; a note says that they do not light the scene.
//
// Every index, count, offset and stride is checked against its buffer before it is read, every
// number for being finite; a bad file throws vplkit::error naming the file and the problem. Images
// are decoded only when a base colour texture uses them, each distinct file once however many
// images name it, each within gltf_limits::textures, and all together, with their mipmaps, within
// textures.max_scene_bytes (1 GiB).
// Nothing recurses on the input's depth: the JSON's nesting is measured (skipping strings) before
// tinygltf parses it (its conversion recurses per level), and the node tree is walked with an
// explicit stack. External files (buffers, images) are read only from the glTF's folder tree:
// the URI, percent-decoded once (by tinygltf), must be a relative path without a ".." component,
// and all of them together count against one budget. Accessors are read in place (nothing is
// widened or copied), their sizes checked before anything is allocated, and a primitive with
// normals keeps its vertices shared (indexed) in the mesh.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>

#include "frontend/image/texture_decode.hpp"
#include "frontend/scene/scene.hpp"

namespace vplkit {

/// What a glTF file may make vplkit read and allocate.
struct gltf_limits {
  std::uintmax_t max_file_bytes = std::uintmax_t{1} << 30;      ///< the .gltf/.glb file
  std::uintmax_t max_external_bytes = std::uintmax_t{1} << 30;  ///< every external buffer and image together
  std::size_t max_triangles = std::size_t{1} << 24;
  texture_limits textures;  ///< each base colour texture's image; max_scene_bytes: all of them with mipmaps
  /// Arrays and objects nested in the JSON (glTF's own schema nests 7 deep; extras take the rest).
  int max_json_depth = 64;
};

/// Loads a .gltf or .glb file (external buffers and images are read from its folder tree).
scene load_gltf(const std::filesystem::path& path, const gltf_limits& limits = {});

/// The same from bytes in memory: `binary` for GLB; external buffers are looked up in
/// `base_dir`, or refused when it is empty. `name` starts every message.
scene parse_gltf(const std::string& bytes, bool binary, const std::string& name, const std::filesystem::path& base_dir,
                 const gltf_limits& limits = {});

/// The scene as glTF 2.0 text with its buffer embedded (a data URI): one mesh with a primitive
/// per albedo, a perspective camera node and a KHR_lights_punctual light node.
/// Throws vplkit::error for a mesh with material ranges (textures are not written; the built-in
/// scenes export-scene writes have none).
std::string gltf_text(const scene& source);

}  // namespace vplkit
