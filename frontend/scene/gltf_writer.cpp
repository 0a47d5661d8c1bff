// Writing a scene as glTF 2.0 text (export-scene): one mesh with a primitive per albedo, a
// perspective camera node and a KHR_lights_punctual node per light, the buffer embedded.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <sstream>
#include <string>
#include <vector>

#include <glm/gtc/quaternion.hpp>

#include <tiny_gltf.h>

#include "frontend/core/error.hpp"
#include "frontend/scene/gltf_scene.hpp"

namespace vplkit {

std::string gltf_text(const scene& source) {
  check_scene(source);
  if (!source.geometry.material_ranges.empty())
    throw error("scene " + source.name + ": textured, alpha-tested and emissive materials are not written as glTF (only colour factors are)");
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
  // Every light, in the scene's order, each on its own node after the mesh and camera nodes.
  std::vector<int> roots = {0, 1};
  for (std::size_t k = 0; k < source.lights.size(); ++k) {
    const scene_light& light = source.lights[k];
    tinygltf::Light out_light;
    tinygltf::Node light_node;
    light_node.name = "light " + std::to_string(k);
    if (light.kind == light_kind::spot) {
      const spot_light<float>& spot = light.spot;
      out_light.type = "spot";
      set_power(out_light, spot.intensity);
      out_light.spot.innerConeAngle = std::acos(static_cast<double>(spot.cos_inner));
      out_light.spot.outerConeAngle = std::acos(static_cast<double>(spot.cos_outer));
      pose(light_node, spot.position, spot.direction, glm::vec3(0, 1, 0));
    } else if (light.kind == light_kind::point) {
      out_light.type = "point";
      set_power(out_light, light.point.intensity);
      pose(light_node, light.point.position, glm::vec3(0, 0, -1), glm::vec3(0, 1, 0));
    } else {
      const directional_light<float>& sun = light.directional;
      out_light.type = "directional";
      set_power(out_light, sun.irradiance);
      pose(light_node, glm::vec3(0.0f), sun.direction, glm::vec3(0, 1, 0));
    }
    model.lights.push_back(out_light);
    tinygltf::Value::Object reference;
    reference["light"] = tinygltf::Value(static_cast<int>(k));
    light_node.extensions["KHR_lights_punctual"] = tinygltf::Value(reference);
    roots.push_back(static_cast<int>(model.nodes.size()));
    model.nodes.push_back(light_node);
  }

  tinygltf::Scene out_scene;
  out_scene.name = source.name;
  out_scene.nodes = roots;
  model.scenes.push_back(out_scene);
  model.defaultScene = 0;

  tinygltf::TinyGLTF writer;
  std::ostringstream text;
  if (!writer.WriteGltfSceneToStream(&model, text, true, false)) throw error("scene " + source.name + ": tinygltf could not write it as glTF");
  return text.str();
}

}  // namespace vplkit
