#include "frontend/scene/gltf_scene.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <functional>
#include <limits>
#include <map>
#include <optional>
#include <sstream>
#include <string_view>
#include <unordered_map>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>

#include <tiny_gltf.h>

#include "frontend/core/error.hpp"
#include "frontend/core/files.hpp"
#include "frontend/image/texture_decode.hpp"
#include "frontend/scene/draco.hpp"

namespace fs = std::filesystem;

namespace vplkit {
namespace {

std::string size_text(std::uintmax_t bytes) {
  if (bytes >= (std::uintmax_t{1} << 30) && bytes % (std::uintmax_t{1} << 30) == 0) return std::to_string(bytes >> 30) + " GiB";
  if (bytes >= (std::uintmax_t{1} << 20) && bytes % (std::uintmax_t{1} << 20) == 0) return std::to_string(bytes >> 20) + " MiB";
  return std::to_string(bytes) + " bytes";
}

// tinygltf's file access, bounded: only regular files in the glTF's folder tree, named by a
// relative path without "..", all of them together at most max_bytes; nothing written. Without a
// folder (parse_gltf from memory) nothing is read. tinygltf has percent-decoded the URI once and
// joined it to the folder; it then also tries the current folder, which is never ours.
struct file_access {
  std::string base_dir;            ///< as tinygltf joins it
  std::uintmax_t max_bytes = 0;    ///< the budget of all external files
  std::uintmax_t used_bytes = 0;
  std::string refusal;             ///< why a file was refused: the message, not tinygltf's
};

std::string folder_prefix(const std::string& base) { return base.empty() || base.back() == '/' ? base : base + "/"; }

bool file_exists(const std::string& path, void* user) {
  const auto* access = static_cast<const file_access*>(user);
  if (access->base_dir.empty()) return true;  // read_whole_file then says why it is refused
  // Only the candidate in the glTF's folder; read_whole_file decides whether it may be read.
  return path.compare(0, folder_prefix(access->base_dir).size(), folder_prefix(access->base_dir)) == 0;
}

std::string expand_file_path(const std::string& path, void*) { return path; }

// Why a URI (percent-decoded, relative to the glTF's folder) may not be read; empty when it may.
std::string refused_path(const std::string& relative) {
  if (relative.empty()) return "it is empty";
  if (relative.find('\0') != std::string::npos) return "it contains a NUL character";
  if (relative.front() == '/') return "it is an absolute path";
  for (std::size_t begin = 0; begin <= relative.size();) {
    std::size_t end = relative.find('/', begin);
    if (end == std::string::npos) end = relative.size();
    if (relative.compare(begin, end - begin, "..") == 0) return "it has a '..' component";
    begin = end + 1;
  }
  return {};
}

bool read_whole_file(std::vector<unsigned char>* out, std::string* err, const std::string& path, void* user) {
  auto* access = static_cast<file_access*>(user);
  const auto refuse = [&](const std::string& why) {
    access->refusal = why;
    if (err) *err += why;
    return false;
  };
  if (access->base_dir.empty()) return refuse("external file '" + excerpt_path(path) + "' refused: the glTF was given from memory");
  const std::string relative = path.substr(folder_prefix(access->base_dir).size());
  if (const std::string why = refused_path(relative); !why.empty())
    return refuse("external file '" + excerpt_path(relative) + "' refused: " + why + " (a glTF reads files in its own folder tree only)");
  try {
    std::error_code code;
    const std::uintmax_t bytes = fs::is_regular_file(path, code) ? fs::file_size(path, code) : 0;
    if (!code && access->used_bytes + bytes > access->max_bytes)
      return refuse("external file '" + excerpt_path(relative) + "' (" + std::to_string(bytes) + " bytes) would bring its external data to " +
                    std::to_string(access->used_bytes + bytes) + " bytes, more than the " + size_text(access->max_bytes) +
                    " vplkit reads for one glTF (all buffers and images together)");
    read_file_into(path, access->max_bytes - access->used_bytes, "glTF external file", *out);
    access->used_bytes += out->size();
    return true;
  } catch (const error& failure) {
    return refuse(failure.what());
  }
}

bool write_whole_file(std::string* err, const std::string&, const std::vector<unsigned char>&, void*) {
  if (err) *err += "vplkit does not write files while reading a glTF";
  return false;
}

// tinygltf hands over each image's bytes (a data URI decoded, or an external file read through
// read_whole_file above); they are kept undecoded, and only the images a base colour texture uses
// are decoded, after the model is read. An image in a buffer view is read from the buffer later
// with its bounds checked (tinygltf passes a pointer into the buffer without checking them).
using image_bytes = std::map<int, std::string>;

bool keep_image_bytes(tinygltf::Image* image, const int index, std::string*, std::string*, int, int, const unsigned char* bytes, int size, void* user) {
  if (image->bufferView >= 0 || size <= 0) return true;
  (*static_cast<image_bytes*>(user))[index].assign(reinterpret_cast<const char*>(bytes), static_cast<std::size_t>(size));
  return true;
}

// The extensions the reader reads; any other one the file uses or requires is named in a note.
bool extension_read(const std::string& name) {
  return name == "KHR_lights_punctual" || name == "KHR_texture_transform" || name == "KHR_draco_mesh_compression";
}

// glTF 1.0 (a different schema: objects keyed by id where 2.0 has arrays, techniques and
// shaders) is refused by its declared version rather than read as a 2.0 file without meshes.
void refuse_gltf_1(const std::string& version, const std::string& how, const std::string& name) {
  if (version == "1" || version.rfind("1.", 0) == 0)
    throw error(name + ": a glTF 1.0 file (" + how + "); vplkit reads glTF 2.0 only (glTF 1.0 is not read: convert it, e.g. with gltf-pipeline or Blender)");
}

// The deepest nesting of arrays and objects in JSON text (strings skipped, escapes too), checked
// before tinygltf parses it: its conversion to tinygltf::Value recurses once per level, and a
// 40 KB file nested 20,000 deep overflows the stack.
void check_json_depth(std::string_view json, const std::string& name, int max_depth) {
  int depth = 0;
  bool in_string = false;
  for (std::size_t at = 0; at < json.size(); ++at) {
    const char c = json[at];
    if (in_string) {
      if (c == '\\') ++at;
      else if (c == '"') in_string = false;
    } else if (c == '"') {
      in_string = true;
    } else if (c == '[' || c == '{') {
      if (++depth > max_depth)
        throw error(name + ": its JSON nests arrays and objects more than " + std::to_string(max_depth) + " deep (at byte " + std::to_string(at) +
                    "); vplkit reads at most " + std::to_string(max_depth) + " levels");
    } else if (c == ']' || c == '}') {
      --depth;
    }
  }
}

// The JSON chunk of a GLB, when its header and first chunk are well formed (tinygltf reports
// the rest).
std::string_view glb_json(const std::string& bytes) {
  const auto word = [&](std::size_t at) {
    std::uint32_t value = 0;
    std::memcpy(&value, bytes.data() + at, 4);
    return value;  // GLB is little-endian, as is every machine vplkit builds on
  };
  if (bytes.size() < 20 || word(16) != 0x4E4F534Au) return {};  // "JSON"
  const std::uint32_t length = word(12);
  if (length > bytes.size() - 20) return {};
  return std::string_view(bytes).substr(20, length);
}

bool finite(const glm::dvec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

std::string number_text(double value) {
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

// Source vertex -> mesh vertex of one primitive instance: a table when the primitive uses many
// of its accessor's vertices, a hash map when it uses few of a large one (so that instancing a
// 3-index primitive of a 10^7-vertex accessor 1000 times costs 3000 entries, not 10^10).
class vertex_map {
 public:
  vertex_map(std::size_t vertex_count, std::size_t corner_count) {
    if (vertex_count <= 4 * corner_count + 1024) table_.assign(vertex_count, none);
  }
  static constexpr std::uint32_t none = 0xffffffffu;
  std::uint32_t find(std::uint32_t source) const {
    if (!table_.empty()) return table_[source];
    const auto found = map_.find(source);
    return found == map_.end() ? none : found->second;
  }
  void insert(std::uint32_t source, std::uint32_t target) {
    if (!table_.empty()) table_[source] = target;
    else map_.emplace(source, target);
  }

 private:
  std::vector<std::uint32_t> table_;
  std::unordered_map<std::uint32_t, std::uint32_t> map_;
};

// TRIANGLES (4, or -1: tinygltf's value when the mode is absent), TRIANGLE_STRIP (5) and
// TRIANGLE_FAN (6) have triangles; POINTS and LINES* nothing to shade.
bool has_triangles(const tinygltf::Primitive& primitive) {
  return primitive.mode == TINYGLTF_MODE_TRIANGLES || primitive.mode == -1 || primitive.mode == TINYGLTF_MODE_TRIANGLE_STRIP ||
         primitive.mode == TINYGLTF_MODE_TRIANGLE_FAN;
}

// How many triangles `corners` indices (or vertices) make in the primitive's mode.
std::size_t triangles_in(int mode, std::size_t corners) {
  if (mode == TINYGLTF_MODE_TRIANGLE_STRIP || mode == TINYGLTF_MODE_TRIANGLE_FAN) return corners >= 3 ? corners - 2 : 0;
  return corners / 3;
}

// The corners of triangle t, as the glTF 2.0 specification (3.7.2.1) numbers them: a strip's
// odd triangles swap their last two corners, so that every triangle winds as the first does; a
// fan's triangle t is (t + 1, t + 2, 0).
std::array<std::size_t, 3> triangle_corners(int mode, std::size_t t) {
  if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) return t % 2 == 0 ? std::array<std::size_t, 3>{t, t + 1, t + 2} : std::array<std::size_t, 3>{t, t + 2, t + 1};
  if (mode == TINYGLTF_MODE_TRIANGLE_FAN) return {t + 1, t + 2, 0};
  return {3 * t, 3 * t + 1, 3 * t + 2};
}

class reader {
 public:
  reader(const tinygltf::Model& model, const std::string& name, const gltf_limits& limits, const image_bytes& images)
      : model_(model), name_(name), limits_(limits), images_(images) {}

  scene read() {
    note_model_features();
    visited_.assign(model_.nodes.size(), false);
    material_of_.assign(model_.materials.size(), unread);
    texture_of_.assign(model_.images.size(), unread);
    walk(roots());
    if (geometry_.indices.empty())
      fail("no triangles in its scene (TRIANGLES, TRIANGLE_STRIP and TRIANGLE_FAN primitives are read; points and lines are not drawn)");
    if (!library_.materials.empty()) geometry_.materials = std::make_shared<const material_library>(std::move(library_));
    framing_needs needs;
    needs.camera = !camera_;
    needs.light = !light_;
    scene framed = frame_mesh(name_stem(), std::move(geometry_), needs);
    if (light_) framed.light = *light_;
    if (camera_) framed.view = *camera_;
    framed.name = name_stem();
    framed.notes.insert(framed.notes.begin(), notes_.begin(), notes_.end());
    return framed;
  }

 private:
  [[noreturn]] void fail(const std::string& what) const { throw error(name_ + ": " + what); }

  // One line per feature the file has and vplkit does not read, the first time it is met.
  void note(const std::string& feature, const std::string& consequence) {
    if (std::find(noted_.begin(), noted_.end(), feature) != noted_.end()) return;
    noted_.push_back(feature);
    notes_.push_back(name_ + ": " + feature + " not read (" + consequence + ")");
  }

  void note_model_features() {
    for (const std::string& extension : model_.extensionsRequired)
      if (!extension_read(extension)) note("required extension " + extension, "vplkit does not know it; the scene may look other than its author meant");
    for (const std::string& extension : model_.extensionsUsed)
      if (!extension_read(extension) &&
          std::find(model_.extensionsRequired.begin(), model_.extensionsRequired.end(), extension) == model_.extensionsRequired.end())
        note("extension " + extension, "what it adds is left out");
    if (!model_.animations.empty()) note("animations", "the scene is drawn at rest");
    if (!model_.skins.empty()) note("skins", "skinned meshes are drawn in their bind pose");
    int spots_and_suns = 0;
    for (const tinygltf::Light& light : model_.lights) {
      if (light.type == "point") note("point lights", "vplkit's primary light is one spot light or one sun; a file with only point lights is framed with a spot light");
      if (light.type == "spot" || light.type == "directional") ++spots_and_suns;
    }
    if (spots_and_suns > 1) note("lights after the first", "vplkit renders one primary light: the first spot or directional light met in the node tree");
    for (const tinygltf::Camera& source : model_.cameras)
      if (source.type != "perspective") note("orthographic cameras", "the first perspective camera is used, else a framing camera");
    for (const tinygltf::Material& material : model_.materials) {
      if (material.normalTexture.index >= 0) note("normalTexture", "surfaces are shaded with their geometric normals");
      if (material.occlusionTexture.index >= 0) note("occlusionTexture", "the techniques compute their own occlusion");
      if (material.emissiveTexture.index >= 0) note("emissiveTexture", "surfaces do not emit");
      if (material.emissiveFactor.size() == 3 && (material.emissiveFactor[0] > 0.0 || material.emissiveFactor[1] > 0.0 || material.emissiveFactor[2] > 0.0))
        note("emissiveFactor", "surfaces do not emit");
      if (material.pbrMetallicRoughness.metallicRoughnessTexture.index >= 0)
        note("metallicRoughnessTexture", "surfaces are diffuse: the base colour is their albedo");
      if (material.alphaMode == "BLEND") note("alphaMode BLEND", "blended surfaces are drawn opaque");
      if (material.doubleSided)
        note("doubleSided materials", "every surface is lit on the side its normal faces, the references' included; its back gets no light");
      for (const auto& [extension, value] : material.extensions)
        if (!extension_read(extension)) note("material extension " + extension, "the base colour alone is the albedo");
    }
  }

  std::string name_stem() const { return fs::path(name_).stem().string(); }

  std::vector<int> roots() const {
    const int count = static_cast<int>(model_.nodes.size());
    const auto check_node = [&](int index, const std::string& where) {
      if (index < 0 || index >= count) fail(where + " names node " + std::to_string(index) + ", but there are " + std::to_string(count));
    };
    if (!model_.scenes.empty()) {
      const int chosen = model_.defaultScene >= 0 ? model_.defaultScene : 0;
      if (chosen >= static_cast<int>(model_.scenes.size())) fail("the default scene " + std::to_string(chosen) + " does not exist");
      for (int node : model_.scenes[static_cast<std::size_t>(chosen)].nodes) check_node(node, "scene " + std::to_string(chosen));
      return model_.scenes[static_cast<std::size_t>(chosen)].nodes;
    }
    std::vector<bool> is_child(model_.nodes.size(), false);
    for (const tinygltf::Node& node : model_.nodes)
      for (int child : node.children) {
        check_node(child, "node '" + excerpt(node.name) + "'");
        is_child[static_cast<std::size_t>(child)] = true;
      }
    std::vector<int> out;
    for (int i = 0; i < count; ++i)
      if (!is_child[static_cast<std::size_t>(i)]) out.push_back(i);
    return out;
  }

  glm::dmat4 local_transform(const tinygltf::Node& node, int index) const {
    const std::string where = "node " + std::to_string(index);
    for (double v : node.matrix)
      if (!std::isfinite(v)) fail(where + ": its matrix is not finite");
    if (node.matrix.size() == 16) return glm::make_mat4(node.matrix.data());
    if (!node.matrix.empty()) fail(where + ": a matrix needs 16 numbers, it has " + std::to_string(node.matrix.size()));
    glm::dmat4 m(1.0);
    if (!node.translation.empty()) {
      if (node.translation.size() != 3) fail(where + ": a translation needs 3 numbers");
      const glm::dvec3 t(node.translation[0], node.translation[1], node.translation[2]);
      if (!finite(t)) fail(where + ": its translation is not finite");
      m = glm::translate(m, t);
    }
    if (!node.rotation.empty()) {
      if (node.rotation.size() != 4) fail(where + ": a rotation needs 4 numbers");
      const glm::dquat q(node.rotation[3], node.rotation[0], node.rotation[1], node.rotation[2]);  // glTF: x, y, z, w
      const double length = glm::length(q);
      if (!std::isfinite(length) || length < 1e-6) fail(where + ": its rotation is not a finite, non-zero quaternion");
      m = m * glm::mat4_cast(q / length);
    }
    if (!node.scale.empty()) {
      if (node.scale.size() != 3) fail(where + ": a scale needs 3 numbers");
      const glm::dvec3 s(node.scale[0], node.scale[1], node.scale[2]);
      if (!finite(s)) fail(where + ": its scale is not finite");
      m = glm::scale(m, s);
    }
    return m;
  }

  // Depth first, children in their order (the first camera and light met are the same as a
  // recursive walk's), with an explicit stack: a chain of 20,000 nodes is as easy as a flat list.
  void walk(const std::vector<int>& roots) {
    struct pending {
      int index;
      glm::dmat4 parent;
    };
    std::vector<pending> stack;
    for (auto root = roots.rbegin(); root != roots.rend(); ++root) stack.push_back({*root, glm::dmat4(1.0)});
    while (!stack.empty()) {
      const pending next = stack.back();
      stack.pop_back();
      const int index = next.index;
      if (index < 0 || index >= static_cast<int>(model_.nodes.size())) fail("node " + std::to_string(index) + " does not exist");
      if (visited_[static_cast<std::size_t>(index)]) fail("node " + std::to_string(index) + " is reached twice (the node graph must be a tree)");
      visited_[static_cast<std::size_t>(index)] = true;
      const tinygltf::Node& node = model_.nodes[static_cast<std::size_t>(index)];
      const glm::dmat4 world = next.parent * local_transform(node, index);
      for (int k = 0; k < 4; ++k)
        if (!finite(glm::dvec3(world[k])) || !std::isfinite(world[k][3])) fail("node " + std::to_string(index) + ": its world transform is not finite");
      if (node.mesh >= 0) add_mesh(node.mesh, world);
      if (node.camera >= 0 && !camera_) read_camera(node.camera, world);
      if (!light_) {
        const auto found = node.extensions.find("KHR_lights_punctual");
        if (found != node.extensions.end() && found->second.Has("light")) read_light(found->second.Get("light").GetNumberAsInt(), world);
      }
      for (auto child = node.children.rbegin(); child != node.children.rend(); ++child) stack.push_back({*child, world});
    }
  }

  // The accessor's elements, `components` per element, after checking every byte it reads.
  accessor_view view_accessor(int index, int components, const std::string& what) const {
    if (index < 0 || index >= static_cast<int>(model_.accessors.size())) fail(what + ": accessor " + std::to_string(index) + " does not exist");
    const tinygltf::Accessor& accessor = model_.accessors[static_cast<std::size_t>(index)];
    const std::string where = what + " (accessor " + std::to_string(index) + ")";
    if (accessor.sparse.isSparse) fail(where + ": sparse accessors are not read");
    if (tinygltf::GetNumComponentsInType(static_cast<std::uint32_t>(accessor.type)) != components)
      fail(where + ": expected " + std::to_string(components) + " components per element");
    const int component_bytes = tinygltf::GetComponentSizeInBytes(static_cast<std::uint32_t>(accessor.componentType));
    if (component_bytes <= 0) fail(where + ": unknown component type " + std::to_string(accessor.componentType));
    if (accessor.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT && accessor.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT &&
        accessor.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT && accessor.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE)
      fail(where + ": component type " + std::to_string(accessor.componentType) + " is not read here");
    if (accessor.bufferView < 0 || accessor.bufferView >= static_cast<int>(model_.bufferViews.size()))
      fail(where + ": buffer view " + std::to_string(accessor.bufferView) + " does not exist");
    const tinygltf::BufferView& view = model_.bufferViews[static_cast<std::size_t>(accessor.bufferView)];
    if (view.buffer < 0 || view.buffer >= static_cast<int>(model_.buffers.size())) fail(where + ": buffer " + std::to_string(view.buffer) + " does not exist");
    const std::vector<unsigned char>& data = model_.buffers[static_cast<std::size_t>(view.buffer)].data;
    const std::uint64_t element_bytes = static_cast<std::uint64_t>(component_bytes) * static_cast<std::uint64_t>(components);
    const std::uint64_t stride = view.byteStride > 0 ? static_cast<std::uint64_t>(view.byteStride) : element_bytes;
    const std::uint64_t count = accessor.count;
    if (stride < element_bytes) fail(where + ": its stride is shorter than an element");
    const std::uint64_t view_begin = view.byteOffset, view_length = view.byteLength;
    if (view_begin > data.size() || view_length > data.size() - view_begin) fail(where + ": its buffer view lies outside buffer " + std::to_string(view.buffer));
    const std::uint64_t first = accessor.byteOffset;
    if (count > 0 && (first > view_length || (count - 1) > (view_length - first) / stride || (count - 1) * stride + element_bytes > view_length - first))
      fail(where + ": " + std::to_string(count) + " elements do not fit in its buffer view");
    return accessor_view(data.data() + view_begin + first, static_cast<std::size_t>(count), static_cast<std::size_t>(stride), accessor.componentType);
  }

  // A primitive's attribute: decoded from its Draco data when the extension names it there, else
  // its accessor in place.
  accessor_view attribute_view(const tinygltf::Primitive& primitive, const draco_mesh* compressed, const std::string& name, int components,
                               const std::string& what) const {
    if (compressed) {
      const auto found = compressed->attributes.find(name);
      if (found != compressed->attributes.end()) {
        if (found->second.components != components)
          fail(what + ": its Draco attribute has " + std::to_string(found->second.components) + " components, expected " + std::to_string(components));
        return accessor_view(reinterpret_cast<const unsigned char*>(found->second.values.data()), compressed->points,
                             static_cast<std::size_t>(components) * sizeof(float), TINYGLTF_COMPONENT_TYPE_FLOAT);
      }
    }
    return view_accessor(primitive.attributes.at(name), components, what);
  }

  // The decoded Draco data of mesh `mesh`'s primitive `which` (decoded once however often the
  // mesh is instanced), or null when the primitive is not compressed.
  const draco_mesh* draco_of(int mesh, std::size_t which, const std::string& what) {
    const tinygltf::Primitive& primitive = model_.meshes[static_cast<std::size_t>(mesh)].primitives[which];
    const auto extension = primitive.extensions.find("KHR_draco_mesh_compression");
    if (extension == primitive.extensions.end()) return nullptr;
    const auto key = std::make_pair(mesh, which);
    if (const auto found = draco_.find(key); found != draco_.end()) return &found->second;
    const std::string where = what + " KHR_draco_mesh_compression";
    const tinygltf::Value& value = extension->second;
    if (!value.IsObject() || !value.Has("bufferView") || !value.Get("bufferView").IsInt() || !value.Has("attributes") || !value.Get("attributes").IsObject())
      fail(where + ": needs an integer bufferView and an attributes object");
    const int view_index = value.Get("bufferView").GetNumberAsInt();
    if (view_index < 0 || view_index >= static_cast<int>(model_.bufferViews.size()))
      fail(where + ": buffer view " + std::to_string(view_index) + " does not exist");
    const tinygltf::BufferView& view = model_.bufferViews[static_cast<std::size_t>(view_index)];
    if (view.buffer < 0 || view.buffer >= static_cast<int>(model_.buffers.size())) fail(where + ": buffer " + std::to_string(view.buffer) + " does not exist");
    const std::vector<unsigned char>& data = model_.buffers[static_cast<std::size_t>(view.buffer)].data;
    if (view.byteOffset > data.size() || view.byteLength > data.size() - view.byteOffset) fail(where + ": its buffer view lies outside its buffer");
    std::map<std::string, int> ids;
    const tinygltf::Value& attributes = value.Get("attributes");
    for (const std::string& name : attributes.Keys()) {
      const tinygltf::Value& id = attributes.Get(name);
      if (!id.IsInt()) fail(where + ": attribute " + name + " needs an integer Draco id");
      // Only what the reader uses is converted.
      if (name == "POSITION" || name == "NORMAL" || name.rfind("TEXCOORD_", 0) == 0) ids[name] = id.GetNumberAsInt();
    }
    if (!ids.count("POSITION")) fail(where + ": POSITION is not among its attributes");
    const std::size_t left = limits_.max_triangles - std::min(limits_.max_triangles, geometry_.triangle_count());
    draco_mesh decoded = decode_draco_mesh(data.data() + view.byteOffset, view.byteLength, ids, left, name_ + ": " + where);
    return &draco_.emplace(key, std::move(decoded)).first->second;
  }

  glm::vec3 albedo_of(int material) const {
    if (material < 0) return glm::vec3(1.0f);
    if (material >= static_cast<int>(model_.materials.size())) fail("material " + std::to_string(material) + " does not exist");
    const std::vector<double>& factor = model_.materials[static_cast<std::size_t>(material)].pbrMetallicRoughness.baseColorFactor;
    if (factor.size() != 4) fail("material " + std::to_string(material) + ": baseColorFactor needs 4 numbers");
    const glm::dvec3 albedo(factor[0], factor[1], factor[2]);
    if (!finite(albedo) || glm::any(glm::lessThan(albedo, glm::dvec3(0.0))) || glm::any(glm::greaterThan(albedo, glm::dvec3(1.0))))
      fail("material " + std::to_string(material) + ": baseColorFactor must be in [0, 1]");
    return glm::vec3(albedo);
  }

  static constexpr int unread = -2;

  // A number of a JSON value, or fail.
  double number(const tinygltf::Value& value, const std::string& what) const {
    if (!value.IsNumber() || !std::isfinite(value.GetNumberAsDouble())) fail(what + " must be a finite number");
    return value.GetNumberAsDouble();
  }

  static texture_wrap wrap_of(int mode, bool& known) {
    known = true;
    if (mode == TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE) return texture_wrap::clamp_to_edge;
    if (mode == TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT) return texture_wrap::mirrored_repeat;
    known = mode == TINYGLTF_TEXTURE_WRAP_REPEAT;
    return texture_wrap::repeat;
  }

  texture_sampler sampler_of(int index) const {
    texture_sampler sampler;  // glTF leaves the filters to the renderer: linear, mipmapped
    if (index < 0) return sampler;
    if (index >= static_cast<int>(model_.samplers.size())) fail("sampler " + std::to_string(index) + " does not exist");
    const tinygltf::Sampler& source = model_.samplers[static_cast<std::size_t>(index)];
    const std::string where = "sampler " + std::to_string(index);
    bool known_s = false, known_t = false;
    sampler.wrap_s = wrap_of(source.wrapS, known_s);
    sampler.wrap_t = wrap_of(source.wrapT, known_t);
    if (!known_s || !known_t) fail(where + ": wrapS and wrapT must be 33071 (CLAMP_TO_EDGE), 33648 (MIRRORED_REPEAT) or 10497 (REPEAT)");
    if (source.magFilter == TINYGLTF_TEXTURE_FILTER_NEAREST) sampler.mag = texture_filter::nearest;
    else if (source.magFilter != TINYGLTF_TEXTURE_FILTER_LINEAR && source.magFilter != -1) fail(where + ": magFilter must be 9728 (NEAREST) or 9729 (LINEAR)");
    switch (source.minFilter) {
      case -1: break;
      case TINYGLTF_TEXTURE_FILTER_NEAREST: sampler.min = texture_filter::nearest; sampler.mipmaps = false; break;
      case TINYGLTF_TEXTURE_FILTER_LINEAR: sampler.mipmaps = false; break;
      case TINYGLTF_TEXTURE_FILTER_NEAREST_MIPMAP_NEAREST: sampler.min = sampler.between_levels = texture_filter::nearest; break;
      case TINYGLTF_TEXTURE_FILTER_LINEAR_MIPMAP_NEAREST: sampler.between_levels = texture_filter::nearest; break;
      case TINYGLTF_TEXTURE_FILTER_NEAREST_MIPMAP_LINEAR: sampler.min = texture_filter::nearest; break;
      case TINYGLTF_TEXTURE_FILTER_LINEAR_MIPMAP_LINEAR: break;
      default: fail(where + ": minFilter " + std::to_string(source.minFilter) + " is not a GL minification filter");
    }
    return sampler;
  }

  // The encoded bytes of image `index`: from its buffer view (bounds checked) or as tinygltf read
  // its URI; both stay in memory while the model is read (they are not copied).
  std::string_view bytes_of_image(int index, const std::string& what) const {
    const tinygltf::Image& image = model_.images[static_cast<std::size_t>(index)];
    if (image.bufferView >= 0) {
      if (image.bufferView >= static_cast<int>(model_.bufferViews.size())) fail(what + ": buffer view " + std::to_string(image.bufferView) + " does not exist");
      const tinygltf::BufferView& view = model_.bufferViews[static_cast<std::size_t>(image.bufferView)];
      if (view.buffer < 0 || view.buffer >= static_cast<int>(model_.buffers.size())) fail(what + ": buffer " + std::to_string(view.buffer) + " does not exist");
      const std::vector<unsigned char>& data = model_.buffers[static_cast<std::size_t>(view.buffer)].data;
      if (view.byteOffset > data.size() || view.byteLength > data.size() - view.byteOffset) fail(what + ": its buffer view lies outside its buffer");
      return std::string_view(reinterpret_cast<const char*>(data.data() + view.byteOffset), view.byteLength);
    }
    const auto found = images_.find(index);
    if (found == images_.end()) fail(what + ": its file '" + image.uri + "' could not be read (missing, not a regular file, or over the size limit)");
    return found->second;
  }

  // Image `index` decoded into the library, or fail naming it. Each distinct content is decoded
  // once: images that name one file (or carry the same bytes) share its texture, so a file named
  // by four images costs one decode and one budget share, not four.
  int texture_of(int index) {
    if (index < 0 || index >= static_cast<int>(model_.images.size())) fail("image " + std::to_string(index) + " does not exist");
    int& cached = texture_of_[static_cast<std::size_t>(index)];
    if (cached != unread) return cached;
    const tinygltf::Image& image = model_.images[static_cast<std::size_t>(index)];
    const std::string what = "image " + std::to_string(index) + (image.name.empty() ? "" : " '" + image.name + "'") + (image.uri.empty() || image.uri.rfind("data:", 0) == 0 ? "" : " (" + image.uri + ")");
    const std::string_view bytes = bytes_of_image(index, what);
    const auto [first, last] = texture_of_bytes_.equal_range(std::hash<std::string_view>{}(bytes));
    for (auto same = first; same != last; ++same)
      if (same->second.first == bytes) return cached = same->second.second;
    cached = texture_budget_.decode_into(library_, bytes, name_ + ": " + what, what, limits_.textures);
    texture_of_bytes_.emplace(std::hash<std::string_view>{}(bytes), std::make_pair(bytes, cached));
    return cached;
  }

  // What a primitive's material needs: the index of its surface_material (-1: plain, the factor
  // alone and opaque) and the TEXCOORD set its texture reads (-1: none).
  struct material_use {
    int material = -1;
    int texcoord_set = -1;
  };

  material_use material_for(int index) {
    if (index < 0) return {};
    int& cached = material_of_[static_cast<std::size_t>(index)];
    const tinygltf::Material& source = model_.materials[static_cast<std::size_t>(index)];
    const tinygltf::TextureInfo& base = source.pbrMetallicRoughness.baseColorTexture;
    // KHR_texture_transform may name another TEXCOORD set.
    int texcoord_set = base.texCoord;
    const auto transform = base.extensions.find("KHR_texture_transform");
    if (transform != base.extensions.end() && transform->second.IsObject() && transform->second.Has("texCoord"))
      texcoord_set = static_cast<int>(number(transform->second.Get("texCoord"), "material " + std::to_string(index) + " KHR_texture_transform texCoord"));
    if (cached != unread) return {cached, cached >= 0 && library_.materials[static_cast<std::size_t>(cached)].texture >= 0 ? texcoord_set : -1};
    const std::string where = "material " + std::to_string(index) + (source.name.empty() ? "" : " '" + source.name + "'");
    surface_material made;
    made.name = source.name;
    const std::vector<double>& factor = source.pbrMetallicRoughness.baseColorFactor;
    if (factor.size() == 4) {
      if (!(factor[3] >= 0.0 && factor[3] <= 1.0)) fail(where + ": baseColorFactor's alpha must be in [0, 1]");
      made.alpha_factor = static_cast<float>(factor[3]);
    }
    if (source.alphaMode == "MASK") {
      if (!(source.alphaCutoff >= 0.0 && std::isfinite(source.alphaCutoff))) fail(where + ": alphaCutoff must be a finite number >= 0");
      made.alpha_mask = true;
      made.alpha_cutoff = static_cast<float>(std::min(source.alphaCutoff, 1.0));
    } else if (source.alphaMode != "OPAQUE" && source.alphaMode != "BLEND") {
      fail(where + ": alphaMode must be OPAQUE, MASK or BLEND, not '" + source.alphaMode + "'");
    }
    if (base.index >= 0) {
      if (base.index >= static_cast<int>(model_.textures.size())) fail(where + ": baseColorTexture names texture " + std::to_string(base.index) + ", which does not exist");
      const tinygltf::Texture& texture = model_.textures[static_cast<std::size_t>(base.index)];
      if (texture.source < 0) {
        std::string in;
        for (const auto& [extension, value] : texture.extensions) in += (in.empty() ? "" : ", ") + extension;
        note("texture images given only by " + (in.empty() ? std::string("no source") : in), "those textures are left out: their factor alone is the albedo");
      } else if (texcoord_set < 0 || texcoord_set > 7) {
        fail(where + ": baseColorTexture's texCoord must be in [0, 7]");
      } else {
        made.texture = texture_of(texture.source);
        made.sampler = sampler_of(texture.sampler);
      }
      if (transform != base.extensions.end() && transform->second.IsObject()) {
        const tinygltf::Value& t = transform->second;
        const std::string in = where + " KHR_texture_transform";
        glm::dvec2 offset(0.0), scale(1.0);
        double rotation = 0.0;
        for (const auto& [key, target] : {std::pair<const char*, glm::dvec2*>{"offset", &offset}, {"scale", &scale}}) {
          if (!t.Has(key)) continue;
          const tinygltf::Value& pair = t.Get(key);
          if (!pair.IsArray() || pair.ArrayLen() != 2) fail(in + ": " + key + " needs 2 numbers");
          *target = glm::dvec2(number(pair.Get(0), in + " " + key), number(pair.Get(1), in + " " + key));
        }
        if (t.Has("rotation")) rotation = number(t.Get("rotation"), in + " rotation");
        // The extension's matrix: translation x rotation x scale, the rotation counter-clockwise
        // in the image (v points down): [cos sin; -sin cos].
        const double c = std::cos(rotation), s = std::sin(rotation);
        const glm::dmat2 rotate(glm::dvec2(c, -s), glm::dvec2(s, c));  // columns
        const glm::dmat2 matrix = rotate * glm::dmat2(glm::dvec2(scale.x, 0.0), glm::dvec2(0.0, scale.y));
        made.texture_matrix = glm::mat2(matrix);
        made.texture_offset = glm::vec2(offset);
        if (!std::isfinite(made.texture_matrix[0][0] + made.texture_matrix[0][1] + made.texture_matrix[1][0] + made.texture_matrix[1][1]) ||
            !std::isfinite(made.texture_offset.x + made.texture_offset.y))
          fail(in + ": the transform is not finite as floats");
      }
    }
    if (made.texture < 0 && !made.alpha_mask) {
      cached = -1;  // plain: the factor alone, opaque
      return {};
    }
    library_.materials.push_back(std::move(made));
    cached = static_cast<int>(library_.materials.size() - 1);
    return {cached, library_.materials.back().texture >= 0 ? texcoord_set : -1};
  }

  // TEXCOORD_<set> of a primitive where it lies in its buffer (normalized unsigned bytes and shorts
  // scaled to [0, 1], as the spec allows), or an empty view when the primitive has none.
  struct texcoord_view {
    accessor_view values;
    double scale = 1.0;
    std::string where;
    bool empty() const { return values.count() == 0; }
  };
  texcoord_view texture_coordinates(const tinygltf::Primitive& primitive, const draco_mesh* compressed, int set, std::size_t vertex_count,
                                    const std::string& what) const {
    const std::string name = "TEXCOORD_" + std::to_string(set);
    const auto found = primitive.attributes.find(name);
    if (found == primitive.attributes.end()) return {};
    texcoord_view out;
    out.where = what + " " + name;
    if (compressed && compressed->attributes.count(name)) {
      // Decoded to floats, normalized integers already scaled by libdraco.
      out.values = attribute_view(primitive, compressed, name, 2, out.where);
      if (out.values.count() != vertex_count) fail(out.where + " and POSITION differ in count");
      return out;
    }
    if (found->second >= 0 && found->second < static_cast<int>(model_.accessors.size())) {
      const tinygltf::Accessor& accessor = model_.accessors[static_cast<std::size_t>(found->second)];
      if (accessor.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE && accessor.normalized) out.scale = 1.0 / 255.0;
      else if (accessor.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT && accessor.normalized) out.scale = 1.0 / 65535.0;
      else if (accessor.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT) fail(out.where + ": must be float, or normalized unsigned bytes or shorts");
    }
    out.values = view_accessor(found->second, 2, out.where);
    if (out.values.count() != vertex_count) fail(out.where + " and POSITION differ in count");
    return out;
  }

  // Vertex i's texture coordinate, checked as it is read.
  glm::vec2 texture_coordinate(const texcoord_view& texcoords, std::uint32_t i) const {
    if (texcoords.empty()) return glm::vec2(0.0f);
    const glm::dvec2 uv(texcoords.values.get(i, 0) * texcoords.scale, texcoords.values.get(i, 1) * texcoords.scale);
    if (!std::isfinite(uv.x) || !std::isfinite(uv.y) || std::fabs(uv.x) > 1e6 || std::fabs(uv.y) > 1e6)
      fail(texcoords.where + ": a coordinate is not finite or beyond 1e6");
    return glm::vec2(uv);
  }

  void add_mesh(int index, const glm::dmat4& world) {
    if (index >= static_cast<int>(model_.meshes.size())) fail("mesh " + std::to_string(index) + " does not exist");
    const glm::dmat3 normal_matrix = glm::transpose(glm::inverse(glm::dmat3(world)));
    const bool mirrored = glm::determinant(glm::dmat3(world)) < 0.0;
    const tinygltf::Mesh& source = model_.meshes[static_cast<std::size_t>(index)];
    for (std::size_t which = 0; which < source.primitives.size(); ++which) {
      const tinygltf::Primitive& primitive = source.primitives[which];
      if (!has_triangles(primitive)) continue;  // points and lines: nothing to shade
      const std::string what = "mesh " + std::to_string(index) + " primitive " + std::to_string(which);
      const auto position = primitive.attributes.find("POSITION");
      if (position == primitive.attributes.end()) fail(what + ": no POSITION");
      const draco_mesh* compressed = draco_of(index, which, what);
      if (!compressed && model_.accessors.size() > static_cast<std::size_t>(position->second) && position->second >= 0 &&
          model_.accessors[static_cast<std::size_t>(position->second)].componentType != TINYGLTF_COMPONENT_TYPE_FLOAT)
        fail(what + ": POSITION must be float (quantized positions are not read)");
      const accessor_view positions = attribute_view(primitive, compressed, "POSITION", 3, what + " POSITION");
      const std::size_t vertex_count = positions.count();
      accessor_view normals;
      bool has_normals = false;
      if (const auto normal = primitive.attributes.find("NORMAL"); normal != primitive.attributes.end()) {
        if (!(compressed && compressed->attributes.count("NORMAL")) && normal->second >= 0 && normal->second < static_cast<int>(model_.accessors.size()) &&
            model_.accessors[static_cast<std::size_t>(normal->second)].componentType != TINYGLTF_COMPONENT_TYPE_FLOAT)
          fail(what + ": NORMAL must be float (quantized normals are not read)");
        normals = attribute_view(primitive, compressed, "NORMAL", 3, what + " NORMAL");
        if (normals.count() != vertex_count) fail(what + ": NORMAL and POSITION differ in count");
        has_normals = true;
      }
      // A Draco primitive's triangles are its decoded faces (a triangle list, whatever the mode).
      const int mode = compressed ? TINYGLTF_MODE_TRIANGLES : primitive.mode;
      const bool indexed = compressed || primitive.indices >= 0;
      accessor_view indices;
      if (compressed) {
        indices = accessor_view(reinterpret_cast<const unsigned char*>(compressed->indices.data()), compressed->indices.size(), 4,
                                TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT);
      } else if (primitive.indices >= 0) {
        if (primitive.indices < static_cast<int>(model_.accessors.size()) &&
            model_.accessors[static_cast<std::size_t>(primitive.indices)].componentType == TINYGLTF_COMPONENT_TYPE_FLOAT)
          fail(what + ": indices must be unsigned integers, not floats");
        indices = view_accessor(primitive.indices, 1, what + " indices");
      }
      const std::size_t corner_count = indexed ? indices.count() : vertex_count;
      // Sizes first: nothing is allocated for a primitive the limits refuse.
      if ((mode == TINYGLTF_MODE_TRIANGLES || mode == -1) && corner_count % 3 != 0)
        fail(what + ": " + std::to_string(corner_count) + " corners is not a whole number of triangles");
      const std::size_t triangle_count = triangles_in(mode, corner_count);
      if (geometry_.triangle_count() + triangle_count > limits_.max_triangles)
        fail("more than " + std::to_string(limits_.max_triangles) + " triangles");
      if (vertex_count > std::size_t{0xfffffffe}) fail(what + ": " + std::to_string(vertex_count) + " vertices is too many");
      const auto corner = [&](std::size_t k) -> std::uint32_t {
        if (!indexed) return static_cast<std::uint32_t>(k);
        const double v = indices.get(k, 0);
        if (v >= static_cast<double>(vertex_count))
          fail(what + ": index " + std::to_string(static_cast<std::uint64_t>(v)) + " is beyond its " + std::to_string(vertex_count) + " vertices");
        return static_cast<std::uint32_t>(v);
      };
      const glm::vec3 albedo = albedo_of(primitive.material);
      const material_use use = material_for(primitive.material);
      texcoord_view texcoords;
      if (use.texcoord_set >= 0) {
        texcoords = texture_coordinates(primitive, compressed, use.texcoord_set, vertex_count, what);
        if (texcoords.empty())
          note("base colour textures on primitives without their TEXCOORD set", "those primitives take their material's factor alone");
      }
      if (primitive.attributes.count("COLOR_0")) note("COLOR_0 (vertex colours)", "the material's colour is the albedo");
      if (!primitive.targets.empty()) note("morph targets", "meshes are drawn undeformed");
      const std::size_t first_index = geometry_.indices.size();
      const auto world_position = [&](std::uint32_t i) {
        const glm::dvec3 p = glm::dvec3(world * glm::dvec4(positions.vec3(i), 1.0));
        if (!finite(p) || glm::any(glm::greaterThan(glm::abs(p), glm::dvec3(max_mesh_coordinate))))
          fail(what + ": vertex " + std::to_string(i) + " is not finite or beyond " + std::to_string(max_mesh_coordinate) + " in the world");
        return p;
      };
      // The vertex's own normal in the world, or nothing when it has none or a degenerate one.
      const auto world_normal = [&](std::uint32_t i) -> std::optional<glm::dvec3> {
        if (!has_normals) return std::nullopt;
        const glm::dvec3 turned = normal_matrix * normals.vec3(i);
        const double length = glm::length(turned);
        if (std::isfinite(length) && length > 1e-12) return turned / length;
        return std::nullopt;
      };
      // A vertex with its own normal is shared by every triangle that uses it (the mesh stays
      // indexed); without one it takes its triangle's flat normal, as the glTF spec asks, and
      // so needs a copy per triangle.
      vertex_map shared(has_normals ? vertex_count : 0, 3 * triangle_count);
      geometry_.indices.reserve(geometry_.indices.size() + 3 * triangle_count);
      for (std::size_t t = 0; t < triangle_count; ++t) {
        const std::array<std::size_t, 3> k = triangle_corners(mode, t);
        std::uint32_t a = corner(k[0]), b = corner(k[1]), c = corner(k[2]);
        if (mirrored) std::swap(b, c);
        const glm::dvec3 pa = world_position(a), pb = world_position(b), pc = world_position(c);
        const glm::dvec3 face = glm::cross(pb - pa, pc - pa);
        const double face_length = glm::length(face);
        const glm::dvec3 flat = face_length > 0.0 ? face / face_length : glm::dvec3(0, 1, 0);
        for (const auto& [i, p] : {std::pair{a, pa}, std::pair{b, pb}, std::pair{c, pc}}) {
          const std::optional<glm::dvec3> own = world_normal(i);
          if (own) {
            if (const std::uint32_t found = shared.find(i); found != vertex_map::none) {
              geometry_.indices.push_back(found);
              continue;
            }
          }
          if (geometry_.vertices.size() >= std::size_t{0xffffffffu}) fail("more than 2^32 vertices");
          const auto added = static_cast<std::uint32_t>(geometry_.vertices.size());
          geometry_.vertices.push_back({glm::vec3(p), glm::vec3(own ? *own : flat), albedo, texture_coordinate(texcoords, i)});
          geometry_.indices.push_back(added);
          if (own) shared.insert(i, added);
        }
      }
      // A range for the primitive's triangles when its material is more than a factor (one range
      // with the previous when they are adjacent and share the material).
      const auto count = static_cast<std::uint32_t>(geometry_.indices.size() - first_index);
      const bool untextured = use.texcoord_set >= 0 && texcoords.empty();
      if (use.material >= 0 && count > 0 && !(untextured && !library_.materials[static_cast<std::size_t>(use.material)].alpha_mask)) {
        std::uint32_t material = static_cast<std::uint32_t>(use.material);
        if (untextured) {
          // Alpha-tested without coordinates: the same material without its texture.
          surface_material plain = library_.materials[material];
          plain.texture = -1;
          library_.materials.push_back(plain);
          material = static_cast<std::uint32_t>(library_.materials.size() - 1);
        }
        std::vector<material_range>& ranges = geometry_.material_ranges;
        if (!ranges.empty() && ranges.back().material == material && ranges.back().first_index + ranges.back().index_count == first_index)
          ranges.back().index_count += count;
        else
          ranges.push_back({static_cast<std::uint32_t>(first_index), count, material});
      }
    }
    if (std::any_of(source.primitives.begin(), source.primitives.end(), [](const tinygltf::Primitive& primitive) { return !has_triangles(primitive); }))
      note("points and lines", "only triangles, strips and fans are drawn");
  }

  static glm::dvec3 axis(const glm::dmat4& world, const glm::dvec3& local) { return glm::normalize(glm::dmat3(world) * local); }

  void read_camera(int index, const glm::dmat4& world) {
    if (index >= static_cast<int>(model_.cameras.size())) fail("camera " + std::to_string(index) + " does not exist");
    const tinygltf::Camera& source = model_.cameras[static_cast<std::size_t>(index)];
    if (source.type != "perspective") return;  // orthographic: not read
    const tinygltf::PerspectiveCamera& p = source.perspective;
    if (!(p.yfov > 0.0 && p.yfov < 3.1) || !(p.znear > 0.0) || !(p.zfar == 0.0 || p.zfar > p.znear))
      fail("camera " + std::to_string(index) + ": needs 0 < yfov < pi and 0 < znear < zfar");
    camera view;
    const glm::dvec3 position(world[3]), forward = axis(world, {0, 0, -1}), up = axis(world, {0, 1, 0});
    if (!finite(forward) || !finite(up)) fail("camera " + std::to_string(index) + ": its node's transform is degenerate");
    view.position = glm::vec3(position);
    view.target = glm::vec3(position + forward);
    view.up = glm::vec3(up);
    view.vertical_fov_degrees = static_cast<float>(glm::degrees(p.yfov));
    view.near_plane = static_cast<float>(p.znear);
    view.far_plane = static_cast<float>(p.zfar > 0.0 ? p.zfar : 1000.0 * p.znear);
    camera_ = view;
  }

  void read_light(int index, const glm::dmat4& world) {
    if (index < 0 || index >= static_cast<int>(model_.lights.size())) fail("light " + std::to_string(index) + " does not exist");
    const tinygltf::Light& source = model_.lights[static_cast<std::size_t>(index)];
    const std::string where = "light " + std::to_string(index);
    glm::dvec3 colour(1.0);
    if (!source.color.empty()) {
      if (source.color.size() != 3) fail(where + ": color needs 3 numbers");
      colour = glm::dvec3(source.color[0], source.color[1], source.color[2]);
    }
    const glm::dvec3 power = colour * source.intensity;
    if (!finite(power) || glm::any(glm::lessThan(power, glm::dvec3(0.0))) || glm::any(glm::greaterThan(power, glm::dvec3(max_light_power))))
      fail(where + ": intensity x color must be in [0, " + number_text(max_light_power) + "] (intensity " + number_text(source.intensity) + ")");
    const glm::dvec3 direction = axis(world, {0, 0, -1});
    if (!finite(direction)) fail(where + ": its node's transform is degenerate");
    scene_light light;
    if (source.type == "spot") {
      const double inner = source.spot.innerConeAngle, outer = source.spot.outerConeAngle;
      if (!(inner >= 0.0 && inner < outer && outer <= 1.5707963267948966)) fail(where + ": needs 0 <= innerConeAngle < outerConeAngle <= pi/2");
      light.kind = light_kind::spot;
      light.spot.position = glm::vec3(glm::dvec3(world[3]));
      light.spot.direction = glm::vec3(direction);
      light.spot.intensity = glm::vec3(power);
      light.spot.cos_inner = static_cast<float>(std::cos(inner));
      light.spot.cos_outer = static_cast<float>(std::cos(outer));
      if (const setting_problem problem = validate(light.spot)) fail(where + ": " + problem.message());
    } else if (source.type == "directional") {
      light.kind = light_kind::directional;
      light.directional.direction = glm::vec3(direction);
      light.directional.irradiance = glm::vec3(power);
      if (const setting_problem problem = validate(light.directional)) fail(where + ": " + problem.message());
    } else {
      return;  // point lights: not read
    }
    light_ = light;
  }

  const tinygltf::Model& model_;
  std::string name_;
  gltf_limits limits_;
  const image_bytes& images_;
  std::vector<bool> visited_;
  mesh geometry_;
  material_library library_;
  std::vector<int> material_of_;  ///< glTF material -> library material (-1 plain, unread not yet)
  std::vector<int> texture_of_;   ///< glTF image -> library texture
  std::map<std::pair<int, std::size_t>, draco_mesh> draco_;  ///< (mesh, primitive) -> its decoded Draco data
  /// Decoded images by the hash of their bytes: (the bytes, the library texture).
  std::unordered_multimap<std::size_t, std::pair<std::string_view, int>> texture_of_bytes_;
  texture_budget texture_budget_{limits_.textures.max_scene_bytes, "gltf_limits::textures.max_scene_bytes"};
  std::vector<std::string> noted_, notes_;
  std::optional<camera> camera_;
  std::optional<scene_light> light_;
};

}  // namespace

scene parse_gltf(const std::string& original, bool binary, const std::string& name, const fs::path& base_dir, const gltf_limits& limits) {
  if (original.size() > std::numeric_limits<unsigned int>::max()) throw error(name + ": larger than 4 GiB");
  const std::string_view json = binary ? glb_json(original) : std::string_view(original);
  check_json_depth(json, name, limits.max_json_depth);
  if (binary && original.size() >= 8 && original.compare(4, 4, std::string("\1\0\0\0", 4)) == 0) refuse_gltf_1("1", "GLB container version 1", name);
  // KHR_draco_mesh_compression: the compressed primitives' indices out of tinygltf's sight.
  std::string edited = without_draco_indices(json);
  if (!edited.empty() && binary) {
    // The same GLB with the edited JSON chunk (padded with spaces to 4 bytes, as GLB asks).
    while (edited.size() % 4 != 0) edited += ' ';
    const std::size_t after_json = 20 + json.size();
    std::string glb = original.substr(0, 12);
    const auto put_word = [&](std::uint32_t value) { glb.append(reinterpret_cast<const char*>(&value), 4); };
    put_word(static_cast<std::uint32_t>(edited.size()));
    put_word(0x4E4F534Au);  // "JSON"
    glb += edited;
    glb.append(original, after_json, std::string::npos);
    const auto total = static_cast<std::uint32_t>(glb.size());
    std::memcpy(glb.data() + 8, &total, 4);
    edited = std::move(glb);
  }
  const std::string& bytes = edited.empty() ? original : edited;
  file_access access;
  access.base_dir = base_dir.empty() ? std::string() : base_dir.string();
  access.max_bytes = limits.max_external_bytes;
  tinygltf::TinyGLTF loader;
  loader.SetFsCallbacks({&file_exists, &expand_file_path, &read_whole_file, &write_whole_file, &access});
  image_bytes images;
  loader.SetImageLoader(&keep_image_bytes, &images);
  tinygltf::Model model;
  std::string err, warn;
  bool loaded = false;
  try {
    loaded = binary ? loader.LoadBinaryFromMemory(&model, &err, &warn, reinterpret_cast<const unsigned char*>(bytes.data()),
                                                  static_cast<unsigned int>(bytes.size()), access.base_dir)
                    : loader.LoadASCIIFromString(&model, &err, &warn, bytes.data(), static_cast<unsigned int>(bytes.size()), access.base_dir);
  } catch (const std::exception& failure) {
    // tinygltf indexes an empty decoded data URI with at(0).
    err += failure.what();
  }
  if (!access.refusal.empty()) {
    // A refused external file: our reason, not tinygltf's wrapping of it. (An image tinygltf
    // could not read is only a warning to it, and a refused one must still fail the load.)
    throw error(name + ": " + access.refusal);
  }
  if (!loaded) {
    // tinygltf's messages echo the input (a 16 MiB data URI, a long path): each line cut short.
    std::string reason;
    std::istringstream lines(err);
    for (std::string line; std::getline(lines, line);)
      if (!line.empty()) reason += (reason.empty() ? "" : "; ") + excerpt(line);
    // A glTF 1.0 file fails here or below (its schema is not 2.0's); named as such.
    const std::string declared = declared_gltf_version(json);
    refuse_gltf_1(declared, "asset.version " + excerpt(declared), name);
    throw error(name + ": not a readable glTF 2.0 file (" + (reason.empty() ? std::string("no reason given") : excerpt(reason, 4 * max_echoed_characters)) + ")");
  }
  if (model.asset.version.empty() || model.asset.version[0] != '2') {
    const std::string declared = declared_gltf_version(json);
    refuse_gltf_1(declared, "asset.version " + excerpt(declared), name);
  }
  return reader(model, name, limits, images).read();
}

scene load_gltf(const fs::path& path, const gltf_limits& limits) {
  const std::string extension = path.extension().string();
  if (extension != ".gltf" && extension != ".glb") throw error(excerpt_path(path.string()) + ": a glTF file ends in .gltf or .glb");
  const std::string bytes = read_file(path, limits.max_file_bytes, "glTF file");
  fs::path folder = path.parent_path();
  if (folder.empty()) folder = ".";
  return parse_gltf(bytes, extension == ".glb", excerpt_path(path.string()), folder, limits);
}

std::string gltf_text(const scene& source) {
  check_scene(source);
  if (!source.geometry.material_ranges.empty())
    throw error("scene " + source.name + ": textured and alpha-tested materials are not written as glTF (only colour factors are)");
  tinygltf::Model model;
  model.asset.version = "2.0";
  model.asset.generator = "vplkit export-scene";
  // One primitive per albedo, in the order the albedos first appear.
  std::vector<glm::vec3> albedos;
  std::vector<std::vector<std::uint32_t>> triangles_of;
  for (std::size_t t = 0; t < source.geometry.indices.size(); t += 3) {
    const glm::vec3 albedo = source.geometry.vertices[source.geometry.indices[t]].albedo;
    const auto found = std::find(albedos.begin(), albedos.end(), albedo);
    const std::size_t group = static_cast<std::size_t>(found - albedos.begin());
    if (found == albedos.end()) {
      albedos.push_back(albedo);
      triangles_of.emplace_back();
    }
    triangles_of[group].insert(triangles_of[group].end(), source.geometry.indices.begin() + static_cast<std::ptrdiff_t>(t),
                               source.geometry.indices.begin() + static_cast<std::ptrdiff_t>(t + 3));
  }
  tinygltf::Buffer buffer;
  const auto append = [&](const void* data, std::size_t bytes, int target) {
    tinygltf::BufferView view;
    view.buffer = 0;
    view.byteOffset = buffer.data.size();
    view.byteLength = bytes;
    view.target = target;
    const auto* begin = static_cast<const unsigned char*>(data);
    buffer.data.insert(buffer.data.end(), begin, begin + bytes);
    while (buffer.data.size() % 4 != 0) buffer.data.push_back(0);
    model.bufferViews.push_back(view);
    return static_cast<int>(model.bufferViews.size() - 1);
  };
  const auto add_accessor = [&](int view, int component_type, int type, std::size_t count) {
    tinygltf::Accessor accessor;
    accessor.bufferView = view;
    accessor.componentType = component_type;
    accessor.type = type;
    accessor.count = count;
    model.accessors.push_back(accessor);
    return static_cast<int>(model.accessors.size() - 1);
  };
  tinygltf::Mesh out_mesh;
  out_mesh.name = source.name;
  for (std::size_t g = 0; g < albedos.size(); ++g) {
    // The group's vertices, renumbered.
    std::map<std::uint32_t, std::uint32_t> renumber;
    std::vector<float> positions, normals;
    std::vector<std::uint32_t> indices;
    glm::vec3 low(std::numeric_limits<float>::max()), high(-std::numeric_limits<float>::max());
    for (std::uint32_t i : triangles_of[g]) {
      auto [at, inserted] = renumber.try_emplace(i, static_cast<std::uint32_t>(positions.size() / 3));
      if (inserted) {
        const vertex& v = source.geometry.vertices[i];
        positions.insert(positions.end(), {v.position.x, v.position.y, v.position.z});
        normals.insert(normals.end(), {v.normal.x, v.normal.y, v.normal.z});
        low = glm::min(low, v.position);
        high = glm::max(high, v.position);
      }
      indices.push_back(at->second);
    }
    tinygltf::Primitive primitive;
    primitive.mode = TINYGLTF_MODE_TRIANGLES;
    const std::size_t count = positions.size() / 3;
    const int position_accessor = add_accessor(append(positions.data(), positions.size() * 4, TINYGLTF_TARGET_ARRAY_BUFFER),
                                               TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, count);
    model.accessors[static_cast<std::size_t>(position_accessor)].minValues = {low.x, low.y, low.z};  // required for POSITION
    model.accessors[static_cast<std::size_t>(position_accessor)].maxValues = {high.x, high.y, high.z};
    primitive.attributes["POSITION"] = position_accessor;
    primitive.attributes["NORMAL"] = add_accessor(append(normals.data(), normals.size() * 4, TINYGLTF_TARGET_ARRAY_BUFFER),
                                                  TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, count);
    primitive.indices = add_accessor(append(indices.data(), indices.size() * 4, TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER),
                                     TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT, TINYGLTF_TYPE_SCALAR, indices.size());
    tinygltf::Material material;
    material.name = "albedo " + std::to_string(g);
    material.pbrMetallicRoughness.baseColorFactor = {albedos[g].r, albedos[g].g, albedos[g].b, 1.0};
    material.pbrMetallicRoughness.metallicFactor = 0.0;
    material.pbrMetallicRoughness.roughnessFactor = 1.0;
    model.materials.push_back(material);
    primitive.material = static_cast<int>(g);
    out_mesh.primitives.push_back(primitive);
  }
  model.buffers.push_back(buffer);
  model.meshes.push_back(out_mesh);

  // A node looking down -Z with +Y up: the rotation whose columns are right, up and back.
  const auto pose = [](tinygltf::Node& node, const glm::vec3& position, const glm::vec3& forward, const glm::vec3& up_hint) {
    const glm::dvec3 back = -glm::normalize(glm::dvec3(forward));
    glm::dvec3 right = glm::cross(glm::dvec3(up_hint), back);
    if (glm::length(right) < 1e-9) right = glm::cross(std::abs(back.y) < 0.9 ? glm::dvec3(0, 1, 0) : glm::dvec3(1, 0, 0), back);
    right = glm::normalize(right);
    const glm::dvec3 up = glm::cross(back, right);
    const glm::dquat q = glm::quat_cast(glm::dmat3(right, up, back));
    node.translation = {position.x, position.y, position.z};
    node.rotation = {q.x, q.y, q.z, q.w};
  };
  tinygltf::Node mesh_node;
  mesh_node.name = source.name;
  mesh_node.mesh = 0;
  model.nodes.push_back(mesh_node);

  tinygltf::Camera out_camera;
  out_camera.type = "perspective";
  out_camera.perspective.yfov = glm::radians(static_cast<double>(source.view.vertical_fov_degrees));
  out_camera.perspective.znear = source.view.near_plane;
  out_camera.perspective.zfar = source.view.far_plane;
  model.cameras.push_back(out_camera);
  tinygltf::Node camera_node;
  camera_node.name = "camera";
  camera_node.camera = 0;
  pose(camera_node, source.view.position, source.view.target - source.view.position, source.view.up);
  model.nodes.push_back(camera_node);

  // glTF splits a light's power into an intensity and a colour: the brightest channel and the
  // colour relative to it (read back as intensity x color).
  const auto set_power = [](tinygltf::Light& light, const glm::vec3& power) {
    const float peak = std::max({power.r, power.g, power.b});
    light.intensity = peak;
    light.color = peak > 0.0f ? std::vector<double>{power.r / peak, power.g / peak, power.b / peak} : std::vector<double>{1.0, 1.0, 1.0};
  };
  tinygltf::Light out_light;
  tinygltf::Node light_node;
  light_node.name = "light";
  if (source.light.kind == light_kind::spot) {
    const spot_light<float>& spot = source.light.spot;
    out_light.type = "spot";
    set_power(out_light, spot.intensity);
    out_light.spot.innerConeAngle = std::acos(static_cast<double>(spot.cos_inner));
    out_light.spot.outerConeAngle = std::acos(static_cast<double>(spot.cos_outer));
    pose(light_node, spot.position, spot.direction, glm::vec3(0, 1, 0));
  } else {
    const directional_light<float>& sun = source.light.directional;
    out_light.type = "directional";
    set_power(out_light, sun.irradiance);
    pose(light_node, glm::vec3(0.0f), sun.direction, glm::vec3(0, 1, 0));
  }
  model.lights.push_back(out_light);
  tinygltf::Value::Object reference;
  reference["light"] = tinygltf::Value(0);
  light_node.extensions["KHR_lights_punctual"] = tinygltf::Value(reference);
  model.nodes.push_back(light_node);

  tinygltf::Scene out_scene;
  out_scene.name = source.name;
  out_scene.nodes = {0, 1, 2};
  model.scenes.push_back(out_scene);
  model.defaultScene = 0;

  tinygltf::TinyGLTF writer;
  std::ostringstream text;
  if (!writer.WriteGltfSceneToStream(&model, text, true, false)) throw error("scene " + source.name + ": tinygltf could not write it as glTF");
  return text.str();
}

}  // namespace vplkit
