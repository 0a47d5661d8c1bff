#include "frontend/techniques/final_gather/final_gather_scene.hpp"

#include <algorithm>
#include <filesystem>

#include "frontend/core/error.hpp"
#include "frontend/scene/obj_loader.hpp"

namespace vplkit {

namespace {

// The object ("sphere" or an .obj file) scaled to `size` across and centred at `position`.
void place_object(final_gather_scene& s, const std::string& object, glm::vec3 position, float size) {
  if (!(size > 0.0f)) throw error("the object's size must be > 0");
  s.object_source = object;
  s.object_size = size;
  mesh shape;
  if (object == "sphere") {
    add_sphere(shape, glm::vec3(0.0f), 1.0f, 24, 48, glm::vec3(0.8f));  // 2304 triangles, the paper's ~2300
    s.name = "sphere";
  } else {
    shape = load_obj(object);
    for (vertex& v : shape.vertices) v.albedo = glm::vec3(0.8f);
    s.name = std::filesystem::path(object).stem().string();
  }
  const bounding_box box_of_shape = bounds(shape);
  const float scale = size / std::max({box_of_shape.maximum.x - box_of_shape.minimum.x, box_of_shape.maximum.y - box_of_shape.minimum.y,
                                        box_of_shape.maximum.z - box_of_shape.minimum.z, 1e-9f});
  for (vertex& v : shape.vertices) v.position = (v.position - box_of_shape.centre()) * scale;
  for (const vertex& v : shape.vertices) s.object_radius = std::max(s.object_radius, glm::length(v.position));
  s.local_object = std::move(shape);
  s.object = s.local_object;
  for (std::size_t i = 0; i < s.object.vertices.size(); ++i) s.object.vertices[i].position = s.local_object.vertices[i].position + position;
  s.reference_point = position;
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
  const std::string where = "final gathering in scene " + environment.name;
  const scene_light& light = single_light(environment, "final gathering");
  if (light.kind != light_kind::spot)
    throw error(where + ": its light is " + light_kind_name(light.kind) + "; the cube map's faces and the shading are lit by a spot light (give the scene a spot)");
  if (environment.geometry.indices.empty()) throw error(where + ": the scene has no triangles around the object");
  final_gather_scene s;
  s.room = environment.geometry;
  s.view = environment.view;
  s.light = light.spot;
  place_object(s, object, position, size);
  return s;
}

}  // namespace vplkit
