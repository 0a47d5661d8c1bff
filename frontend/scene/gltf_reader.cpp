// The glTF reader: the node tree (depth first, with an explicit stack), the first camera met,
// every light in the order met, and a note per feature the file has and vplkit does not read.
#include "frontend/scene/gltf_reader.hpp"

#include <algorithm>
#include <filesystem>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>

namespace vplkit::gltf_detail {

namespace {

// The extensions the reader reads; any other one the file uses or requires is named in a note.
bool extension_read(const std::string& name) {
  return name == "KHR_lights_punctual" || name == "KHR_texture_transform" || name == "KHR_draco_mesh_compression" ||
         name == "KHR_materials_emissive_strength";
}

}  // namespace

scene reader::read() {
  note_model_features();
  visited_.assign(model_.nodes.size(), false);
  material_of_.assign(model_.materials.size(), unread);
  texcoord_set_of_.assign(model_.materials.size(), -1);
  texture_of_.assign(model_.images.size(), unread);
  walk(roots());
  if (geometry_.indices.empty())
    fail("no triangles in its scene (TRIANGLES, TRIANGLE_STRIP and TRIANGLE_FAN primitives are read; points and lines are not drawn)");
  if (!library_.materials.empty()) geometry_.materials = std::make_shared<const material_library>(std::move(library_));
  std::vector<scene_node> nodes = named_nodes();  // before frame_mesh, which may add a floor after every node's triangles
  framing_needs needs;
  needs.camera = !camera_;
  needs.light = lights_.empty();
  scene framed = frame_mesh(name_stem(), std::move(geometry_), needs);
  if (!lights_.empty()) framed.lights = std::move(lights_);
  if (camera_) framed.view = *camera_;
  framed.name = name_stem();
  framed.nodes = std::move(nodes);
  framed.notes.insert(framed.notes.begin(), notes_.begin(), notes_.end());
  return framed;
}

// One line per feature the file has and vplkit does not read, the first time it is met.
void reader::note(const std::string& feature, const std::string& consequence) {
  if (std::find(noted_.begin(), noted_.end(), feature) != noted_.end()) return;
  noted_.push_back(feature);
  notes_.push_back(name_ + ": " + feature + " not read (" + consequence + ")");
}

void reader::note_model_features() {
  for (const std::string& extension : model_.extensionsRequired)
    if (!extension_read(extension)) note("required extension " + extension, "vplkit does not know it; the scene may look other than its author meant");
  for (const std::string& extension : model_.extensionsUsed)
    if (!extension_read(extension) &&
        std::find(model_.extensionsRequired.begin(), model_.extensionsRequired.end(), extension) == model_.extensionsRequired.end())
      note("extension " + extension, "what it adds is left out");
  if (!model_.animations.empty()) note("animations", "the scene is drawn at rest");
  if (!model_.skins.empty()) note("skins", "skinned meshes are drawn in their bind pose");
  for (const tinygltf::Light& light : model_.lights)
    if (light.range > 0.0) note("light range", "lights fall off with the inverse square of the distance, without a cut-off");
  for (const tinygltf::Camera& source : model_.cameras)
    if (source.type != "perspective") note("orthographic cameras", "the first perspective camera is used, else a framing camera");
  for (const tinygltf::Material& material : model_.materials) {
    if (material.normalTexture.index >= 0) note("normalTexture", "surfaces are shaded with their geometric normals");
    if (material.occlusionTexture.index >= 0) note("occlusionTexture", "the techniques compute their own occlusion");
    // Not a feature left out: emission is drawn (material.hpp), but it lights nothing, and a user
    // who meant a lamp by it should know.
    if (material.emissiveFactor.size() == 3 && (material.emissiveFactor[0] > 0.0 || material.emissiveFactor[1] > 0.0 || material.emissiveFactor[2] > 0.0) &&
        std::find(noted_.begin(), noted_.end(), "emission") == noted_.end()) {
      noted_.push_back("emission");
      notes_.push_back(name_ + ": emissive materials are drawn as seen, but they do not light the scene (only its lights do)");
    }
    if (material.pbrMetallicRoughness.metallicRoughnessTexture.index >= 0)
      note("metallicRoughnessTexture", "surfaces are diffuse: the base colour is their albedo");
    if (material.alphaMode == "BLEND") note("alphaMode BLEND", "blended surfaces are drawn opaque");
    if (material.doubleSided)
      note("doubleSided materials", "every surface is lit on the side its normal faces, the references' included; its back gets no light");
    for (const auto& [extension, value] : material.extensions)
      if (!extension_read(extension)) note("material extension " + extension, "the base colour alone is the albedo");
  }
}

std::vector<int> reader::roots() const {
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

glm::dmat4 reader::local_transform(const tinygltf::Node& node, int index) const {
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

// Depth first, children in their order (the first camera met and the lights' order are the same as
// a recursive walk's), with an explicit stack: a chain of 20,000 nodes is as easy as a flat list.
void reader::walk(const std::vector<int>& roots) {
  struct pending {
    int index;
    glm::dmat4 parent;
    int depth;
  };
  std::vector<pending> stack;
  for (auto root = roots.rbegin(); root != roots.rend(); ++root) stack.push_back({*root, glm::dmat4(1.0), 0});
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
    walked_.push_back({index, next.depth, geometry_.indices.size()});
    if (node.mesh >= 0) add_mesh(node.mesh, world);
    if (node.camera >= 0 && !camera_) read_camera(node.camera, world);
    const auto found = node.extensions.find("KHR_lights_punctual");
    if (found != node.extensions.end() && found->second.Has("light")) read_light(found->second.Get("light").GetNumberAsInt(), world);
    for (auto child = node.children.rbegin(); child != node.children.rend(); ++child) stack.push_back({*child, world, next.depth + 1});
  }
}

std::vector<scene_node> reader::named_nodes() const {
  // One pass with a stack of the open subtrees (a chain of 20,000 nodes stays linear): a node
  // closes every open one at its depth or deeper.
  std::vector<std::size_t> end(walked_.size(), geometry_.indices.size());
  std::vector<std::size_t> open;
  for (std::size_t j = 0; j < walked_.size(); ++j) {
    while (!open.empty() && walked_[open.back()].depth >= walked_[j].depth) {
      end[open.back()] = walked_[j].first_index;
      open.pop_back();
    }
    open.push_back(j);
  }
  std::vector<scene_node> named;
  for (std::size_t i = 0; i < walked_.size(); ++i) {
    const std::string& name = model_.nodes[static_cast<std::size_t>(walked_[i].index)].name;
    if (!name.empty())
      named.push_back({name, static_cast<std::uint32_t>(walked_[i].first_index), static_cast<std::uint32_t>(end[i] - walked_[i].first_index)});
  }
  return named;
}

void reader::read_camera(int index, const glm::dmat4& world) {
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

void reader::read_light(int index, const glm::dmat4& world) {
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
  } else if (source.type == "point") {
    light.kind = light_kind::point;
    light.point.position = glm::vec3(glm::dvec3(world[3]));
    light.point.intensity = glm::vec3(power);
  } else {
    fail(where + ": unknown type '" + source.type.substr(0, 40) + "' (spot, directional or point)");
  }
  lights_.push_back(light);
}

}  // namespace vplkit::gltf_detail
