// KHR_draco_mesh_compression: a glTF primitive's triangles and attributes decoded from their
// Draco buffer view by Google's libdraco (Debian's libdraco-dev), and the JSON edit that lets
// tinygltf read such a file at all.
#pragma once

#include <cstddef>
#include <cstdint>
#include <map>
#include <string>
#include <string_view>
#include <vector>

namespace vplkit {

/// A Draco mesh as the glTF reader uses it: three point indices per triangle, and per glTF
/// attribute (POSITION, NORMAL, TEXCOORD_0, ...) its values as floats, `components` per point.
struct draco_mesh {
  struct attribute {
    int components = 0;
    std::vector<float> values;  ///< points x components (normalized integers scaled to [0, 1] or [-1, 1])
  };
  std::size_t points = 0;
  std::vector<std::uint32_t> indices;
  std::map<std::string, attribute> attributes;
};

/// Decodes `size` bytes of Draco mesh data. `attribute_ids` maps each glTF attribute name to its
/// Draco unique id (the extension's "attributes"). Throws vplkit::error starting with `where`
/// when the data is not a Draco triangle mesh, an id names no attribute, or the mesh has more
/// than `max_triangles` triangles.
draco_mesh decode_draco_mesh(const unsigned char* bytes, std::size_t size, const std::map<std::string, int>& attribute_ids,
                             std::size_t max_triangles, const std::string& where);

/// tinygltf (Debian's build has no Draco) refuses a primitive whose indices accessor has no
/// buffer view, which a Draco-compressed primitive's need not have. Returns the glTF JSON with
/// the "indices" of every primitive that has KHR_draco_mesh_compression removed (the reader takes
/// the triangles from the Draco data), or an empty string when the text names no such
/// extension or is not JSON nlohmann's parser reads (tinygltf then reports it).
std::string without_draco_indices(std::string_view json);

/// The glTF's asset.version as written (a string, or a number as text), or "" when the JSON
/// has none or does not parse.
std::string declared_gltf_version(std::string_view json);

}  // namespace vplkit
