#include "frontend/scene/draco.hpp"

#include <cmath>
#include <new>

#include <draco/compression/decode.h>
#include <draco/core/decoder_buffer.h>
#include <nlohmann/json.hpp>

#include "frontend/core/error.hpp"

namespace vplkit {

draco_mesh decode_draco_mesh(const unsigned char* bytes, std::size_t size, const std::map<std::string, int>& attribute_ids,
                             std::size_t max_triangles, const std::string& where) {
  draco::DecoderBuffer buffer;
  buffer.Init(reinterpret_cast<const char*>(bytes), size);
  const auto type = draco::Decoder::GetEncodedGeometryType(&buffer);
  if (!type.ok()) throw error(where + ": not Draco data (" + type.status().error_msg_string() + ")");
  if (type.value() != draco::TRIANGULAR_MESH) throw error(where + ": the Draco data is a point cloud, not a triangle mesh");
  draco::Decoder decoder;
  std::unique_ptr<draco::Mesh> decoded;
  try {
    auto result = decoder.DecodeMeshFromBuffer(&buffer);
    if (!result.ok()) throw error(where + ": libdraco could not decode it (" + result.status().error_msg_string() + ")");
    decoded = std::move(result).value();
  } catch (const std::bad_alloc&) {
    throw error(where + ": libdraco ran out of memory decoding it (the counts it encodes are too large)");
  }
  if (decoded->num_faces() > max_triangles)
    throw error(where + ": " + std::to_string(decoded->num_faces()) + " triangles, more than the " + std::to_string(max_triangles) + " vplkit loads");
  draco_mesh out;
  out.points = decoded->num_points();
  out.indices.reserve(static_cast<std::size_t>(decoded->num_faces()) * 3);
  for (draco::FaceIndex f(0); f < decoded->num_faces(); ++f)
    for (const draco::PointIndex& point : decoded->face(f)) {
      if (point.value() >= out.points) throw error(where + ": a Draco face names point " + std::to_string(point.value()) + " of " + std::to_string(out.points));
      out.indices.push_back(point.value());
    }
  for (const auto& [name, id] : attribute_ids) {
    const draco::PointAttribute* source = id >= 0 ? decoded->GetAttributeByUniqueId(static_cast<std::uint32_t>(id)) : nullptr;
    if (!source) throw error(where + ": attribute " + name + " names Draco attribute " + std::to_string(id) + ", which the data does not have");
    const int components = source->num_components();
    if (components < 1 || components > 4) throw error(where + ": Draco attribute " + std::to_string(id) + " has " + std::to_string(components) + " components");
    draco_mesh::attribute& target = out.attributes[name];
    target.components = components;
    target.values.resize(out.points * static_cast<std::size_t>(components));
    for (std::size_t p = 0; p < out.points; ++p) {
      float* value = target.values.data() + p * static_cast<std::size_t>(components);
      if (!source->ConvertValue<float>(source->mapped_index(draco::PointIndex(static_cast<std::uint32_t>(p))), static_cast<std::int8_t>(components), value))
        throw error(where + ": Draco attribute " + std::to_string(id) + " (" + name + ") could not be read as numbers");
    }
  }
  return out;
}

std::string without_draco_indices(std::string_view json) {
  if (json.find("KHR_draco_mesh_compression") == std::string_view::npos) return {};
  // The JSON's depth was checked before (gltf_scene.cpp): nlohmann's parser recurses per level.
  nlohmann::json document = nlohmann::json::parse(json.begin(), json.end(), nullptr, false);
  if (document.is_discarded() || !document.is_object()) return {};
  bool changed = false;
  const auto meshes = document.find("meshes");
  if (meshes == document.end() || !meshes->is_array()) return {};
  for (nlohmann::json& mesh : *meshes) {
    if (!mesh.is_object() || !mesh.contains("primitives") || !mesh["primitives"].is_array()) continue;
    for (nlohmann::json& primitive : mesh["primitives"]) {
      if (!primitive.is_object() || !primitive.contains("extensions") || !primitive["extensions"].is_object()) continue;
      if (!primitive["extensions"].contains("KHR_draco_mesh_compression")) continue;
      changed = primitive.erase("indices") > 0 || changed;
    }
  }
  return changed ? document.dump() : std::string();
}

std::string declared_gltf_version(std::string_view json) {
  const nlohmann::json document = nlohmann::json::parse(json.begin(), json.end(), nullptr, false);
  if (document.is_discarded() || !document.is_object()) return {};
  const auto asset = document.find("asset");
  if (asset == document.end() || !asset->is_object()) return {};
  const auto version = asset->find("version");
  if (version == asset->end()) return {};
  if (version->is_string()) return version->get<std::string>();
  if (version->is_number()) return version->dump();
  return {};
}

}  // namespace vplkit
