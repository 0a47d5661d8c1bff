#include "frontend/scene/gltf_scene.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <functional>
#include <limits>
#include <map>
#include <optional>
#include <sstream>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>

#include <tiny_gltf.h>

#include "frontend/core/error.hpp"
#include "frontend/core/files.hpp"

namespace fs = std::filesystem;

namespace vplkit {
namespace {

// tinygltf's file access, bounded: only regular files in the glTF's folder tree, at most
// max_file_bytes each, nothing written. Without a folder (parse_gltf from memory) nothing is read.
struct file_access {
  fs::path base_dir;
  std::uintmax_t max_bytes;
};

bool file_exists(const std::string& path, void* user) {
  const auto* access = static_cast<const file_access*>(user);
  if (access->base_dir.empty()) return true;  // read_whole_file then says why it is refused
  std::error_code ignored;
  return fs::is_regular_file(path, ignored);
}

std::string expand_file_path(const std::string& path, void*) { return path; }

bool read_whole_file(std::vector<unsigned char>* out, std::string* err, const std::string& path, void* user) {
  const auto* access = static_cast<const file_access*>(user);
  if (access->base_dir.empty()) {
    if (err) *err += "external file '" + path + "' refused: the glTF was given from memory";
    return false;
  }
  try {
    const std::string bytes = read_file(path, access->max_bytes, "glTF buffer");
    out->assign(bytes.begin(), bytes.end());
    return true;
  } catch (const error& failure) {
    if (err) *err += failure.what();
    return false;
  }
}

bool write_whole_file(std::string* err, const std::string&, const std::vector<unsigned char>&, void*) {
  if (err) *err += "vplkit does not write files while reading a glTF";
  return false;
}

// Images are not used (base colour textures are not sampled): accept them undecoded.
bool skip_image(tinygltf::Image*, const int, std::string*, std::string*, int, int, const unsigned char*, int, void*) { return true; }

bool finite(const glm::dvec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

class reader {
 public:
  reader(const tinygltf::Model& model, const std::string& name, const gltf_limits& limits) : model_(model), name_(name), limits_(limits) {}

  scene read() {
    visited_.assign(model_.nodes.size(), false);
    for (int root : roots()) visit(root, glm::dmat4(1.0));
    if (geometry_.indices.empty()) fail("no triangles in its scene (only TRIANGLES primitives are read; points, lines, strips and fans are not)");
    scene framed = frame_mesh(name_stem(), geometry_);
    if (light_) {
      framed.geometry = geometry_;  // its own light: no floor added
      framed.light = *light_;
    }
    if (camera_) framed.view = *camera_;
    framed.name = name_stem();
    return framed;
  }

 private:
  [[noreturn]] void fail(const std::string& what) const { throw error(name_ + ": " + what); }

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
        check_node(child, "node '" + node.name + "'");
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

  void visit(int index, const glm::dmat4& parent) {
    if (index < 0 || index >= static_cast<int>(model_.nodes.size())) fail("node " + std::to_string(index) + " does not exist");
    if (visited_[static_cast<std::size_t>(index)]) fail("node " + std::to_string(index) + " is reached twice (the node graph must be a tree)");
    visited_[static_cast<std::size_t>(index)] = true;
    const tinygltf::Node& node = model_.nodes[static_cast<std::size_t>(index)];
    const glm::dmat4 world = parent * local_transform(node, index);
    for (int k = 0; k < 4; ++k)
      if (!finite(glm::dvec3(world[k])) || !std::isfinite(world[k][3])) fail("node " + std::to_string(index) + ": its world transform is not finite");
    if (node.mesh >= 0) add_mesh(node.mesh, world);
    if (node.camera >= 0 && !camera_) read_camera(node.camera, world);
    if (!light_) {
      const auto found = node.extensions.find("KHR_lights_punctual");
      if (found != node.extensions.end() && found->second.Has("light")) read_light(found->second.Get("light").GetNumberAsInt(), world);
    }
    for (int child : node.children) visit(child, world);
  }

  // The accessor's elements as doubles, `components` per element, after checking every byte it reads.
  std::vector<double> read_accessor(int index, int components, const std::string& what) const {
    if (index < 0 || index >= static_cast<int>(model_.accessors.size())) fail(what + ": accessor " + std::to_string(index) + " does not exist");
    const tinygltf::Accessor& accessor = model_.accessors[static_cast<std::size_t>(index)];
    const std::string where = what + " (accessor " + std::to_string(index) + ")";
    if (accessor.sparse.isSparse) fail(where + ": sparse accessors are not read");
    if (tinygltf::GetNumComponentsInType(static_cast<std::uint32_t>(accessor.type)) != components)
      fail(where + ": expected " + std::to_string(components) + " components per element");
    const int component_bytes = tinygltf::GetComponentSizeInBytes(static_cast<std::uint32_t>(accessor.componentType));
    if (component_bytes <= 0) fail(where + ": unknown component type " + std::to_string(accessor.componentType));
    if (accessor.bufferView < 0 || accessor.bufferView >= static_cast<int>(model_.bufferViews.size()))
      fail(where + ": buffer view " + std::to_string(accessor.bufferView) + " does not exist");
    const tinygltf::BufferView& view = model_.bufferViews[static_cast<std::size_t>(accessor.bufferView)];
    if (view.buffer < 0 || view.buffer >= static_cast<int>(model_.buffers.size())) fail(where + ": buffer " + std::to_string(view.buffer) + " does not exist");
    const std::vector<unsigned char>& data = model_.buffers[static_cast<std::size_t>(view.buffer)].data;
    const std::uint64_t element_bytes = static_cast<std::uint64_t>(component_bytes) * static_cast<std::uint64_t>(components);
    const std::uint64_t stride = view.byteStride > 0 ? static_cast<std::uint64_t>(view.byteStride) : element_bytes;
    const std::uint64_t count = accessor.count;
    if (count > (std::uint64_t{1} << 32)) fail(where + ": " + std::to_string(count) + " elements is too many");
    if (stride < element_bytes) fail(where + ": its stride is shorter than an element");
    const std::uint64_t view_begin = view.byteOffset, view_length = view.byteLength;
    if (view_begin > data.size() || view_length > data.size() - view_begin) fail(where + ": its buffer view lies outside buffer " + std::to_string(view.buffer));
    const std::uint64_t first = accessor.byteOffset;
    if (count > 0 && (first > view_length || (count - 1) > (view_length - first) / stride || (count - 1) * stride + element_bytes > view_length - first))
      fail(where + ": " + std::to_string(count) + " elements do not fit in its buffer view");
    std::vector<double> out(static_cast<std::size_t>(count) * static_cast<std::size_t>(components));
    const unsigned char* base = data.data() + view_begin + first;
    for (std::uint64_t i = 0; i < count; ++i)
      for (int c = 0; c < components; ++c) {
        const unsigned char* at = base + i * stride + static_cast<std::uint64_t>(c * component_bytes);
        double value = 0.0;
        switch (accessor.componentType) {
          case TINYGLTF_COMPONENT_TYPE_FLOAT: { float f; std::memcpy(&f, at, 4); value = f; break; }
          case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: { std::uint32_t u; std::memcpy(&u, at, 4); value = u; break; }
          case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: { std::uint16_t u; std::memcpy(&u, at, 2); value = u; break; }
          case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: value = *at; break;
          default: fail(where + ": component type " + std::to_string(accessor.componentType) + " is not read here");
        }
        out[static_cast<std::size_t>(i) * static_cast<std::size_t>(components) + static_cast<std::size_t>(c)] = value;
      }
    return out;
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

  void add_mesh(int index, const glm::dmat4& world) {
    if (index >= static_cast<int>(model_.meshes.size())) fail("mesh " + std::to_string(index) + " does not exist");
    const glm::dmat3 normal_matrix = glm::transpose(glm::inverse(glm::dmat3(world)));
    const bool mirrored = glm::determinant(glm::dmat3(world)) < 0.0;
    const tinygltf::Mesh& source = model_.meshes[static_cast<std::size_t>(index)];
    for (std::size_t which = 0; which < source.primitives.size(); ++which) {
      const tinygltf::Primitive& primitive = source.primitives[which];
      if (primitive.mode != TINYGLTF_MODE_TRIANGLES && primitive.mode != -1) continue;  // points and lines: nothing to shade
      const std::string what = "mesh " + std::to_string(index) + " primitive " + std::to_string(which);
      const auto position = primitive.attributes.find("POSITION");
      if (position == primitive.attributes.end()) fail(what + ": no POSITION");
      if (model_.accessors.size() > static_cast<std::size_t>(position->second) && position->second >= 0 &&
          model_.accessors[static_cast<std::size_t>(position->second)].componentType != TINYGLTF_COMPONENT_TYPE_FLOAT)
        fail(what + ": POSITION must be float (quantized positions are not read)");
      const std::vector<double> positions = read_accessor(position->second, 3, what + " POSITION");
      const std::size_t vertex_count = positions.size() / 3;
      std::vector<double> normals;
      if (const auto normal = primitive.attributes.find("NORMAL"); normal != primitive.attributes.end()) {
        if (normal->second >= 0 && normal->second < static_cast<int>(model_.accessors.size()) &&
            model_.accessors[static_cast<std::size_t>(normal->second)].componentType != TINYGLTF_COMPONENT_TYPE_FLOAT)
          fail(what + ": NORMAL must be float (quantized normals are not read)");
        normals = read_accessor(normal->second, 3, what + " NORMAL");
        if (normals.size() != positions.size()) fail(what + ": NORMAL and POSITION differ in count");
      }
      std::vector<std::uint32_t> corners;
      if (primitive.indices >= 0) {
        if (primitive.indices < static_cast<int>(model_.accessors.size()) &&
            model_.accessors[static_cast<std::size_t>(primitive.indices)].componentType == TINYGLTF_COMPONENT_TYPE_FLOAT)
          fail(what + ": indices must be unsigned integers, not floats");
        for (double v : read_accessor(primitive.indices, 1, what + " indices")) {
          if (v >= static_cast<double>(vertex_count)) fail(what + ": index " + std::to_string(static_cast<std::uint64_t>(v)) + " is beyond its " + std::to_string(vertex_count) + " vertices");
          corners.push_back(static_cast<std::uint32_t>(v));
        }
      } else {
        for (std::size_t i = 0; i < vertex_count; ++i) corners.push_back(static_cast<std::uint32_t>(i));
      }
      if (corners.size() % 3 != 0) fail(what + ": " + std::to_string(corners.size()) + " corners is not a whole number of triangles");
      if (geometry_.triangle_count() + corners.size() / 3 > limits_.max_triangles)
        fail("more than " + std::to_string(limits_.max_triangles) + " triangles");
      const glm::vec3 albedo = albedo_of(primitive.material);
      const auto world_position = [&](std::uint32_t i) {
        const glm::dvec3 p = glm::dvec3(world * glm::dvec4(positions[3 * i], positions[3 * i + 1], positions[3 * i + 2], 1.0));
        if (!finite(p) || glm::any(glm::greaterThan(glm::abs(p), glm::dvec3(max_mesh_coordinate))))
          fail(what + ": vertex " + std::to_string(i) + " is not finite or beyond " + std::to_string(max_mesh_coordinate) + " in the world");
        return p;
      };
      // Each triangle gets its own three vertices: flat normals need them, and a vertex of a
      // smooth mesh is simply repeated.
      for (std::size_t t = 0; t + 2 < corners.size(); t += 3) {
        std::uint32_t a = corners[t], b = corners[t + 1], c = corners[t + 2];
        if (mirrored) std::swap(b, c);
        const glm::dvec3 pa = world_position(a), pb = world_position(b), pc = world_position(c);
        const glm::dvec3 face = glm::cross(pb - pa, pc - pa);
        const double face_length = glm::length(face);
        for (const auto& [i, p] : {std::pair{a, pa}, std::pair{b, pb}, std::pair{c, pc}}) {
          glm::dvec3 n = face_length > 0.0 ? face / face_length : glm::dvec3(0, 1, 0);
          if (!normals.empty()) {
            const glm::dvec3 turned = normal_matrix * glm::dvec3(normals[3 * i], normals[3 * i + 1], normals[3 * i + 2]);
            const double length = glm::length(turned);
            if (std::isfinite(length) && length > 1e-12) n = turned / length;
          }
          geometry_.vertices.push_back({glm::vec3(p), glm::vec3(n), albedo});
          geometry_.indices.push_back(static_cast<std::uint32_t>(geometry_.vertices.size() - 1));
        }
      }
    }
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
    if (!finite(power) || glm::any(glm::lessThan(power, glm::dvec3(0.0)))) fail(where + ": intensity x color must be finite and >= 0");
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
  std::vector<bool> visited_;
  mesh geometry_;
  std::optional<camera> camera_;
  std::optional<scene_light> light_;
};

}  // namespace

scene parse_gltf(const std::string& bytes, bool binary, const std::string& name, const fs::path& base_dir, const gltf_limits& limits) {
  if (bytes.size() > std::numeric_limits<unsigned int>::max()) throw error(name + ": larger than 4 GiB");
  file_access access{base_dir, limits.max_file_bytes};
  tinygltf::TinyGLTF loader;
  loader.SetFsCallbacks({&file_exists, &expand_file_path, &read_whole_file, &write_whole_file, &access});
  loader.SetImageLoader(&skip_image, nullptr);
  tinygltf::Model model;
  std::string err, warn;
  const std::string base = base_dir.empty() ? std::string() : base_dir.string();
  const bool loaded = binary ? loader.LoadBinaryFromMemory(&model, &err, &warn, reinterpret_cast<const unsigned char*>(bytes.data()),
                                                           static_cast<unsigned int>(bytes.size()), base)
                             : loader.LoadASCIIFromString(&model, &err, &warn, bytes.data(), static_cast<unsigned int>(bytes.size()), base);
  if (!loaded) {
    while (!err.empty() && (err.back() == '\n' || err.back() == ' ')) err.pop_back();
    throw error(name + ": not a readable glTF 2.0 file (" + (err.empty() ? std::string("no reason given") : err) + ")");
  }
  return reader(model, name, limits).read();
}

scene load_gltf(const fs::path& path, const gltf_limits& limits) {
  const std::string extension = path.extension().string();
  if (extension != ".gltf" && extension != ".glb") throw error(path.string() + ": a glTF file ends in .gltf or .glb");
  const std::string bytes = read_file(path, limits.max_file_bytes, "glTF file");
  fs::path folder = path.parent_path();
  if (folder.empty()) folder = ".";
  return parse_gltf(bytes, extension == ".glb", path.string(), folder, limits);
}

std::string gltf_text(const scene& source) {
  check_scene(source);
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
