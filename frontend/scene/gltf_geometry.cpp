// The glTF reader's geometry: accessors checked before they are read, Draco primitives decoded
// once, and each primitive's triangles (lists, strips, fans) in world space.
#include "frontend/scene/gltf_reader.hpp"

#include <algorithm>
#include <array>
#include <utility>

namespace vplkit::gltf_detail {

namespace {

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

}  // namespace

// The accessor's elements, `components` per element, after checking every byte it reads.
accessor_view reader::view_accessor(int index, int components, const std::string& what) const {
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
accessor_view reader::attribute_view(const tinygltf::Primitive& primitive, const draco_mesh* compressed, const std::string& name, int components,
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
const draco_mesh* reader::draco_of(int mesh, std::size_t which, const std::string& what) {
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

reader::texcoord_view reader::texture_coordinates(const tinygltf::Primitive& primitive, const draco_mesh* compressed, int set, std::size_t vertex_count,
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
glm::vec2 reader::texture_coordinate(const texcoord_view& texcoords, std::uint32_t i) const {
  if (texcoords.empty()) return glm::vec2(0.0f);
  const glm::dvec2 uv(texcoords.values.get(i, 0) * texcoords.scale, texcoords.values.get(i, 1) * texcoords.scale);
  if (!std::isfinite(uv.x) || !std::isfinite(uv.y) || std::fabs(uv.x) > 1e6 || std::fabs(uv.y) > 1e6)
    fail(texcoords.where + ": a coordinate is not finite or beyond 1e6");
  return glm::vec2(uv);
}

void reader::add_mesh(int index, const glm::dmat4& world) {
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
    geometry_.indices.reserve(geometry_.indices.size() + 3 * triangle_count + framing_floor_indices);  // room for frame_mesh's floor
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

}  // namespace vplkit::gltf_detail
