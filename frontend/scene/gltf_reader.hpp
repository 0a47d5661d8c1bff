// The glTF reader's internals, shared by its parts (not installed, not for other code): the
// reader walks a model tinygltf has loaded (gltf_scene.cpp loads it, with vplkit's file policy)
// into a scene. gltf_reader.cpp: the node tree, cameras, lights and the notes; gltf_geometry.cpp:
// accessors, Draco and the primitives' triangles; gltf_materials.cpp: materials, samplers and
// textures.
#pragma once

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <unordered_map>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

#include <tiny_gltf.h>

#include "frontend/core/error.hpp"
#include "frontend/image/texture_decode.hpp"
#include "frontend/scene/draco.hpp"
#include "frontend/scene/gltf_scene.hpp"

namespace vplkit::gltf_detail {

// tinygltf hands over each image's bytes (a data URI decoded, or an external file read through
// gltf_scene.cpp's read_whole_file); they are kept undecoded, and only the images a base colour texture uses
// are decoded, after the model is read. An image in a buffer view is read from the buffer later
// with its bounds checked (tinygltf passes a pointer into the buffer without checking them).
using image_bytes = std::map<int, std::string>;

inline bool finite(const glm::dvec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

inline std::string number_text(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", value);
  return text;
}

// An accessor's elements where they lie in their buffer, checked once (count, offset, stride
// against the buffer view and the buffer, the component type); reading allocates nothing.
class accessor_view {
 public:
  accessor_view() = default;
  accessor_view(const unsigned char* base, std::size_t count, std::size_t stride, int component_type)
      : base_(base), count_(count), stride_(stride), component_type_(component_type) {}
  std::size_t count() const { return count_; }
  double get(std::size_t element, int component) const {
    const unsigned char* at = base_ + element * stride_;
    switch (component_type_) {
      case TINYGLTF_COMPONENT_TYPE_FLOAT: { float f; std::memcpy(&f, at + 4 * component, 4); return f; }
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: { std::uint32_t u; std::memcpy(&u, at + 4 * component, 4); return u; }
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: { std::uint16_t u; std::memcpy(&u, at + 2 * component, 2); return u; }
      default: return at[component];  // UNSIGNED_BYTE
    }
  }
  glm::dvec3 vec3(std::size_t element) const { return {get(element, 0), get(element, 1), get(element, 2)}; }

 private:
  const unsigned char* base_ = nullptr;
  std::size_t count_ = 0, stride_ = 0;
  int component_type_ = TINYGLTF_COMPONENT_TYPE_FLOAT;
};

// Reads one loaded model into a scene; read() once.
class reader {
 public:
  reader(const tinygltf::Model& model, const std::string& name, const gltf_limits& limits, const image_bytes& images)
      : model_(model), name_(name), limits_(limits), images_(images) {}

  scene read();

 private:
  [[noreturn]] void fail(const std::string& what) const { throw error(name_ + ": " + what); }

  // One line per feature the file has and vplkit does not read, the first time it is met.
  void note(const std::string& feature, const std::string& consequence);

  void note_model_features();

  std::string name_stem() const { return std::filesystem::path(name_).stem().string(); }

  std::vector<int> roots() const;

  glm::dmat4 local_transform(const tinygltf::Node& node, int index) const;

  // Depth first, children in their order (the first camera met and the lights' order are the same as a
  // recursive walk's), with an explicit stack: a chain of 20,000 nodes is as easy as a flat list.
  void walk(const std::vector<int>& roots);

  // The accessor's elements, `components` per element, after checking every byte it reads.
  accessor_view view_accessor(int index, int components, const std::string& what) const;

  // A primitive's attribute: decoded from its Draco data when the extension names it there, else
  // its accessor in place.
  accessor_view attribute_view(const tinygltf::Primitive& primitive, const draco_mesh* compressed, const std::string& name, int components,
                               const std::string& what) const;

  // The decoded Draco data of mesh `mesh`'s primitive `which` (decoded once however often the
  // mesh is instanced), or null when the primitive is not compressed.
  const draco_mesh* draco_of(int mesh, std::size_t which, const std::string& what);

  glm::vec3 albedo_of(int material) const;

  static constexpr int unread = -2;

  // A number of a JSON value, or fail.
  double number(const tinygltf::Value& value, const std::string& what) const;

  static texture_wrap wrap_of(int mode, bool& known);

  texture_sampler sampler_of(int index) const;

  // The encoded bytes of image `index`: from its buffer view (bounds checked) or as tinygltf read
  // its URI; both stay in memory while the model is read (they are not copied).
  std::string_view bytes_of_image(int index, const std::string& what) const;

  // Image `index` decoded into the library, or fail naming it. Each distinct content is decoded
  // once: images that name one file (or carry the same bytes) share its texture, so a file named
  // by four images costs one decode and one budget share, not four.
  int texture_of(int index);

  // What a primitive's material needs: the index of its surface_material (-1: plain, the factor
  // alone and opaque) and the TEXCOORD set its texture reads (-1: none).
  struct material_use {
    int material = -1;
    int texcoord_set = -1;
  };

  material_use material_for(int index);
  // A material's texture slot as read: the library texture (-1: none), its sampler, its
  // KHR_texture_transform and the TEXCOORD set it reads.
  struct texture_slot {
    int texture = -1;
    texture_sampler sampler;
    glm::mat2 matrix{1.0f};
    glm::vec2 offset{0.0f};
    int texcoord_set = -1;
  };
  int texcoord_set_of(const tinygltf::TextureInfo& info, const std::string& where) const;
  texture_slot texture_slot_of(const tinygltf::TextureInfo& info, const std::string& where, const std::string& slot, const std::string& without);
  glm::vec3 emission_of(const tinygltf::Material& source, const std::string& where) const;

  // TEXCOORD_<set> of a primitive where it lies in its buffer (normalized unsigned bytes and shorts
  // scaled to [0, 1], as the spec allows), or an empty view when the primitive has none.
  struct texcoord_view {
    accessor_view values;
    double scale = 1.0;
    std::string where;
    bool empty() const { return values.count() == 0; }
  };
  texcoord_view texture_coordinates(const tinygltf::Primitive& primitive, const draco_mesh* compressed, int set, std::size_t vertex_count,
                                    const std::string& what) const;

  // Vertex i's texture coordinate, checked as it is read.
  glm::vec2 texture_coordinate(const texcoord_view& texcoords, std::uint32_t i) const;

  void add_mesh(int index, const glm::dmat4& world);

  static glm::dvec3 axis(const glm::dmat4& world, const glm::dvec3& local) { return glm::normalize(glm::dmat3(world) * local); }

  void read_camera(int index, const glm::dmat4& world);

  void read_light(int index, const glm::dmat4& world);

  const tinygltf::Model& model_;
  std::string name_;
  gltf_limits limits_;
  const image_bytes& images_;
  std::vector<bool> visited_;
  mesh geometry_;
  material_library library_;
  std::vector<int> material_of_;  ///< glTF material -> library material (-1 plain, unread not yet)
  std::vector<int> texture_of_;   ///< glTF image -> library texture
  std::vector<int> texcoord_set_of_;  ///< glTF material -> the TEXCOORD set its textures read (-1: none), once read
  std::map<std::pair<int, std::size_t>, draco_mesh> draco_;  ///< (mesh, primitive) -> its decoded Draco data
  /// Decoded images by the hash of their bytes: (the bytes, the library texture).
  std::unordered_multimap<std::size_t, std::pair<std::string_view, int>> texture_of_bytes_;
  texture_budget texture_budget_{limits_.textures.max_scene_bytes, "gltf_limits::textures.max_scene_bytes"};
  std::vector<std::string> noted_, notes_;
  std::optional<camera> camera_;
  std::vector<scene_light> lights_;  ///< in the order met
  // The nodes in the walk's order with their depth and where their triangles begin: each named
  // one's subtree ends where the next node no deeper than it begins (scene_node).
  struct walked_node {
    int index;
    int depth;
    std::size_t first_index;
  };
  std::vector<walked_node> walked_;
  std::vector<scene_node> named_nodes() const;
};

}  // namespace vplkit::gltf_detail
