#include "frontend/obj_loader.hpp"

#include <tiny_obj_loader.h>

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "frontend/error.hpp"

namespace vplkit {
namespace fs = std::filesystem;

namespace {

// Reads the file once to report problems with their line numbers, which tinyobj does not give.
void validate_obj(const fs::path& path) {
  std::ifstream in(path);
  if (!in) throw error(path.string() + ": cannot open the OBJ file");
  std::string line;
  long line_number = 0;
  long positions = 0, texture_coordinates = 0, normals = 0, faces = 0;
  const auto where = [&] { return path.string() + ":" + std::to_string(line_number) + ": "; };
  while (std::getline(in, line)) {
    ++line_number;
    std::istringstream words(line);
    std::string keyword;
    if (!(words >> keyword) || keyword[0] == '#') continue;
    if (keyword == "v" || keyword == "vn" || keyword == "vt") {
      const int needed = keyword == "vt" ? 2 : 3;
      std::string word;
      for (int i = 0; i < needed; ++i) {
        if (!(words >> word)) throw error(where() + "'" + keyword + "' needs " + std::to_string(needed) + " numbers");
        char* end = nullptr;
        errno = 0;
        const double value = std::strtod(word.c_str(), &end);
        if (end == word.c_str() || *end != '\0') throw error(where() + "'" + word + "' is not a number");
        if (!std::isfinite(value) || errno == ERANGE) throw error(where() + "coordinate '" + word + "' is not finite");
      }
      (keyword == "v" ? positions : keyword == "vn" ? normals : texture_coordinates) += 1;
    } else if (keyword == "f") {
      std::string corner;
      int corners = 0;
      while (words >> corner) {
        ++corners;
        // v, v/vt, v//vn or v/vt/vn; each index 1..count, or negative (relative to the end).
        std::istringstream parts(corner);
        std::string part;
        const long counts[3] = {positions, texture_coordinates, normals};
        const char* names[3] = {"vertex", "texture coordinate", "normal"};
        for (int k = 0; k < 3 && std::getline(parts, part, '/'); ++k) {
          if (part.empty()) continue;
          char* end = nullptr;
          const long index = std::strtol(part.c_str(), &end, 10);
          if (end == part.c_str() || *end != '\0') throw error(where() + "face corner '" + corner + "' is not an index");
          const long resolved = index < 0 ? counts[k] + index + 1 : index;
          if (index == 0 || resolved < 1 || resolved > counts[k])
            throw error(where() + "face " + names[k] + " index " + std::to_string(index) + " is out of range (" +
                        std::to_string(counts[k]) + " defined so far)");
        }
      }
      if (corners < 3) throw error(where() + "a face needs at least 3 corners");
      ++faces;
    }
  }
  if (positions == 0 || faces == 0) throw error(path.string() + ": no faces (an OBJ mesh needs 'v' and 'f' lines)");
}

}  // namespace

mesh load_obj(const fs::path& path) {
  validate_obj(path);
  tinyobj::ObjReaderConfig config;
  config.triangulate = true;
  config.mtl_search_path = path.parent_path().string();
  tinyobj::ObjReader reader;
  if (!reader.ParseFromFile(path.string(), config))
    throw error(path.string() + ": " + (reader.Error().empty() ? std::string("tinyobjloader could not parse it") : reader.Error()));
  const tinyobj::attrib_t& attributes = reader.GetAttrib();
  const auto& materials = reader.GetMaterials();
  const auto corner_of = [&](const tinyobj::index_t& index) {
    const auto i = static_cast<std::size_t>(index.vertex_index);
    return glm::vec3(attributes.vertices[3 * i], attributes.vertices[3 * i + 1], attributes.vertices[3 * i + 2]);
  };
  // Where the file has no normals, each corner takes the area-weighted mean of the normals of
  // the faces around its position (smooth shading, as the meshes were scanned or modelled).
  std::vector<glm::vec3> smooth_normals(attributes.vertices.size() / 3, glm::vec3(0.0f));
  for (const tinyobj::shape_t& shape : reader.GetShapes()) {
    const auto& indices = shape.mesh.indices;
    for (std::size_t face = 0; face + 2 < indices.size(); face += 3) {
      glm::vec3 corner[3];
      for (int k = 0; k < 3; ++k) corner[k] = corner_of(indices[face + static_cast<std::size_t>(k)]);
      const glm::vec3 area_weighted = glm::cross(corner[1] - corner[0], corner[2] - corner[0]);
      for (int k = 0; k < 3; ++k)
        smooth_normals[static_cast<std::size_t>(indices[face + static_cast<std::size_t>(k)].vertex_index)] += area_weighted;
    }
  }
  mesh result;
  for (const tinyobj::shape_t& shape : reader.GetShapes()) {
    const auto& indices = shape.mesh.indices;
    for (std::size_t face = 0; face + 2 < indices.size(); face += 3) {
      glm::vec3 corner[3];
      for (int k = 0; k < 3; ++k) corner[k] = corner_of(indices[face + static_cast<std::size_t>(k)]);
      glm::vec3 face_normal = glm::cross(corner[1] - corner[0], corner[2] - corner[0]);
      const float area = glm::length(face_normal);
      if (!(area > 0.0f)) continue;  // degenerate triangle: nothing to shade
      face_normal /= area;
      const int material = shape.mesh.material_ids.empty() ? -1 : shape.mesh.material_ids[face / 3];
      glm::vec3 albedo(0.73f);
      if (material >= 0 && static_cast<std::size_t>(material) < materials.size()) {
        const auto& kd = materials[static_cast<std::size_t>(material)].diffuse;
        albedo = glm::clamp(glm::vec3(kd[0], kd[1], kd[2]), 0.0f, 1.0f);
      }
      for (int k = 0; k < 3; ++k) {
        const int normal_index = indices[face + static_cast<std::size_t>(k)].normal_index;
        const glm::vec3 smooth = smooth_normals[static_cast<std::size_t>(indices[face + static_cast<std::size_t>(k)].vertex_index)];
        // The smooth normal, unless it leans away from the face (a crease folded over itself).
        glm::vec3 normal = glm::length(smooth) > 0.0f && glm::dot(smooth, face_normal) > 0.0f ? glm::normalize(smooth) : face_normal;
        if (normal_index >= 0) {
          const auto n = static_cast<std::size_t>(normal_index);
          const glm::vec3 given(attributes.normals[3 * n], attributes.normals[3 * n + 1], attributes.normals[3 * n + 2]);
          if (glm::length(given) > 0.0f) normal = glm::normalize(given);
        }
        result.indices.push_back(static_cast<std::uint32_t>(result.vertices.size()));
        result.vertices.push_back({corner[k], normal, albedo});
      }
    }
  }
  if (result.indices.empty()) throw error(path.string() + ": no faces with area (every triangle is degenerate)");
  return result;
}

}  // namespace vplkit
