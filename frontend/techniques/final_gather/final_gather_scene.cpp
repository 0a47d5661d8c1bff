#include "frontend/techniques/final_gather/final_gather_scene.hpp"

#include <algorithm>
#include <cstdint>
#include <filesystem>

#include "frontend/core/error.hpp"
#include "frontend/core/setting.hpp"
#include "frontend/scene/obj_loader.hpp"

namespace vplkit {

namespace {

// The triangles of `source` whose first index is inside [first, last) (or outside, with
// `inside` false), their vertices renumbered and their material ranges kept.
mesh select_triangles(const mesh& source, std::size_t first, std::size_t last, bool inside) {
  mesh out;
  out.materials = source.materials;
  std::vector<std::uint32_t> renumbered(source.vertices.size(), UINT32_MAX);
  std::size_t range = 0;
  for (std::size_t i = 0; i + 2 < source.indices.size(); i += 3) {
    if ((i >= first && i < last) != inside) continue;
    while (range < source.material_ranges.size() &&
           i >= std::size_t{source.material_ranges[range].first_index} + source.material_ranges[range].index_count)
      ++range;
    const bool in_range = range < source.material_ranges.size() && i >= source.material_ranges[range].first_index;
    if (in_range) {
      const std::uint32_t material = source.material_ranges[range].material;
      const auto at = static_cast<std::uint32_t>(out.indices.size());
      material_range* last_range = out.material_ranges.empty() ? nullptr : &out.material_ranges.back();
      if (last_range && last_range->material == material && last_range->first_index + last_range->index_count == at) last_range->index_count += 3;
      else out.material_ranges.push_back({at, 3, material});
    }
    for (std::size_t k = 0; k < 3; ++k) {
      std::uint32_t& index = renumbered[source.indices[i + k]];
      if (index == UINT32_MAX) {
        index = static_cast<std::uint32_t>(out.vertices.size());
        out.vertices.push_back(source.vertices[source.indices[i + k]]);
      }
      out.indices.push_back(index);
    }
  }
  if (out.material_ranges.empty()) out.materials = nullptr;
  return out;
}

std::string point_text(glm::vec3 p) { return "(" + format_real(p.x) + ", " + format_real(p.y) + ", " + format_real(p.z) + ")"; }

// The object's mesh in its own units: the sphere (2304 triangles, the paper's ~2300, 2 across) or
// an OBJ file, albedo 0.8.
mesh object_shape(const std::string& object) {
  mesh shape;
  if (object == "sphere") {
    add_sphere(shape, glm::vec3(0.0f), 1.0f, 24, 48, glm::vec3(0.8f));
  } else {
    shape = load_obj(object);
    for (vertex& v : shape.vertices) v.albedo = glm::vec3(0.8f);
  }
  return shape;
}

// The object `shape` scaled by `scale` about its bounding box's centre, which lands at `centre`.
void place_object(final_gather_scene& s, mesh shape, float scale, glm::vec3 centre) {
  const bounding_box box_of_shape = bounds(shape);
  for (vertex& v : shape.vertices) v.position = (v.position - box_of_shape.centre()) * scale;
  for (const vertex& v : shape.vertices) s.object_radius = std::max(s.object_radius, glm::length(v.position));
  s.local_object = std::move(shape);
  s.object = s.local_object;
  for (std::size_t i = 0; i < s.object.vertices.size(); ++i) s.object.vertices[i].position = s.local_object.vertices[i].position + centre;
  s.reference_point = centre;
}

// The node's triangles out of the environment (into s.object's shape, returned) and the rest
// into s.room; an unknown name is refused with the names there are.
mesh take_node(final_gather_scene& s, const scene& environment, const std::string& node, const std::string& where) {
  const auto found = std::find_if(environment.nodes.begin(), environment.nodes.end(), [&](const scene_node& n) { return n.name == node; });
  if (found == environment.nodes.end()) {
    if (environment.nodes.empty())
      throw error(where + ": --object-node '" + excerpt(node, 60) + "': the scene has no named nodes (--object-node names a node of a glTF scene)");
    std::string names;
    const std::size_t shown = std::min<std::size_t>(environment.nodes.size(), 40);
    for (std::size_t i = 0; i < shown; ++i) names += (i ? ", '" : "'") + excerpt(environment.nodes[i].name, 60) + "'";
    if (shown < environment.nodes.size()) names += " and " + std::to_string(environment.nodes.size() - shown) + " more";
    throw error(where + ": no node named '" + excerpt(node, 60) + "' (--object-node); its named nodes: " + names);
  }
  if (found->index_count == 0) throw error(where + ": node '" + excerpt(node, 60) + "' (--object-node) has no triangles, nor have its children");
  const std::size_t first = found->first_index, last = first + found->index_count;
  s.room = select_triangles(environment.geometry, first, last, false);
  if (s.room.indices.empty()) throw error(where + ": node '" + excerpt(node, 60) + "' (--object-node) holds every triangle: nothing is left around the object");
  return select_triangles(environment.geometry, first, last, true);
}

}  // namespace

scene final_gather_box() {
  scene room = make_cornell_box();  // its camera and light
  room.name = "final-gather-box";
  room.geometry = mesh();
  add_cornell_room(room.geometry);
  // Closed at the front (the paper's box room): the cube map must see a surface everywhere. The
  // camera looks in through it: the G-buffer pass culls the room's back faces.
  add_quad(room.geometry, {1, 0, 1}, {-1, 0, 1}, {-1, 2, 1}, {1, 2, 1}, {0, 0, -1}, glm::vec3(0.73f));
  return room;
}

final_gather_scene make_final_gather_scene(const std::string& object, glm::vec3 position, float size) {
  return make_final_gather_scene(final_gather_box(), object, position, size);
}

final_gather_scene make_final_gather_scene(const scene& environment, const std::string& object, glm::vec3 position, float size) {
  final_gather_setup setup;
  setup.object = object;
  setup.object_position = position;
  setup.object_size = size;
  return make_final_gather_scene(&environment, setup);
}

final_gather_scene make_final_gather_scene(const scene* given, const final_gather_setup& setup) {
  if (!given && !setup.object_node.empty())
    throw error("--object-node '" + excerpt(setup.object_node, 60) + "' names a node of the scene: give the glTF scene with --scene");
  const scene box = given ? scene() : final_gather_box();
  const scene& environment = given ? *given : box;
  const std::string where = "final gathering in scene " + environment.name;
  check_lights(environment.lights, where);
  if (environment.geometry.indices.empty()) throw error(where + ": the scene has no triangles around the object");
  if (!(setup.object_size > 0.0f)) throw error("the object's size must be > 0");
  final_gather_scene s;
  s.view = environment.view;
  s.lights = environment.lights;
  s.object_source = object_key(setup);
  s.object_size = setup.object_size;
  mesh shape;
  if (!setup.object_node.empty()) {
    shape = take_node(s, environment, setup.object_node, where);
    s.name = setup.object_node;
  } else {
    s.room = environment.geometry;
    shape = object_shape(setup.object);
    s.name = setup.object == "sphere" ? "sphere" : std::filesystem::path(setup.object).stem().string();
  }
  const bounding_box own = bounds(shape);
  const glm::vec3 extent = own.maximum - own.minimum;
  if (!setup.object_at.empty()) {
    object_placement placement;
    if (const std::string problem = parse_object_at(setup.object_at, placement); !problem.empty()) throw error("--object-at " + problem);
    // The bottom centre of the bounding box at the point: an object stands where it is put.
    const glm::vec3 centre = placement.bottom_centre + glm::vec3(0.0f, 0.5f * extent.y * placement.scale, 0.0f);
    const bounding_box room = bounds(s.room);
    const glm::vec3 low = centre - 0.5f * extent * placement.scale, high = centre + 0.5f * extent * placement.scale;
    if (glm::any(glm::lessThan(low, room.minimum)) || glm::any(glm::greaterThan(high, room.maximum)))
      throw error(where + ": --object-at " + excerpt(setup.object_at, 60) + " puts the object's box " + point_text(low) + " to " + point_text(high) +
                  " outside the scene's bounds " + point_text(room.minimum) + " to " + point_text(room.maximum));
    place_object(s, std::move(shape), placement.scale, centre);
  } else if (!setup.object_node.empty()) {
    place_object(s, std::move(shape), 1.0f, own.centre());  // where the scene has it
  } else {
    // --object-size across, centred at --object-position.
    place_object(s, std::move(shape), setup.object_size / std::max({extent.x, extent.y, extent.z, 1e-9f}), setup.object_position);
  }
  return s;
}

}  // namespace vplkit
